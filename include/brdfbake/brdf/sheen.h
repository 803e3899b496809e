/* The "Charlie" microfacet sheen of
 *   [EK17] Estevez, Kulla, "Production Friendly Microfacet Sheen BRDF", SIGGRAPH 2017 course
 *          "Physically Based Shading in Theory and Practice" (Sony Pictures Imageworks),
 * the sheen lobe of glTF's KHR_materials_sheen, Filament's cloth and OpenPBR's fuzz:
 *
 *   f = D(h) V(wo, wi),  D = (2 + 1/alpha) sin^(1/alpha)(theta_h) / (2 pi)   [EK17 eq. 2]
 *
 * with alpha = sheenRoughness^2 (the glTF sample viewer's and Filament's convention), in (0, 1].
 * D is normalised as a microfacet distribution (integral of D cos(theta_h) over the hemisphere
 * is 1); it puts its fibres' normals towards the horizon, so that the lobe lights grazing
 * directions. Two visibility terms V = G / (4 cos_o cos_i), chosen by a slot:
 *
 *   charlie    the height-correlated Smith form with [EK17]'s fitted Lambda (sec. 3, "Shadowing
 *              term", and the KHR_materials_sheen specification, "Sheen visibility"):
 *                V = 1 / ((1 + Lambda(cos_o) + Lambda(cos_i)) 4 cos_o cos_i),
 *                Lambda(mu) = exp(L(mu))                     for mu < 1/2,
 *                           = exp(2 L(1/2) - L(1 - mu))     otherwise,
 *                L(x) = a / (1 + b x^c) + d x + e, the coefficients interpolated between their
 *                fits at alpha = 0 and alpha = 1 with weight t = (1 - alpha)^2:
 *                  (a, b, c, d, e) = (1 - t) (21.5473, 3.82987, 0.19823, -1.97760, -4.32054)
 *                                   +     t  (25.3245, 3.32435, 0.16801, -1.27393, -4.85967).
 *              [EK17]'s further "terminator softening" Lambda^(1 + 2 (1 - mu)^8) is a shading
 *              trick for the shadow terminator of a lit sphere, not part of the BRDF: left out,
 *              as glTF leaves it out.
 *   ashikhmin  the visibility of Neubelt and Pettineo, "Crafting a Next-Gen Material Pipeline
 *              for The Order: 1886", SIGGRAPH 2013 course notes (after Ashikhmin and Premoze,
 *              "Distribution-based BRDFs", 2007):
 *                V = 1 / (4 (cos_i + cos_o - cos_i cos_o)),
 *              which is not a shadowing function of D: its lobe gains energy at grazing angles
 *              (albedo above 1; `brdfbake check` reports where and how much).
 *
 * Both are symmetric in wo and wi (reciprocal). Edge cases (the policy of microfacet.h): 0 at or
 * below either horizon; sin^2(theta_h) is computed from the tangential part of wo + wi, without
 * the cancellation of 1 - cos^2; sin^(1/alpha) is pow(sin^2, 1/(2 alpha)), 0 where it underflows,
 * finite for alpha down to BB_ALPHA_MIN; Lambda is at most exp(a + e) < 1e9 (mu = 0), so the
 * charlie V stays finite for every cos_o, cos_i > 0 in float.
 *
 * Sampling: the lobe has no shape that one warp could follow at every roughness (it peaks on the
 * horizon of wi at azimuth phi_o for small alpha and grazing wo, and has a cone of exponent
 * 1/alpha at the mirror direction), so the sampler is model-agnostic, like the uniform sampling
 * of the half vector with which Filament builds its cloth table (libs/ibl/src/CubemapIBL.cpp,
 * DFV_Charlie_Uniform): phi_i = 2 pi u2 and cos(theta_i) = u1^2 (3 - 2 u1), the smoothstep of
 * u1, with density 1/(2 pi 6 u1 (1 - u1)) and weight 12 pi u1 (1 - u1) cos(theta_i) f. Unlike
 * cos(theta_i) = u1 (uniform on the hemisphere), the smoothstep flattens both ends of the
 * cos(theta_i) range: the horizon of wi, where D peaks and the fitted Lambda has its x^c
 * (c ~ 0.2) behaviour, and the normal, where the cone sits for wo = n. The sampler-space
 * quadrature (integrands.h) integrates that weight on the unit square, and converges there
 * about geometrically: at n = 64 nodes per axis its error is below 2e-8 over sheenRoughness
 * 0.05-1 and mu 1e-3-1 for both visibilities, where cos(theta_i) = u1 leaves up to 2e-4
 * (grazing wo, small roughness) and 2e-7 (wo = n, sheenRoughness 1). sin(theta_i) is taken
 * from 1 - cos(theta_i) = (1 - u1)^2 (1 + 2 u1), exact in float near the normal.
 */
#ifndef BRDFBAKE_BRDF_SHEEN_H
#define BRDFBAKE_BRDF_SHEEN_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Parameter slots. */
#define BB_SHEEN_ALPHA 0      /* alpha = sheenRoughness^2, in [BB_ALPHA_MIN, 1] */
#define BB_SHEEN_VISIBILITY 1 /* BB_SHEEN_V_CHARLIE or BB_SHEEN_V_ASHIKHMIN */

#define BB_SHEEN_V_CHARLIE 0
#define BB_SHEEN_V_ASHIKHMIN 1

/* The Charlie distribution [EK17 eq. 2] from sin^2(theta_h). */
BB_FN bb_real bb_sheen_d(bb_real alpha, bb_real sin2_h) {
    bb_real inv = BB_R(1.0) / alpha;
    return (BB_R(2.0) + inv) * (BB_R(0.5) * BB_INV_PI) * bb_pow(sin2_h, BB_R(0.5) * inv);
}

/* [EK17]'s fit L(x) of log Lambda, its coefficients interpolated in t = (1 - alpha)^2. */
BB_FN bb_real bb_sheen_l(bb_real x, bb_real alpha) {
    bb_real t = bb_sqr(BB_R(1.0) - alpha);
    bb_real a = BB_R(21.5473) + t * (BB_R(25.3245) - BB_R(21.5473));
    bb_real b = BB_R(3.82987) + t * (BB_R(3.32435) - BB_R(3.82987));
    bb_real c = BB_R(0.19823) + t * (BB_R(0.16801) - BB_R(0.19823));
    bb_real d = BB_R(-1.97760) + t * (BB_R(-1.27393) - BB_R(-1.97760));
    bb_real e = BB_R(-4.32054) + t * (BB_R(-4.85967) - BB_R(-4.32054));
    return a / (BB_R(1.0) + b * bb_pow(x, c)) + d * x + e;
}

/* [EK17]'s Lambda(mu) for mu in [0, 1], branch-free (both halves computed, one selected). */
BB_FN bb_real bb_sheen_lambda(bb_real mu, bb_real alpha) {
    bb_real lo = bb_sheen_l(mu, alpha);
    bb_real hi = BB_R(2.0) * bb_sheen_l(BB_R(0.5), alpha) - bb_sheen_l(BB_R(1.0) - mu, alpha);
    return bb_exp(bb_select(hi, lo, mu < BB_R(0.5)));
}

/* The visibility V = G / (4 cos_o cos_i) of the slot's kind, for cos_o, cos_i > 0. */
BB_FN bb_real bb_sheen_visibility(bb_real visibility, bb_real alpha, bb_real co, bb_real ci) {
    bb_real charlie = BB_R(1.0) / ((BB_R(1.0) + bb_sheen_lambda(co, alpha) + bb_sheen_lambda(ci, alpha)) *
                                (BB_R(4.0) * co * ci));
    bb_real ashikhmin = BB_R(1.0) / (BB_R(4.0) * (co + ci - co * ci));
    return bb_select(charlie, ashikhmin, visibility == BB_R(BB_SHEEN_V_ASHIKHMIN));
}

BB_FN bb_real bb_sheen_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_mask above = wo.z > BB_R(0.0) && wi.z > BB_R(0.0);
    bb_real co = bb_select(BB_R(1.0), wo.z, above), ci = bb_select(BB_R(1.0), wi.z, above);
    /* sin^2(theta_h) of h = (wo + wi)/|wo + wi|: the tangential part over the whole */
    bb_real sx = wo.x + wi.x, sy = wo.y + wi.y, sz = co + ci;
    bb_real t2 = sx * sx + sy * sy;
    bb_real sin2_h = t2 / (t2 + sz * sz);
    bb_real alpha = p.v[BB_SHEEN_ALPHA];
    bb_real f = bb_sheen_d(alpha, sin2_h) * bb_sheen_visibility(p.v[BB_SHEEN_VISIBILITY], alpha, co, ci);
    return bb_select(BB_R(0.0), f, above);
}

/* cos(theta_i) = u1^2 (3 - 2 u1), phi_i = 2 pi u2 (the head of this file): weight
 * 12 pi u1 (1 - u1) cos(theta_i) f. */
BB_FN bb_sample bb_sheen_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_real v = BB_R(1.0) - u1;
    bb_real ci = u1 * u1 * (BB_R(3.0) - BB_R(2.0) * u1);
    bb_real one_minus = v * v * (BB_R(1.0) + BB_R(2.0) * u1); /* 1 - cos(theta_i) */
    bb_real s = bb_safe_sqrt(one_minus * (BB_R(1.0) + ci));
    bb_real phi = BB_2PI * u2;
    bb_vec3 wi = bb_v3(s * bb_cos(phi), s * bb_sin(phi), ci);
    return bb_make_sample(wi, BB_R(6.0) * BB_2PI * u1 * v * ci * bb_sheen_eval(p, wo, wi));
}

#endif /* BRDFBAKE_BRDF_SHEEN_H */

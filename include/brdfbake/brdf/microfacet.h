/* Microfacet distributions and Smith masking-shadowing, shared by host and kernels.
 *
 * Trowbridge-Reitz (GGX) distribution, anisotropic with roughness alpha_x, alpha_y along the
 * local x and y axes; the isotropic model is alpha_x = alpha_y.
 * References:
 *   [WMLT07] Walter, Marschner, Li, Torrance, "Microfacet Models for Refraction through Rough
 *            Surfaces", EGSR 2007 (eq. 33: D, eq. 34: G1).
 *   [H14]    Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
 *            JCGT 3(2), 2014 (eq. 72 and 86: anisotropic Lambda; eq. 98/99: separable and
 *            height-correlated G2).
 *   [H18]    Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018.
 *
 * Edge-case policy (written once, here): D = 0 for back-facing microfacets (m.z <= 0);
 * G1 = 0 for directions at or below the horizon, G1 = 1 exactly at normal incidence; every
 * function is finite for alpha >= BB_ALPHA_MIN (the host rejects smaller alpha). */
#ifndef BRDFBAKE_BRDF_MICROFACET_H
#define BRDFBAKE_BRDF_MICROFACET_H

#include "brdfbake/brdf/params.h"

/* Below this alpha a float kernel cannot resolve the lobe (D ~ 1/(pi alpha^2) overflows the
 * sample weights' useful range); the host refuses smaller values. */
#define BB_ALPHA_MIN BB_R(1e-4)

/* GGX D(m) [WMLT07 eq. 33] written without tan(): for a unit m with m.z > 0,
 * D = 1 / (pi ax ay ((mx/ax)^2 + (my/ay)^2 + mz^2)^2). Returns 0 for m.z <= 0. */
BB_FN real bb_ggx_d(bb_vec3 m, real ax, real ay) {
    real x = m.x / ax, y = m.y / ay;
    real q = x * x + y * y + m.z * m.z;
    real d = BB_R(1.0) / (BB_PI * ax * ay * q * q);
    return bb_select(BB_R(0.0), d, m.z > BB_R(0.0));
}

/* Smith Lambda for GGX [H14 eq. 86], anisotropic through the projected roughness [H14 eq. 80]:
 * with r2 = (wx ax)^2 + (wy ay)^2 and z = w.z, alpha^2 tan^2 = r2 / z^2 and
 * Lambda = (sqrt(1 + r2/z^2) - 1)/2 = r2 / (2 z (sqrt(z^2 + r2) + z)),
 * the last form free of cancellation at small roughness. Infinite at the horizon. */
BB_FN real bb_ggx_lambda(bb_vec3 w, real ax, real ay) {
    real z = bb_fabs(w.z);
    real r2 = bb_sqr(w.x * ax) + bb_sqr(w.y * ay);
    real den = BB_R(2.0) * z * (bb_sqrt(z * z + r2) + z);
    return r2 / den;
}

/* Smith G1 = 1 / (1 + Lambda) [H14 eq. 43], in the closed form
 * G1 = 2z(s + z) / (2z(s + z) + r2), s = sqrt(z^2 + r2): finite everywhere, exactly 1 at
 * normal incidence and 0 at the horizon. Returns 0 for w.z <= 0. */
BB_FN real bb_ggx_g1(bb_vec3 w, real ax, real ay) {
    real z = bb_max(w.z, BB_R(0.0));
    real r2 = bb_sqr(w.x * ax) + bb_sqr(w.y * ay);
    real a = BB_R(2.0) * z * (bb_sqrt(z * z + r2) + z);
    real g = a / (a + r2);
    return bb_select(BB_R(0.0), g, w.z > BB_R(0.0));
}

/* Separable masking-shadowing G2 = G1(wo) G1(wi) [H14 eq. 98]. */
BB_FN real bb_ggx_g2_separable(bb_vec3 wo, bb_vec3 wi, real ax, real ay) {
    return bb_ggx_g1(wo, ax, ay) * bb_ggx_g1(wi, ax, ay);
}

/* Height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) [H14 eq. 99],
 * written as 1/(1/G1o + 1/G1i - 1) so that it reaches 0, not NaN, at the horizon. */
BB_FN real bb_ggx_g2_correlated(bb_vec3 wo, bb_vec3 wi, real ax, real ay) {
    real g1o = bb_ggx_g1(wo, ax, ay), g1i = bb_ggx_g1(wi, ax, ay);
    real p = g1o * g1i;
    real den = g1o + g1i - p;
    real g = p / bb_select(den, BB_R(1.0), den <= BB_R(0.0));
    return bb_select(BB_R(0.0), g, p > BB_R(0.0));
}

/* Sample a visible normal of GGX seen from wo (wo.z > 0) [H18, listing 1].
 * u1, u2 in [0, 1). The density of the result is D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z. */
BB_FN bb_vec3 bb_ggx_sample_vndf(bb_vec3 wo, real ax, real ay, real u1, real u2) {
    /* Section 3.2: stretch the view vector to the hemisphere configuration. */
    bb_vec3 vh = bb_normalize(bb_v3(ax * wo.x, ay * wo.y, wo.z));
    /* Section 4.1: orthonormal basis (with the special case at normal incidence). */
    real lensq = vh.x * vh.x + vh.y * vh.y;
    real inv_len = BB_R(1.0) / bb_sqrt(bb_select(BB_R(1.0), lensq, lensq > BB_R(0.0)));
    bb_vec3 t1 = bb_v3(bb_select(BB_R(1.0), -vh.y * inv_len, lensq > BB_R(0.0)),
                       bb_select(BB_R(0.0), vh.x * inv_len, lensq > BB_R(0.0)), BB_R(0.0));
    bb_vec3 t2 = bb_cross(vh, t1);
    /* Section 4.2: parameterisation of the projected area. */
    real r = bb_sqrt(u1);
    real phi = BB_2PI * u2;
    real p1 = r * bb_cos(phi);
    real p2 = r * bb_sin(phi);
    real s = BB_R(0.5) * (BB_R(1.0) + vh.z);
    p2 = (BB_R(1.0) - s) * bb_safe_sqrt(BB_R(1.0) - p1 * p1) + s * p2;
    /* Section 4.3: reprojection onto the hemisphere. */
    real p3 = bb_safe_sqrt(BB_R(1.0) - p1 * p1 - p2 * p2);
    bb_vec3 nh = bb_add(bb_add(bb_scale(t1, p1), bb_scale(t2, p2)), bb_scale(vh, p3));
    /* Section 3.4: unstretch back to the ellipsoid configuration. */
    return bb_normalize(bb_v3(ax * nh.x, ay * nh.y, bb_max(BB_R(0.0), nh.z)));
}

#endif /* BRDFBAKE_BRDF_MICROFACET_H */

/* The Torrance-Sparrow BRDF with the V-groove masking-shadowing term (`torrance-sparrow`):
 *   f = D(wh) G(wo, wi) F(wo.wh) / (4 cos_o cos_i),
 *   G = min(1, 2 (n.h)(n.o)/(o.h), 2 (n.h)(n.i)/(o.h))
 *   [TS67] Torrance, Sparrow, "Theory for Off-Specular Reflection from Roughened Surfaces",
 *          JOSA 57(9), 1967 (the V-groove geometry, their eq. for G);
 *   [CT82] Cook, Torrance, "A Reflectance Model for Computer Graphics", ACM TOG 1(1), 1982
 *          (G in the form above, eq. 7 there, and the 4 cos_o cos_i denominator used here).
 * D is chosen by a parameter: normalised Blinn (exponent N), Beckmann or GGX (alpha, or
 * alpha_x/alpha_y), from microfacet.h. o.h = i.h, so f is reciprocal.
 *
 * Written without 0/0: G/(cos_o cos_i) = min(1/(cos_o cos_i), 2 (n.h)/((o.h) max(cos_o, cos_i))),
 * because the smaller of the two V-groove terms is the one with the larger cosine.
 *
 * Sampling: wh with density D(wh) cos(theta_h) (the distribution's own sampler), wi = reflect(wo, wh),
 * pdf(wi) = D cos(theta_h) / (4 wo.wh) [WMLT07 eq. 14 and 38]; the weight is
 *   f cos_i / pdf = F G (o.h) / (cos_o cos_h) = F min((o.h)/(cos_o cos_h), 2, 2 cos_i/cos_o) <= 2 F,
 * bounded for every wo (visible-normal sampling of the Smith distributions would not be: the
 * V-groove G is not the Smith G1 that their density contains). */
#ifndef BRDFBAKE_BRDF_TORRANCE_SPARROW_H
#define BRDFBAKE_BRDF_TORRANCE_SPARROW_H

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/quad_dist.h"

/* Parameter slots. */
#define BB_TORRANCE_SPARROW_DIST 0 /* one of BB_TS_D_* */
#define BB_TORRANCE_SPARROW_N 1    /* Blinn exponent (d=blinn) */
#define BB_TORRANCE_SPARROW_ALPHA_X 2
#define BB_TORRANCE_SPARROW_ALPHA_Y 3

#define BB_TS_D_BLINN 0
#define BB_TS_D_BECKMANN 1
#define BB_TS_D_GGX 2

BB_FN bb_real bb_torrance_sparrow_d(bb_params p, bb_vec3 m) {
    bb_real ax = p.v[BB_TORRANCE_SPARROW_ALPHA_X], ay = p.v[BB_TORRANCE_SPARROW_ALPHA_Y];
    /* The distribution is the same for every work-item: a uniform branch. */
    switch ((int)bb_first(p.v[BB_TORRANCE_SPARROW_DIST])) {
    case BB_TS_D_BECKMANN:
        return bb_beckmann_d(m, ax, ay);
    case BB_TS_D_GGX:
        return bb_ggx_d(m, ax, ay);
    default:
        return bb_blinn_d(m, p.v[BB_TORRANCE_SPARROW_N]);
    }
}

/* A microfacet normal with density D(m) cos(theta_m). */
BB_FN bb_vec3 bb_torrance_sparrow_sample_dcos(bb_params p, bb_real u1, bb_real u2) {
    bb_real ax = p.v[BB_TORRANCE_SPARROW_ALPHA_X], ay = p.v[BB_TORRANCE_SPARROW_ALPHA_Y];
    switch ((int)bb_first(p.v[BB_TORRANCE_SPARROW_DIST])) {
    case BB_TS_D_BECKMANN:
        return bb_beckmann_sample_dcos(ax, ay, u1, u2);
    case BB_TS_D_GGX:
        return bb_ggx_sample_dcos(ax, ay, u1, u2);
    default:
        return bb_blinn_sample_dcos(p.v[BB_TORRANCE_SPARROW_N], u1, u2);
    }
}

/* The V-groove G(wo, wi) of [CT82] eq. 7 (for tests and plots; the BRDF uses the form above). */
BB_FN bb_real bb_vgroove_g(bb_vec3 wo, bb_vec3 wi) {
    bb_vec3 h = bb_normalize(bb_add(wo, wi));
    bb_real oh = bb_dot(wo, h);
    bb_real inv = BB_R(1.0) / bb_select(oh, BB_R(1.0), oh <= BB_R(0.0));
    bb_real g = bb_min(BB_R(1.0), BB_R(2.0) * h.z * bb_min(wo.z, wi.z) * inv);
    return bb_select(BB_R(0.0), g, wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && oh > BB_R(0.0));
}

BB_FN bb_real bb_torrance_sparrow_eval(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    bb_vec3 wh = bb_normalize(bb_add(wo, wi));
    bb_real oh = bb_clamp_cos(bb_dot(wo, wh));
    bb_mask ok = wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && wh.z > BB_R(0.0) && oh > BB_R(0.0);
    bb_real co = bb_select(BB_R(1.0), wo.z, ok), ci = bb_select(BB_R(1.0), wi.z, ok);
    bb_real ohs = bb_select(BB_R(1.0), oh, ok);
    /* G / (cos_o cos_i); 1/(co ci) may overflow to inf in float, which min() discards. */
    bb_real g_over = bb_min(BB_R(1.0) / (co * ci), BB_R(2.0) * wh.z / (ohs * bb_max(co, ci)));
    bb_real v = BB_R(0.25) * bb_torrance_sparrow_d(p, wh) * g_over * bb_fresnel_eval(fkind, fp, oh);
    return bb_select(BB_R(0.0), v, ok);
}

BB_FN bb_sample bb_torrance_sparrow_sample(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_vec3 wh = bb_torrance_sparrow_sample_dcos(p, u1, u2);
    bb_real oh = bb_clamp_cos(bb_dot(wo, wh));
    bb_vec3 wi = bb_reflect(wo, wh);
    bb_mask ok = wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && wh.z > BB_R(0.0) && oh > BB_R(0.0);
    bb_real co = bb_select(BB_R(1.0), wo.z, ok), hz = bb_select(BB_R(1.0), wh.z, ok);
    bb_real g = bb_min(bb_min(oh / (co * hz), BB_R(2.0)), BB_R(2.0) * wi.z / co);
    bb_real w = g * bb_fresnel_eval(fkind, fp, oh);
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, ok));
}

/* The half-vector quadrature (integrands.h) in the radial CDF of the chosen D. */
BB_FN bb_quad_dist bb_torrance_sparrow_quad_dist(bb_params p) {
    int d = (int)bb_first(p.v[BB_TORRANCE_SPARROW_DIST]);
    int kind = d == BB_TS_D_GGX ? BB_QUAD_GGX : (d == BB_TS_D_BECKMANN ? BB_QUAD_BECKMANN : BB_QUAD_BLINN);
    return bb_make_quad_dist(kind, p.v[BB_TORRANCE_SPARROW_ALPHA_X], p.v[BB_TORRANCE_SPARROW_ALPHA_Y],
                             p.v[BB_TORRANCE_SPARROW_N]);
}

/* Its integrand f cos_theta_i 4 (wo.h) / (D cos_theta_h) times djc = D J cos(theta_h)
 * (bb_quad_halfvector_point): with f = D G F / (4 co ci) and
 * G = min(1, 2 hz co/oh, 2 hz ci/oh) it is F djc min(oh/(co ch), 2, 2 ci/co). */
BB_FN bb_real bb_torrance_sparrow_halfvector_weight(bb_params p, bb_real f_oh, bb_vec3 wo, bb_vec3 wi, bb_real oh, bb_real co,
                                                 bb_real ch, bb_real djc) {
    (void)p, (void)wo;
    return f_oh * djc * bb_min(bb_min(oh / (co * ch), BB_R(2.0)), BB_R(2.0) * wi.z / co);
}

#endif /* BRDFBAKE_BRDF_TORRANCE_SPARROW_H */

/* The Blinn-Phong BRDF (`blinn-phong`):
 *   f = K (wh.n)^N,  K = ks, or ks (N + 2)/(2 pi) with normalized=1,
 * the half-vector form of the Phong highlight [B77: Blinn, "Models of Light Reflection for
 * Computer Synthesized Pictures", SIGGRAPH 1977, the D1 term]; (N + 2)/(2 pi) is the factor that
 * normalises (wh.n)^N as a microfacet distribution (integral of D cos(theta_h) = 1) [WMLT07 eq. 30],
 * not the BRDF's energy. Symmetric in wo and wi, hence reciprocal.
 *
 * Sampling in half-vector space [WMLT07 sec. 5.3]: wh with density (N + 1)/(2 pi) cos^N(theta_h)
 * (the lobe itself), wi = reflect(wo, wh), pdf(wi) = pdf(wh) / (4 wo.wh); the weight is
 *   f cos_i / pdf = K 8 pi (wo.wh) cos_i / (N + 1).
 * Edge cases: microfacet.h's policy (horizon, zero half vector, cos^N for N up to 1e4). */
#ifndef BRDFBAKE_BRDF_BLINN_PHONG_H
#define BRDFBAKE_BRDF_BLINN_PHONG_H

#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/quad_dist.h"

/* Parameter slots. */
#define BB_BLINN_PHONG_N 0
#define BB_BLINN_PHONG_KS 1
#define BB_BLINN_PHONG_NORMALIZED 2 /* 1: K = ks (N + 2)/(2 pi) */

BB_FN bb_real bb_blinn_phong_k(bb_params p) {
    bb_real n = p.v[BB_BLINN_PHONG_N];
    return p.v[BB_BLINN_PHONG_KS] * bb_select(BB_R(1.0), (n + BB_R(2.0)) * (BB_R(0.5) * BB_INV_PI),
                                              p.v[BB_BLINN_PHONG_NORMALIZED] > BB_R(0.5));
}

BB_FN bb_real bb_blinn_phong_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_vec3 wh = bb_normalize(bb_add(wo, wi));
    bb_real v = bb_blinn_phong_k(p) * bb_pow1m(bb_one_minus_z(wh), p.v[BB_BLINN_PHONG_N]);
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && wh.z > BB_R(0.0));
}

BB_FN bb_sample bb_blinn_phong_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_real n = p.v[BB_BLINN_PHONG_N];
    bb_vec3 wh = bb_sample_cos_power(n, u1, u2);
    bb_real cos_oh = bb_dot(wo, wh);
    bb_vec3 wi = bb_reflect(wo, wh);
    bb_real w = bb_blinn_phong_k(p) * (BB_R(4.0) * BB_2PI) * cos_oh * wi.z / (n + BB_R(1.0));
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && cos_oh > BB_R(0.0)));
}

/* The half-vector quadrature (integrands.h) in the radial CDF of the cos^(N+1) density. */
BB_FN bb_quad_dist bb_blinn_phong_quad_dist(bb_params p) {
    return bb_make_quad_dist(BB_QUAD_BLINN, BB_R(1.0), BB_R(1.0), p.v[BB_BLINN_PHONG_N]);
}

/* Its integrand f cos_theta_i 4 (wo.h) / (D cos_theta_h) times djc = D J cos(theta_h)
 * (bb_quad_halfvector_point): f = K cos^N = K 2 pi/(N + 2) D. */
BB_FN bb_real bb_blinn_phong_halfvector_weight(bb_params p, bb_real f_oh, bb_vec3 wo, bb_vec3 wi, bb_real oh, bb_real co,
                                            bb_real ch, bb_real djc) {
    (void)f_oh, (void)wo, (void)co;
    return bb_blinn_phong_k(p) * (BB_R(4.0) * BB_2PI) / (p.v[BB_BLINN_PHONG_N] + BB_R(2.0)) * wi.z * oh / ch * djc;
}

#endif /* BRDFBAKE_BRDF_BLINN_PHONG_H */

/* The GGX (Trowbridge-Reitz) microfacet BRDF with Smith masking-shadowing:
 *   f = D(wh) G2(wo, wi) F(wo.wh) / (4 cos_theta_o cos_theta_i)      [WMLT07 eq. 20]
 * with D, G1, G2 from microfacet.h; G2 separable or height-correlated. */
#ifndef BRDFBAKE_BRDF_GGX_H
#define BRDFBAKE_BRDF_GGX_H

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/microfacet.h"

/* Parameter slots. */
#define BB_GGX_ALPHA_X 0
#define BB_GGX_ALPHA_Y 1
#define BB_GGX_SHADOWING 2 /* 0: separable, 1: height-correlated */

BB_FN real bb_ggx_g2(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    real ax = p.v[BB_GGX_ALPHA_X], ay = p.v[BB_GGX_ALPHA_Y];
    return bb_select(bb_ggx_g2_separable(wo, wi, ax, ay), bb_ggx_g2_correlated(wo, wi, ax, ay),
                     p.v[BB_GGX_SHADOWING] > BB_R(0.5));
}

BB_FN real bb_ggx_eval(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    bb_vec3 wh = bb_normalize(bb_add(wo, wi));
    real d = bb_ggx_d(wh, p.v[BB_GGX_ALPHA_X], p.v[BB_GGX_ALPHA_Y]);
    real f = bb_fresnel_eval(fkind, fp, bb_clamp_cos(bb_dot(wo, wh)));
    real den = BB_R(4.0) * wo.z * wi.z;
    real v = d * bb_ggx_g2(p, wo, wi) * f / bb_select(BB_R(1.0), den, den > BB_R(0.0));
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && wh.z > BB_R(0.0));
}

/* Importance sampling of the visible normals [H18]: with pdf(wi) = D_wo(wh) / (4 wo.wh) the
 * estimator weight f cos_theta_i / pdf reduces to F(wo.wh) G2(wo, wi) / G1(wo) [H18 eq. 19].
 * d is the disk point bb_disk_polar(u1, u2) (cell-independent: the fast kernels tabulate it). */
BB_FN bb_sample bb_ggx_sample_disk(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec2 d) {
    real ax = p.v[BB_GGX_ALPHA_X], ay = p.v[BB_GGX_ALPHA_Y];
    bb_vec3 wh = bb_ggx_sample_vndf_disk(wo, ax, ay, d);
    real cos_oh = bb_clamp_cos(bb_dot(wo, wh));
    bb_vec3 wi = bb_reflect(wo, wh);
    real g1o = bb_ggx_g1(wo, ax, ay);
    real w = bb_fresnel_eval(fkind, fp, cos_oh) * bb_ggx_g2(p, wo, wi) /
             bb_select(BB_R(1.0), g1o, g1o > BB_R(0.0));
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, wi.z > BB_R(0.0) && g1o > BB_R(0.0)));
}

BB_FN bb_sample bb_ggx_sample(bb_params p, int fkind, bb_params fp, bb_vec3 wo, real u1, real u2) {
    return bb_ggx_sample_disk(p, fkind, fp, wo, bb_disk_polar(u1, u2));
}

#endif /* BRDFBAKE_BRDF_GGX_H */

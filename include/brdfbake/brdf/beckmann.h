/* The Beckmann microfacet BRDF with Smith masking-shadowing (`beckmann`):
 *   f = D(wh) G2(wo, wi) F(wo.wh) / (4 cos_theta_o cos_theta_i)      [WMLT07 eq. 20]
 * with the Beckmann D, Lambda (erf form), G1 and G2 (separable or height-correlated) of
 * microfacet.h [WMLT07 eq. 25-27; H14 eq. 71-72, 98-99]; isotropic or anisotropic.
 * Edge cases: microfacet.h's policy. */
#ifndef BRDFBAKE_BRDF_BECKMANN_H
#define BRDFBAKE_BRDF_BECKMANN_H

#include "brdfbake/brdf/smith.h"

/* Parameter slots: those of every Smith lobe (smith.h). */
#define BB_BECKMANN_ALPHA_X BB_SMITH_ALPHA_X
#define BB_BECKMANN_ALPHA_Y BB_SMITH_ALPHA_Y
#define BB_BECKMANN_SHADOWING BB_SMITH_SHADOWING /* 0: separable, 1: height-correlated */

/* The Smith lobe (smith.h) with the Beckmann distribution; visible normals [HD14, J14]. */
BB_FN real bb_beckmann_eval(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    return bb_smith_eval(BB_SMITH_BECKMANN, p, fkind, fp, wo, wi);
}

BB_FN bb_sample bb_beckmann_sample(bb_params p, int fkind, bb_params fp, bb_vec3 wo, real u1, real u2) {
    return bb_smith_sample(BB_SMITH_BECKMANN, p, fkind, fp, wo, u1, u2);
}

BB_FN bb_quad_dist bb_beckmann_quad_dist(bb_params p) { return bb_smith_quad_dist(BB_SMITH_BECKMANN, p); }

BB_FN real bb_beckmann_halfvector_weight(bb_params p, real f_oh, bb_vec3 wo, bb_vec3 wi, real oh, real co, real ch,
                                         real djc) {
    return bb_smith_halfvector_weight(BB_SMITH_BECKMANN, p, f_oh, wo, wi, oh, co, ch, djc);
}

#endif /* BRDFBAKE_BRDF_BECKMANN_H */

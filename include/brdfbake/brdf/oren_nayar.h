/* The Oren-Nayar rough diffuse BRDF, the qualitative model of
 *   [ON94] Oren, Nayar, "Generalization of Lambert's Reflectance Model", SIGGRAPH 1994, eq. 30:
 *     f = rho/pi (A + B max(0, cos(phi_i - phi_o)) sin(alpha) tan(beta)),
 *     A = 1 - 0.5 sigma^2/(sigma^2 + 0.33),  B = 0.45 sigma^2/(sigma^2 + 0.09),
 *     alpha = max(theta_i, theta_o), beta = min(theta_i, theta_o),
 * sigma the standard deviation of the facet slope angle in radians. sigma = 0 is Lambert.
 *
 * Written without angles or tan(): cos(phi_i - phi_o) sin(theta_i) sin(theta_o) is the dot
 * product of the tangential parts, and sin(alpha) tan(beta) = sin_i sin_o / max(cos_i, cos_o)
 * (alpha is the larger angle, whose sine is the larger, beta the one with the larger cosine),
 * so that
 *     f = rho/pi (A + B max(0, wo.x wi.x + wo.y wi.y) / max(cos_i, cos_o))
 * (the form of pbrt-v4's DiffuseBxDF predecessor and of Fujii's reformulation), finite for all
 * directions above the horizon, 0 at or below it. */
#ifndef BRDFBAKE_BRDF_OREN_NAYAR_H
#define BRDFBAKE_BRDF_OREN_NAYAR_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Parameter slots. */
#define BB_OREN_NAYAR_SIGMA 0 /* radians, >= 0 */
#define BB_OREN_NAYAR_RHO 1

/* A and B of [ON94] eq. 30. */
BB_FN bb_real bb_oren_nayar_a(bb_real sigma) {
    bb_real s2 = sigma * sigma;
    return BB_R(1.0) - BB_R(0.5) * s2 / (s2 + BB_R(0.33));
}
BB_FN bb_real bb_oren_nayar_b(bb_real sigma) {
    bb_real s2 = sigma * sigma;
    return BB_R(0.45) * s2 / (s2 + BB_R(0.09));
}

/* pi f / rho: the bracket of [ON94] eq. 30, for wo and wi above the horizon. */
BB_FN bb_real bb_oren_nayar_bracket(bb_real sigma, bb_vec3 wo, bb_vec3 wi) {
    bb_real t = bb_max(wo.x * wi.x + wo.y * wi.y, BB_R(0.0));
    bb_real m = bb_max(wo.z, wi.z);
    return bb_oren_nayar_a(sigma) + bb_oren_nayar_b(sigma) * t / bb_select(m, BB_R(1.0), m <= BB_R(0.0));
}

BB_FN bb_real bb_oren_nayar_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_real v = p.v[BB_OREN_NAYAR_RHO] * BB_INV_PI * bb_oren_nayar_bracket(p.v[BB_OREN_NAYAR_SIGMA], wo, wi);
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wi.z > BB_R(0.0));
}

/* Cosine-weighted hemisphere sampling (Malley's method), pdf = cos_i/pi: the weight is
 * rho (A + B max(0, t)/max(cos_i, cos_o)), bounded by rho (A + B / cos_o); its variance grows
 * only like log(1/cos_o) towards grazing. */
BB_FN bb_sample bb_oren_nayar_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_vec3 wi = bb_cosine_hemisphere(u1, u2);
    bb_real w = p.v[BB_OREN_NAYAR_RHO] * bb_oren_nayar_bracket(p.v[BB_OREN_NAYAR_SIGMA], wo, wi);
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, wo.z > BB_R(0.0) && wi.z > BB_R(0.0)));
}

#endif /* BRDFBAKE_BRDF_OREN_NAYAR_H */

/* Ideal diffuse reflection (Lambert 1760): f = rho / pi. */
#ifndef BRDFBAKE_BRDF_LAMBERT_H
#define BRDFBAKE_BRDF_LAMBERT_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Parameter slots. */
#define BB_LAMBERT_RHO 0

BB_FN bb_real bb_lambert_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    return bb_select(BB_R(0.0), p.v[BB_LAMBERT_RHO] * BB_INV_PI, wo.z > BB_R(0.0) && wi.z > BB_R(0.0));
}

/* Cosine-weighted hemisphere sampling (Malley's method): pdf = cos(theta_i)/pi, so the weight
 * f cos / pdf is rho for every sample (0 for u1 = 0, a direction on the horizon). */
BB_FN bb_sample bb_lambert_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_vec3 wi = bb_cosine_hemisphere(u1, u2);
    return bb_make_sample(wi, bb_select(BB_R(0.0), p.v[BB_LAMBERT_RHO], wo.z > BB_R(0.0) && wi.z > BB_R(0.0)));
}

#endif /* BRDFBAKE_BRDF_LAMBERT_H */

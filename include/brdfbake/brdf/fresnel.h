/* Fresnel reflectance terms, shared by host and kernels.
 *
 * A Fresnel term is a kind (BB_FRESNEL_*) and a parameter block; bb_fresnel_eval dispatches on
 * the kind. Kernels pass a compile-time constant kind, so the switch folds away. */
#ifndef BRDFBAKE_BRDF_FRESNEL_H
#define BRDFBAKE_BRDF_FRESNEL_H

#include "brdfbake/brdf/params.h"

#define BB_FRESNEL_NONE 0
#define BB_FRESNEL_SCHLICK 1

/* Parameter slots. */
#define BB_SCHLICK_F0 0

/* Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 24:
 * F = F0 + (1 - F0)(1 - cos)^5. Relative error against the exact dielectric below 1%
 * for eta in [1.3, 1.7] away from grazing. */
BB_FN real bb_fresnel_schlick(real cos_theta, real f0) {
    real m = bb_clamp(BB_R(1.0) - cos_theta, BB_R(0.0), BB_R(1.0));
    real m2 = m * m;
    return f0 + (BB_R(1.0) - f0) * (m2 * m2 * m);
}

/* F(cos_theta) for the given kind; cos_theta is the cosine between the direction and the
 * (micro)surface normal. Unknown kinds return 1 (no Fresnel weighting). */
BB_FN real bb_fresnel_eval(int kind, bb_params fp, real cos_theta) {
    switch (kind) {
    case BB_FRESNEL_SCHLICK:
        return bb_fresnel_schlick(cos_theta, fp.v[BB_SCHLICK_F0]);
    default:
        return BB_R(1.0);
    }
}

#endif /* BRDFBAKE_BRDF_FRESNEL_H */

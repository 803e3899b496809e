/* Parameter blocks passed from the host to the shared BRDF functions.
 *
 * A model's numeric parameters travel as a fixed-size array so that host and kernels share one
 * layout (the host fills a double array, converted to the kernel's real type). Each model header
 * names the slots it uses. */
#ifndef BRDFBAKE_BRDF_PARAMS_H
#define BRDFBAKE_BRDF_PARAMS_H

#include "brdfbake/brdf/compat.h"

#define BB_MAX_PARAMS 8

typedef struct {
    bb_real v[BB_MAX_PARAMS];
#ifdef __OPENCL_C_VERSION__
    __global const bb_scalar* data; /* the model data (BB_MODEL_DATA_ARG), set by the entry point */
#endif
} bb_params;

/* One importance sample: the incident direction and its estimator weight f*cos(theta_i)/pdf.
 * A weight of 0 means "no contribution" (below the horizon, back-facing microfacet, ...). */
typedef struct {
    bb_vec3 wi;
    bb_real weight;
} bb_sample;

BB_FN bb_sample bb_make_sample(bb_vec3 wi, bb_real weight) {
    bb_sample s = {wi, weight};
    return s;
}

#endif /* BRDFBAKE_BRDF_PARAMS_H */

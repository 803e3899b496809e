/* Point evaluations of the shared BRDF functions on the device: f(wo, wi) for lists of direction
 * pairs, and the model's importance sample for lists of (wo, u1, u2). Used by the reciprocity
 * and non-finite scans and by the host-vs-device parity tests.
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"

BB_FN bb_params load_params(__global const bb_real* src) {
    bb_params p;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) p.v[k] = src[k];
    return p;
}

BB_FN bb_vec3 load_vec3(__global const bb_real* src, unsigned int i) {
    return bb_v3(src[3 * i], src[3 * i + 1], src[3 * i + 2]);
}

__kernel void BB_ENTRY_MODEL_EVAL(__global const bb_real* wo, __global const bb_real* wi, __global const bb_real* model_p,
                         __global const bb_real* fresnel_p,
                         __global const bb_scalar* model_data /* BB_MODEL_DATA_ARG */, const unsigned int n, __global bb_real* out) {
    const unsigned int i = (unsigned int)get_global_id(0);
    if (i >= n)
        return;
    bb_params p = load_params(model_p);
    p.data = model_data;
    out[i] = bb_model_eval(BB_MODEL, p, BB_FRESNEL, load_params(fresnel_p),
                           load_vec3(wo, i), load_vec3(wi, i));
}

__kernel void BB_ENTRY_MODEL_SAMPLE(__global const bb_real* wo, __global const bb_real* u, __global const bb_real* model_p,
                           __global const bb_real* fresnel_p,
                         __global const bb_scalar* model_data /* BB_MODEL_DATA_ARG */, const unsigned int n, __global bb_real* out_wi,
                           __global bb_real* out_weight) {
    const unsigned int i = (unsigned int)get_global_id(0);
    if (i >= n)
        return;
    bb_params p = load_params(model_p);
    p.data = model_data;
    const bb_sample s = bb_model_sample(BB_MODEL, p, BB_FRESNEL, load_params(fresnel_p),
                                        load_vec3(wo, i), u[2 * i], u[2 * i + 1]);
    out_wi[3 * i] = s.wi.x;
    out_wi[3 * i + 1] = s.wi.y;
    out_wi[3 * i + 2] = s.wi.z;
    out_weight[i] = s.weight;
}

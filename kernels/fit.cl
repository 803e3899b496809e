/* `brdfbake fit` (host/fit/model_fit.cpp): the objective of fitting an analytic model to a target
 * BRDF on a fixed set of direction pairs (wo_j, wi_j) with weights w_j (their share of the pair
 * measure d wo d wi):
 *
 *   S(candidate) = sum_j w_j (g(f_c(wo_j, wi_j) cos theta_i) - t_j)^2,   t_j = g(f_target cos theta_i)
 *
 * with g the metric's compression (brdf/fit_metric.h, shared with the host's targets). A target
 * value below 0 is an unmeasured bin and takes no part. One work-item per (candidate, block of
 * pairs); the host sums a candidate's blocks. With `residuals` set (and block = 1) each work-item
 * writes its pair's signed residual g(f_c cos theta_i) - t_j instead (0 where unmeasured), whose
 * derivatives the host's parameter errors take (model_fit.cpp, parameter_errors). Candidates
 * carry their own model and Fresnel parameters and the index of the channel (row of `targets`)
 * they are fitted to.
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. */
#include "brdfbake/brdf/fit_metric.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"

__kernel void BB_ENTRY_MODEL_FIT_OBJECTIVE(__global const bb_scalar* pairs, __global const bb_scalar* targets,
                                           const unsigned int n_pairs, __global const bb_scalar* cand_model_p,
                                           __global const bb_scalar* cand_fresnel_p,
                                           __global const unsigned int* cand_channel, const unsigned int n_cand,
                                           const unsigned int block, const int metric, const int residuals,
                                           __global const bb_scalar* model_data /* BB_MODEL_DATA_ARG */,
                                           __global bb_scalar* out) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    const unsigned int n_blocks = (n_pairs + block - 1) / block;
    if (gid >= n_cand * n_blocks)
        return;
    const unsigned int cand = gid / n_blocks, b = gid - cand * n_blocks;
    bb_params p, fp;
    for (int i = 0; i < BB_MAX_PARAMS; ++i) {
        p.v[i] = cand_model_p[cand * BB_MAX_PARAMS + i];
        fp.v[i] = cand_fresnel_p[cand * BB_MAX_PARAMS + i];
    }
    p.data = model_data;
    __global const bb_scalar* t = targets + (size_t)cand_channel[cand] * n_pairs;
    const unsigned int end = min(n_pairs, (b + 1) * block);
    bb_real sum = BB_R(0.0);
    for (unsigned int j = b * block; j < end; ++j) {
        const bb_real tj = t[j];
        if (tj < BB_R(0.0))
            continue;
        __global const bb_scalar* q = pairs + (size_t)j * BB_FIT_PAIR_VALUES;
        const bb_vec3 wo = bb_v3(q[0], q[1], q[2]), wi = bb_v3(q[3], q[4], q[5]);
        const bb_real f = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, wi) * wi.z;
        const bb_real d = bb_fit_compress(metric, bb_max(f, BB_R(0.0))) - tj;
        sum += residuals ? d : q[6] * d * d;
    }
    out[gid] = sum;
}

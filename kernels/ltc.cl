/* Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time Polygonal-Light
 * Shading with Linearly Transformed Cosines", [HDHN16]): the two kernels of the fit's objective
 * (host/fit/ltc_fit.cpp).
 *
 *   ltc_lobe_points  one work-item per (texel, point): the model's importance sample of the
 *                    point (u1, u2) = ((i + 1/2)/n, (j + 1/2)/n) of an n x n grid, with its weight
 *                    w = f cos(theta_i) / pdf, the inverse pdf 1/pdf = w / (f cos(theta_i)) and the
 *                    Schlick factor (1 - wo.h)^5 of the fresnel channel. Fixed points: the
 *                    objective is a deterministic function of the matrix.
 *   ltc_objective    one work-item per candidate matrix: S = (1/N) sum_k min(p_k, D(w_k)) / pdf_k,
 *                    the estimate of integral over the upper hemisphere of min(p, D) with the
 *                    lobe's own points, where p = f cos / E_s (E_s: the mean weight of the same
 *                    points, so that p integrates to 1 on them) and D the LTC distribution. Each
 *                    term is at most p_k / pdf_k = w_k / E_s, bounded for the models' samplers.
 *                    The host turns it into the L1 distance:
 *                      integral_H |p - D| = integral_H p + integral_H D - 2 integral_H min(p, D)
 *                                         = 1 + (1 + n_z)/2 - 2 S,
 *                    with integral_H D in closed form (host/fit/ltc_fit.cpp).
 *
 * D(w) = D_o(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3           [HDHN16 eq. 1 and its Jacobian]
 * with D_o(w_o) = max(0, z_o) / pi, i.e. D = max(0, (M^-1 w)_z) |det M^-1| / (pi |M^-1 w|^4).
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. Scalar work-items. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"

__kernel void BB_ENTRY_LTC_LOBE_POINTS(__global const bb_scalar* cell_mu, __global const bb_scalar* model_p,
                                       __global const bb_scalar* fresnel_p,
                                       __global const bb_scalar* model_data /* BB_MODEL_DATA_ARG */,
                                       const unsigned int n_cells, const unsigned int n_side,
                                       __global bb_scalar* points) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    const unsigned int per_cell = n_side * n_side;
    if (gid >= n_cells * per_cell)
        return;
    const unsigned int cell = gid / per_cell, k = gid - cell * per_cell;
    bb_params p, fp;
    for (int i = 0; i < BB_MAX_PARAMS; ++i) {
        p.v[i] = model_p[cell * BB_MAX_PARAMS + i];
        fp.v[i] = fresnel_p[i];
    }
    p.data = model_data;
    const bb_real mu = cell_mu[cell];
    const bb_vec3 wo = bb_v3(sqrt(fmax(BB_R(0.0), BB_R(1.0) - mu * mu)), BB_R(0.0), mu);
    const bb_real u1 = ((bb_real)(k % n_side) + BB_R(0.5)) / (bb_real)n_side;
    const bb_real u2 = ((bb_real)(k / n_side) + BB_R(0.5)) / (bb_real)n_side;
    const bb_sample s = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, u1, u2);
    const bb_real f_cos = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, s.wi) * s.wi.z;
    const int ok = s.weight > BB_R(0.0) && f_cos > BB_R(0.0) && s.wi.z > BB_R(0.0) && isfinite(s.weight) &&
                   isfinite(f_cos);
    const bb_vec3 h = bb_normalize(bb_add(wo, s.wi));
    const bb_real c = BB_R(1.0) - clamp(bb_dot(wo, h), BB_R(0.0), BB_R(1.0));
    __global bb_scalar* out = points + (size_t)gid * BB_LTC_POINT_VALUES;
    out[0] = s.wi.x;
    out[1] = s.wi.y;
    out[2] = s.wi.z;
    out[3] = ok ? s.weight : BB_R(0.0);
    out[4] = ok ? s.weight / f_cos : BB_R(0.0);
    out[5] = ok ? c * c * c * c * c : BB_R(0.0);
}

__kernel void BB_ENTRY_LTC_OBJECTIVE(__global const bb_scalar* points, const unsigned int points_per_cell,
                                     __global const unsigned int* candidate_cell,
                                     __global const bb_scalar* candidates, __global const bb_scalar* inv_e,
                                     const unsigned int n_candidates, __global bb_scalar* overlap) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_candidates)
        return;
    const unsigned int cell = candidate_cell[gid];
    __global const bb_scalar* m = candidates + (size_t)gid * BB_LTC_CANDIDATE_VALUES;
    const bb_real m00 = m[0], m01 = m[1], m02 = m[2], m10 = m[3], m11 = m[4], m12 = m[5];
    const bb_real m20 = m[6], m21 = m[7], m22 = m[8], det_over_pi = m[9] * BB_INV_PI;
    const bb_real scale = inv_e[cell];
    __global const bb_scalar* pt = points + (size_t)cell * points_per_cell * BB_LTC_POINT_VALUES;
    bb_real sum = BB_R(0.0);
    for (unsigned int k = 0; k < points_per_cell; ++k, pt += BB_LTC_POINT_VALUES) {
        const bb_real x = pt[0], y = pt[1], z = pt[2];
        const bb_real ox = m00 * x + m01 * y + m02 * z;
        const bb_real oy = m10 * x + m11 * y + m12 * z;
        const bb_real oz = m20 * x + m21 * y + m22 * z;
        const bb_real l2 = ox * ox + oy * oy + oz * oz;
        const bb_real d = fmax(oz, BB_R(0.0)) * det_over_pi / (l2 * l2);
        sum += fmin(pt[3] * scale, d * pt[4]);
    }
    overlap[gid] = sum / (bb_real)points_per_cell;
}

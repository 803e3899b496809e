/* Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time Polygonal-Light
 * Shading with Linearly Transformed Cosines", [HDHN16]): the two kernels of the fit's objective
 * (host/fit/ltc_fit.cpp).
 *
 *   ltc_lobe_points  one work-item per (texel, point): the model's importance sample of the
 *                    point (u1, u2) of an n x n grid, u2 = (j + 1/2)/n and u1 graded towards the
 *                    lobe's tail (the nodes and their weights computed once on the host: the same
 *                    bits whatever the kernel's build), with its weight w = f cos(theta_i) / pdf
 *                    times the node's weight and the inverse pdf 1/pdf = w / (f cos(theta_i)).
 *                    Fixed points: the objective is a deterministic function of the matrix.
 *   ltc_objective    one work-item per candidate matrix: S = (1/N) sum_k min(p_k, D(w_k)) / pdf_k,
 *                    the estimate of integral over the upper hemisphere of min(p, D) with the
 *                    lobe's own points, where p = f cos / E_s (E_s: the mean weight of the same
 *                    points, so that p integrates to 1 on them) and D the LTC distribution. Each
 *                    term is at most p_k / pdf_k = w_k / E_s, bounded for the models' samplers.
 *                    The host turns it into the L1 distance:
 *                      integral_H |p - D| = integral_H p + integral_H D - 2 integral_H min(p, D)
 *                                         = 1 + (1 + n_z)/2 - 2 S,
 *                    with integral_H D in closed form (host/fit/ltc_fit.cpp).
 *   ltc_distance     one work-item per (texel, grid): the reported distance of the written M, on
 *                    n x n jittered grids independent of the fit's points (a fit overfits the
 *                    fixed points it was fitted on: their distance is biased low). Two unbiased
 *                    estimates of integral_H min(p, D) from the same jittered grid: with the
 *                    lobe's sampler (terms min(p, D) / pdf <= w / E) and with the LTC's own
 *                    (w = M w_c / |M w_c|, w_c cosine-distributed, pdf D: terms min(p, D) / D <= 1),
 *                    E the texel's albedo from the host; the host averages the two per grid and
 *                    takes the spread of the grids' values as the distance's error.
 *
 * D(w) = D_o(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3           [HDHN16 eq. 1 and its Jacobian]
 * with D_o(w_o) = max(0, z_o) / pi, i.e. D = max(0, (M^-1 w)_z) |det M^-1| / (pi |M^-1 w|^4).
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. Scalar work-items. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"

/* A texel's model parameters (with the model data) and Fresnel parameters, and its viewer
 * wo = (sin theta_o, 0, cos theta_o): the prologue of ltc_lobe_points and ltc_distance. */
typedef struct {
    bb_params p, fp;
    bb_vec3 wo;
} bb_ltc_texel;

static inline bb_ltc_texel bb_ltc_texel_of(const unsigned int cell, __global const bb_scalar* cell_mu,
                                           __global const bb_scalar* model_p, __global const bb_scalar* fresnel_p,
                                           __global const bb_scalar* model_data) {
    bb_ltc_texel t;
    for (int i = 0; i < BB_MAX_PARAMS; ++i) {
        t.p.v[i] = model_p[cell * BB_MAX_PARAMS + i];
        t.fp.v[i] = fresnel_p[i];
    }
    t.p.data = model_data;
    const bb_real mu = cell_mu[cell];
    t.wo = bb_v3(sqrt(fmax(BB_R(0.0), BB_R(1.0) - mu * mu)), BB_R(0.0), mu);
    return t;
}

__kernel void BB_ENTRY_LTC_LOBE_POINTS(__global const bb_scalar* cell_mu, __global const bb_scalar* model_p,
                                       __global const bb_scalar* fresnel_p,
                                       __global const bb_scalar* model_data /* BB_MODEL_DATA_ARG */,
                                       const unsigned int n_cells, const unsigned int n_side,
                                       __global const bb_scalar* nodes, __global bb_scalar* points) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    const unsigned int per_cell = n_side * n_side;
    if (gid >= n_cells * per_cell)
        return;
    const unsigned int cell = gid / per_cell, k = gid - cell * per_cell;
    const bb_ltc_texel tx = bb_ltc_texel_of(cell, cell_mu, model_p, fresnel_p, model_data);
    const bb_params p = tx.p, fp = tx.fp;
    const bb_vec3 wo = tx.wo;
    /* nodes[2 i], nodes[2 i + 1]: column i's u1 and the weight of its cell's measure in u1
     * (host/fit/ltc_fit.cpp, graded_nodes) */
    const unsigned int i = k % n_side;
    const bb_real u1 = nodes[2u * i], cell_w = nodes[2u * i + 1u];
    const bb_real u2 = ((bb_real)(k / n_side) + BB_R(0.5)) / (bb_real)n_side;
    const bb_sample s = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, u1, u2);
    const bb_real f_cos = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, s.wi) * s.wi.z;
    const int ok = s.weight > BB_R(0.0) && f_cos > BB_R(0.0) && s.wi.z > BB_R(0.0) && isfinite(s.weight) &&
                   isfinite(f_cos);
    __global bb_scalar* out = points + (size_t)gid * BB_LTC_POINT_VALUES;
    out[0] = s.wi.x;
    out[1] = s.wi.y;
    out[2] = s.wi.z;
    out[3] = ok ? s.weight * cell_w : BB_R(0.0);
    out[4] = ok ? s.weight / f_cos * cell_w : BB_R(0.0);
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

/* A 32-bit integer hash (Wellons' "lowbias32" constants): the jitter of ltc_distance's grids. */
static inline unsigned int bb_ltc_hash(unsigned int x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* D(w) of the LTC whose M^-1 (row-major) is inv[0..8] and |det M^-1| inv[9]. */
static inline bb_real bb_ltc_density(__global const bb_scalar* inv, const bb_vec3 w) {
    const bb_real ox = inv[0] * w.x + inv[1] * w.y + inv[2] * w.z;
    const bb_real oy = inv[3] * w.x + inv[4] * w.y + inv[5] * w.z;
    const bb_real oz = inv[6] * w.x + inv[7] * w.y + inv[8] * w.z;
    const bb_real l2 = ox * ox + oy * oy + oz * oz;
    return fmax(oz, BB_R(0.0)) * inv[9] * BB_INV_PI / (l2 * l2);
}

__kernel void BB_ENTRY_LTC_DISTANCE(__global const bb_scalar* cell_mu, __global const bb_scalar* model_p,
                                    __global const bb_scalar* fresnel_p,
                                    __global const bb_scalar* model_data /* BB_MODEL_DATA_ARG */,
                                    const unsigned int n_cells, const unsigned int n_grids, const unsigned int n_side,
                                    __global const bb_scalar* matrices, __global const bb_scalar* albedo,
                                    __global bb_scalar* parts) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_grids)
        return;
    const unsigned int cell = gid / n_grids, grid = gid - cell * n_grids;
    const bb_ltc_texel tx = bb_ltc_texel_of(cell, cell_mu, model_p, fresnel_p, model_data);
    const bb_params p = tx.p, fp = tx.fp;
    const bb_vec3 wo = tx.wo;
    __global const bb_scalar* m = matrices + (size_t)cell * BB_LTC_MATRIX_VALUES;
    const bb_real inv_e = BB_R(1.0) / (bb_real)albedo[cell];
    const unsigned int stream = bb_ltc_hash(bb_ltc_hash(cell) ^ (grid * 0x9e3779b9u + 0x6c74636du));
    const unsigned int per = n_side * n_side;
    bb_real lobe = BB_R(0.0), ltc = BB_R(0.0);
    for (unsigned int k = 0; k < per; ++k) {
        const unsigned int h1 = bb_ltc_hash(stream ^ (2u * k)), h2 = bb_ltc_hash(stream ^ (2u * k + 1u));
        const bb_real u1 = fmin(((bb_real)(k % n_side) + bb_unit_from_bits(h1)) / (bb_real)n_side, BB_R(1.0));
        const bb_real u2 = fmin(((bb_real)(k / n_side) + bb_unit_from_bits(h2)) / (bb_real)n_side, BB_R(1.0));
        /* the lobe's sampler: min(p, D) / pdf = min(w / E, D / pdf), 1/pdf = w / (f cos) */
        const bb_sample s = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, u1, u2);
        const bb_real f_cos = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, s.wi) * s.wi.z;
        if (s.weight > BB_R(0.0) && f_cos > BB_R(0.0) && s.wi.z > BB_R(0.0) && isfinite(s.weight) && isfinite(f_cos))
            lobe += fmin(s.weight * inv_e, bb_ltc_density(m + 9, s.wi) * s.weight / f_cos);
        /* the LTC's own: w = M w_c / |M w_c|, min(p, D) / D = min(p / D, 1) */
        const bb_vec3 wc = bb_cosine_hemisphere(u1, u2);
        const bb_vec3 w = bb_normalize(bb_v3(m[0] * wc.x + m[1] * wc.y + m[2] * wc.z,
                                             m[3] * wc.x + m[4] * wc.y + m[5] * wc.z,
                                             m[6] * wc.x + m[7] * wc.y + m[8] * wc.z));
        if (w.z > BB_R(0.0)) {
            const bb_real d = bb_ltc_density(m + 9, w);
            const bb_real pw = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, w) * w.z * inv_e;
            if (d > BB_R(0.0) && pw > BB_R(0.0) && isfinite(pw))
                ltc += fmin(pw / d, BB_R(1.0));
        }
    }
    parts[2 * (size_t)gid] = lobe / (bb_real)per;
    parts[2 * (size_t)gid + 1] = ltc / (bb_real)per;
}

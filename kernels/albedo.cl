/* Directional albedo E(wo) = integral of f(wo, wi) cos(theta_i) over the upper hemisphere.
 *
 * Estimator: importance sampling of the model (bb_model_sample) driven by a randomised
 * Hammersley set. Each work-item computes one replica of one cell: the n-point set rotated by
 * its own Cranley-Patterson shift. The host turns the replicas into the mean and its standard
 * error. Non-finite weights are counted, never summed, so that a NaN cannot hide in a table.
 *
 * Two entry points from the one shared source, chosen by the build options (Engine::build_options):
 *   albedo_replicas       scalar real: one sample per step (GPUs, and models without a tabulated
 *                         sample);
 *   albedo_replicas_disk  -D BB_VECTOR_WIDTH=W, real a vector of W lanes: W samples per step, their
 *                         disk points bb_disk_polar(u1, u2) read from a table that the host fills
 *                         once for all cells (the points and their sin/cos do not depend on the
 *                         cell). Same point set, same shifts, same estimator; PoCL compiles it to
 *                         SIMD code.
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE] [-D BB_VECTOR_WIDTH=W]. */
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/sampling.h"

#ifndef BB_VECTOR_WIDTH

__kernel void albedo_replicas(__global const real* cell_mu,    /* cos(theta_o) per cell */
                              __global const real* cell_phi,   /* phi_o (radians) per cell */
                              __global const real* model_p,    /* BB_MAX_PARAMS per cell */
                              __global const real* fresnel_p,  /* BB_MAX_PARAMS */
                              __global const real* shifts,     /* 2 per replica */
                              const unsigned int n_points,     /* points per replica */
                              const unsigned int n_replicas,
                              const unsigned int n_cells,
                              __global real* replica_mean,     /* n_cells * n_replicas */
                              __global unsigned int* bad_count) /* n_cells * n_replicas */
{
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas)
        return;
    const unsigned int cell = gid / n_replicas;
    const unsigned int rep = gid - cell * n_replicas;

    bb_params p, fp;
    /* A non-finite parameter would hide behind the models' guards (x > 0 is false for NaN) and
     * turn into zero weights: count every sample of such a cell as non-finite instead. */
    unsigned int params_ok = 1;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) {
        p.v[k] = model_p[cell * BB_MAX_PARAMS + k];
        fp.v[k] = fresnel_p[k];
        params_ok &= (unsigned int)(isfinite(p.v[k]) && isfinite(fp.v[k]));
    }
    const bb_vec3 wo = bb_dir_from_mu_phi(cell_mu[cell], cell_phi[cell]);
    const real s1 = shifts[2 * rep], s2 = shifts[2 * rep + 1];

    /* Kahan-compensated sum: the float sum of 2^16 terms keeps ~1e-7 relative accuracy. */
    real sum = BB_R(0.0), comp = BB_R(0.0);
    unsigned int bad = 0;
    for (unsigned int i = 0; i < n_points; ++i) {
        const real u1 = bb_rotate(bb_hammersley_u1(i, n_points), s1);
        const real u2 = bb_rotate(bb_hammersley_u2(i), s2);
        const bb_sample s = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, u1, u2);
        const int ok = isfinite(s.weight);
        bad += ok ? 0u : 1u;
        const real y = (ok ? s.weight : BB_R(0.0)) - comp;
        const real t = sum + y;
        comp = (t - sum) - y;
        sum = t;
    }
    replica_mean[gid] = sum / (real)n_points;
    bad_count[gid] = params_ok ? bad : n_points;
}

#else /* BB_VECTOR_WIDTH */

/* The sum of the lanes of v, compensated (Kahan). */
BB_FN bb_scalar bb_lane_sum(real v, real c) {
    bb_scalar a[BB_VECTOR_WIDTH], b[BB_VECTOR_WIDTH];
    BB_CAT(vstore, BB_VECTOR_WIDTH)(v, 0, a);
    BB_CAT(vstore, BB_VECTOR_WIDTH)(c, 0, b);
    bb_scalar sum = 0, comp = 0;
    for (int k = 0; k < BB_VECTOR_WIDTH; ++k) {
        const bb_scalar y = (a[k] - b[k]) - comp;
        const bb_scalar t = sum + y;
        comp = (t - sum) - y;
        sum = t;
    }
    return sum;
}

__kernel void albedo_replicas_disk(__global const bb_scalar* cell_mu,
                                   __global const bb_scalar* cell_phi,
                                   __global const bb_scalar* model_p,
                                   __global const bb_scalar* fresnel_p,
                                   __global const bb_scalar* disk,   /* per replica: n_points / W
                                                                        chunks of W x then W y */
                                   const unsigned int n_points,      /* a multiple of W */
                                   const unsigned int n_replicas,
                                   const unsigned int n_cells,
                                   __global bb_scalar* replica_mean,
                                   __global unsigned int* bad_count)
{
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas)
        return;
    const unsigned int cell = gid / n_replicas;
    const unsigned int rep = gid - cell * n_replicas;

    bb_params p, fp;
    unsigned int params_ok = 1;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) {
        const bb_scalar a = model_p[cell * BB_MAX_PARAMS + k], b = fresnel_p[k];
        p.v[k] = (real)a;
        fp.v[k] = (real)b;
        params_ok &= (unsigned int)(isfinite(a) && isfinite(b));
    }
    const bb_vec3 wo = bb_dir_from_mu_phi((real)cell_mu[cell], (real)cell_phi[cell]);

    /* Kahan-compensated sums, one per lane. */
    real sum = BB_R(0.0), comp = BB_R(0.0);
    bb_mask bad = 0;
    const unsigned int n_chunks = n_points / BB_VECTOR_WIDTH;
    __global const bb_scalar* d = disk + (size_t)rep * n_chunks * (2 * BB_VECTOR_WIDTH);
    for (unsigned int c = 0; c < n_chunks; ++c, d += 2 * BB_VECTOR_WIDTH) {
        const bb_vec2 pt = bb_v2(bb_vload(d), bb_vload(d + BB_VECTOR_WIDTH));
        const bb_sample s = bb_model_sample_disk(BB_MODEL, p, BB_FRESNEL, fp, wo, pt);
        const bb_mask ok = isfinite(s.weight);
        bad += bb_select((bb_mask)1, (bb_mask)0, ok);
        const real y = bb_select(BB_R(0.0), s.weight, ok) - comp;
        const real t = sum + y;
        comp = (t - sum) - y;
        sum = t;
    }
    unsigned int n_bad = 0;
    {
        unsigned int nb[BB_VECTOR_WIDTH];
        BB_CAT(vstore, BB_VECTOR_WIDTH)(BB_CAT(convert_uint, BB_VECTOR_WIDTH)(bad), 0, nb);
        for (int k = 0; k < BB_VECTOR_WIDTH; ++k) n_bad += nb[k];
    }
    replica_mean[gid] = bb_lane_sum(sum, comp) / (bb_scalar)n_points;
    bad_count[gid] = params_ok ? n_bad : n_points;
}

#endif /* BB_VECTOR_WIDTH */

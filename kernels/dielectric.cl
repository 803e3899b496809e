/* Reflected and transmitted energy fractions of a rough GGX dielectric interface per cell
 * (mu_o, alpha, eta), one randomised-Hammersley replica per work-item, as kernels/albedo.cl
 * does for BRDFs. Two entry points from the one shared source (rough_dielectric.h):
 *   dielectric_replicas       scalar real, one sample per step (GPUs);
 *   dielectric_replicas_disk  -D BB_VECTOR_WIDTH=W, real a vector of W lanes: W samples per
 *                             step, their disk points read from the table the host fills once
 *                             for all cells (host/integrate/albedo.cpp, disk_table: W x, W y, W h per
 *                             step; h is not used here), as albedo_replicas_disk does.
 * Build options: [-D BB_REAL_DOUBLE] [-D BB_VECTOR_WIDTH=W]. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/brdf/sampling.h"

#ifndef BB_VECTOR_WIDTH

__kernel void BB_ENTRY_DIELECTRIC_REPLICAS(__global const real* cell_mu, __global const real* cell_alpha,
                                  __global const real* cell_eta, __global const real* shifts,
                                  const unsigned int n_points, const unsigned int n_replicas,
                                  const unsigned int n_cells, const int correlated,
                                  __global real* replica_r, __global real* replica_t,
                                  __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas)
        return;
    const unsigned int cell = gid / n_replicas;
    const unsigned int rep = gid - cell * n_replicas;
    const bb_vec3 wo = bb_dir_from_mu_phi(cell_mu[cell], BB_R(0.0));
    const real alpha = cell_alpha[cell], eta = cell_eta[cell];
    const real s1 = shifts[2 * rep], s2 = shifts[2 * rep + 1];
    real sr = BB_R(0.0), cr = BB_R(0.0), st = BB_R(0.0), ct = BB_R(0.0);
    unsigned int bad = 0;
    for (unsigned int i = 0; i < n_points; ++i) {
        const real u1 = bb_rotate(bb_hammersley_u1(i, n_points), s1);
        const real u2 = bb_rotate(bb_hammersley_u2(i), s2);
        const bb_rt s = bb_rough_dielectric_sample(wo, alpha, alpha, eta, correlated, u1, u2);
        const int ok = isfinite(s.r) && isfinite(s.t);
        bad += ok ? 0u : 1u;
        /* Kahan-compensated sums */
        real y = (ok ? s.r : BB_R(0.0)) - cr;
        real t = sr + y;
        cr = (t - sr) - y;
        sr = t;
        y = (ok ? s.t : BB_R(0.0)) - ct;
        t = st + y;
        ct = (t - st) - y;
        st = t;
    }
    replica_r[gid] = sr / (real)n_points;
    replica_t[gid] = st / (real)n_points;
    bad_count[gid] = bad;
}

#else /* BB_VECTOR_WIDTH */

/* The unroll hint is honoured when PoCL compiles the work-group function; silence the early
 * pass that cannot apply it (as kernels/albedo.cl). */
#pragma clang diagnostic ignored "-Wpass-failed"

__kernel void BB_ENTRY_DIELECTRIC_REPLICAS_DISK(__global const bb_scalar* cell_mu, __global const bb_scalar* cell_alpha,
                                       __global const bb_scalar* cell_eta,
                                       __global const bb_scalar* disk, /* per replica: n_points / W steps
                                                                          of W x, W y, W h */
                                       const unsigned int n_points,    /* a multiple of W */
                                       const unsigned int n_replicas, const unsigned int n_cells,
                                       const int correlated, __global bb_scalar* replica_r,
                                       __global bb_scalar* replica_t, __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas)
        return;
    const unsigned int cell = gid / n_replicas;
    const unsigned int rep = gid - cell * n_replicas;
    const bb_vec3 wo = bb_dir_from_mu_phi((real)cell_mu[cell], BB_R(0.0));
    const real alpha = (real)cell_alpha[cell], eta = (real)cell_eta[cell];
    /* Per lane: plain sums over blocks of BB_VECTOR_BLOCK steps, Kahan-compensated across blocks. */
    real sr = BB_R(0.0), cr = BB_R(0.0), st = BB_R(0.0), ct = BB_R(0.0);
    bb_mask bad = 0;
    const unsigned int n_steps = n_points / BB_VECTOR_WIDTH;
    __global const bb_scalar* d = disk + (size_t)rep * n_steps * (BB_DISK_VALUES * BB_VECTOR_WIDTH);
    for (unsigned int c0 = 0; c0 < n_steps; c0 += BB_VECTOR_BLOCK) {
        const unsigned int c1 = min(n_steps, c0 + BB_VECTOR_BLOCK);
        real br = BB_R(0.0), bt = BB_R(0.0);
        __attribute__((opencl_unroll_hint(2)))
        for (unsigned int c = c0; c < c1; ++c, d += BB_DISK_VALUES * BB_VECTOR_WIDTH) {
            const bb_vec2 pt = bb_v2(bb_vload(d), bb_vload(d + BB_VECTOR_WIDTH));
            const bb_rt s = bb_rough_dielectric_sample_disk(wo, alpha, alpha, eta, correlated, pt);
            const bb_mask ok = isfinite(s.r) && isfinite(s.t);
            bad += bb_select((bb_mask)1, (bb_mask)0, ok);
            br += bb_select(BB_R(0.0), s.r, ok);
            bt += bb_select(BB_R(0.0), s.t, ok);
        }
        real y = br - cr, t = sr + y;
        cr = (t - sr) - y;
        sr = t;
        y = bt - ct;
        t = st + y;
        ct = (t - st) - y;
        st = t;
    }
    const unsigned int n_bad = bb_lane_count(bad);
    replica_r[gid] = bb_lane_sum(sr, cr) / (bb_scalar)n_points;
    replica_t[gid] = bb_lane_sum(st, ct) / (bb_scalar)n_points;
    bad_count[gid] = n_bad;
}

#endif /* BB_VECTOR_WIDTH */

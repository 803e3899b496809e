/* Reflected and transmitted energy fractions of a rough GGX dielectric interface per cell
 * (mu_o, alpha, eta), one randomised-Hammersley replica per work-item, as kernels/albedo.cl
 * does for BRDFs. Two entry points from the one shared source (rough_dielectric.h):
 *   dielectric_replicas       scalar real, one sample per step (GPUs);
 *   dielectric_replicas_disk  -D BB_VECTOR_WIDTH=W, real a vector of W lanes: W samples per
 *                             step, their disk points read from the table the host fills once
 *                             for all cells (host/integrate/replicas.cpp, disk_table: W x, W y, W h per
 *                             step; h is not used here), as albedo_replicas_disk does.
 * And, built with -D BB_QUADRATURE -D BB_MODEL=<ggx's id> (a program of its own):
 *   dielectric_quadrature     the product rule in half-vector space (dielectric_quadrature.h),
 *                             one work-item per (cell, rule, piece): three Gauss-Legendre rules,
 *                             or (embedded) one Gauss-Kronrod rule whose work-item also sums its
 *                             embedded Gauss rule from the same nodes into the rule-1 slot.
 * Build options: [-D BB_REAL_DOUBLE] [-D BB_VECTOR_WIDTH=W] [-D BB_QUADRATURE -D BB_MODEL=id]. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/brdf/sampling.h"

#ifdef BB_QUADRATURE
#include "brdfbake/brdf/dielectric_quadrature.h"


/* The arguments of both quadrature kernels. */
#define BB_DIELECTRIC_QUADRATURE_ARGS                                                                  \
    __global const bb_scalar *cell_mu, __global const bb_scalar *cell_alpha,                           \
        __global const bb_scalar *cell_eta, __global const bb_scalar *nodes, const unsigned int n_fine, \
        const unsigned int n_coarse, const unsigned int n_coarsest, const unsigned int n_cells,         \
        const unsigned int embedded, const int shadowing, const int transmission_shadowing,             \
        __global bb_scalar *piece_r, __global bb_scalar *piece_t, __global unsigned int *bad_count


/* The prologue of both: work-item gid is (cell, rule, piece) (returns beyond the last, and for
 * rules 1 and 2 of an embedded pair, whose rule-0 item computes both); declares the rule's n
 * abscissae x and weights wt, the embedded rule's weights wg (0 at the nodes it lacks; only with
 * `embedded`), the cell's wo, a, eta, g1o, r_cap and the piece's azimuth interval az. */
#define BB_DIELECTRIC_QUADRATURE_PROLOGUE                                                              \
    const unsigned int gid = (unsigned int)get_global_id(0);                                           \
    if (gid >= n_cells * BB_QUAD_RULES * BB_DIELECTRIC_QUAD_PIECES)                                    \
        return;                                                                                        \
    const unsigned int cell = gid / (BB_QUAD_RULES * BB_DIELECTRIC_QUAD_PIECES);                       \
    const unsigned int rule = (gid / BB_DIELECTRIC_QUAD_PIECES) % BB_QUAD_RULES;                       \
    const unsigned int piece = gid % BB_DIELECTRIC_QUAD_PIECES;                                        \
    if (embedded != 0u && rule != 0u)                                                                  \
        return;                                                                                        \
    const unsigned int n = rule == 0u ? n_fine : (rule == 1u ? n_coarse : n_coarsest);                 \
    __global const bb_scalar* x = BB_QUAD_RULE_NODES(nodes, rule, n_fine, n_coarse);                   \
    __global const bb_scalar* wt = x + BB_QUAD_PADDED(n);                                              \
    __global const bb_scalar* wg = wt + BB_QUAD_PADDED(n);                                             \
    const bb_vec3 wo = bb_dir_from_mu_phi((bb_real)cell_mu[cell], BB_R(0.0));                            \
    const bb_real a = (bb_real)cell_alpha[cell], eta = (bb_real)cell_eta[cell];                                 \
    const bb_real g1o = bb_ggx_g1(wo, a, a), lo = bb_ggx_lambda(wo, a, a);                                \
    const bb_real lga_o =                                                                                 \
        bb_dielectric_beta_transmission(shadowing, transmission_shadowing) ? bb_lgamma(BB_R(1.0) + lo) \
                                                                           : BB_R(0.0);                \
    const bb_real r_cap = bb_dielectric_r_cap(wo, a);                                                     \
    const bb_interval az = bb_dielectric_piece(wo, eta, piece)

#ifndef BB_VECTOR_WIDTH

/* Work-item gid is (cell, rule, piece): rule 0 has n_fine nodes per axis, 1 n_coarse, 2
 * n_coarsest (the host's error estimate compares them); piece is the azimuth interval of
 * bb_dielectric_piece. `nodes` holds each rule's abscissae in [0, 1] and then its weights (summing
 * to 1), fine, coarse, coarsest, as for albedo_quadrature. Writes the piece's share of R and T
 * (counted twice: delta in [0, pi] stands for [-pi, pi]) and the number of non-finite nodes. */
__kernel void BB_ENTRY_DIELECTRIC_QUADRATURE(BB_DIELECTRIC_QUADRATURE_ARGS) {
    BB_DIELECTRIC_QUADRATURE_PROLOGUE;
    bb_real sr = BB_R(0.0), cr = BB_R(0.0), st = BB_R(0.0), ct = BB_R(0.0), gr = BB_R(0.0), gt = BB_R(0.0);
    unsigned int bad = 0;
    if (az.hi > az.lo) {
        for (unsigned int j = 0; j < n; ++j) {
            const bb_real delta = az.lo + (az.hi - az.lo) * bb_smoothstep(x[j]);
            const bb_real w_delta = BB_R(2.0) * (az.hi - az.lo) * bb_smoothstep_d(x[j]);
            const bb_dielectric_row row = bb_make_dielectric_row(wo, a, eta, r_cap, delta);
            bb_real rr = BB_R(0.0), rc = BB_R(0.0), tr = BB_R(0.0), tc = BB_R(0.0), er = BB_R(0.0), et = BB_R(0.0);
            for (int s = 0; s < BB_DIELECTRIC_QUAD_SEGMENTS; ++s) {
                const bb_real t0 = row.t[s], len = row.t[s + 1] - row.t[s];
                if (!(len > BB_R(0.0)))
                    continue;
                const int tail = row.t[s + 1] >= row.t[BB_DIELECTRIC_QUAD_SEGMENTS];
                for (unsigned int k = 0; k < n; ++k) {
                    const bb_segment_node node = bb_dielectric_segment_node(t0, len, tail, x[k]);
                    const bb_real jac = node.dt;
                    const bb_rt p = bb_dielectric_quad_point(wo, a, eta, shadowing, transmission_shadowing, g1o, lo, lga_o, row.cos_phi, row.sin_phi,
                                                             node.t);
                    const int ok = isfinite(p.r) && isfinite(p.t);
                    bad += ok ? 0u : 1u;
                    BB_KAHAN_ADD(rr, rc, ok ? wt[k] * jac * p.r : BB_R(0.0));
                    BB_KAHAN_ADD(tr, tc, ok ? wt[k] * jac * p.t : BB_R(0.0));
                    if (embedded != 0u && ok) {
                        er += wg[k] * jac * p.r;
                        et += wg[k] * jac * p.t;
                    }
                }
            }
            BB_KAHAN_ADD(sr, cr, wt[j] * w_delta * rr);
            BB_KAHAN_ADD(st, ct, wt[j] * w_delta * tr);
            if (embedded != 0u) {
                gr += wg[j] * w_delta * er;
                gt += wg[j] * w_delta * et;
            }
        }
    }
    piece_r[gid] = sr;
    piece_t[gid] = st;
    bad_count[gid] = bad;
    if (embedded != 0u) {
        piece_r[gid + BB_DIELECTRIC_QUAD_PIECES] = gr;
        piece_t[gid + BB_DIELECTRIC_QUAD_PIECES] = gt;
        bad_count[gid + BB_DIELECTRIC_QUAD_PIECES] = 0u;
        piece_r[gid + 2u * BB_DIELECTRIC_QUAD_PIECES] = BB_R(0.0); /* the unused rule-2 slot */
        piece_t[gid + 2u * BB_DIELECTRIC_QUAD_PIECES] = BB_R(0.0);
        bad_count[gid + 2u * BB_DIELECTRIC_QUAD_PIECES] = 0u;
    }
}

#else /* BB_VECTOR_WIDTH */

#pragma clang diagnostic ignored "-Wpass-failed"

/* The same rule with one row per lane: rows j0 .. j0 + W - 1 of the piece on the W lanes (their
 * azimuths, their segment ends), the radial nodes k one at a time for all W rows. The same nodes,
 * weights and functions as the scalar kernel, so the same sums to rounding. The node arrays are
 * padded to a multiple of W with weight 0: such lanes are neither summed nor counted. */
__kernel void BB_ENTRY_DIELECTRIC_QUADRATURE_ROWS(BB_DIELECTRIC_QUADRATURE_ARGS) {
    BB_DIELECTRIC_QUADRATURE_PROLOGUE;
    bb_real sr = BB_R(0.0), cr = BB_R(0.0), st = BB_R(0.0), ct = BB_R(0.0), gr = BB_R(0.0), gt = BB_R(0.0);
    bb_mask bad = 0;
    if (bb_all(az.hi > az.lo)) {
        for (unsigned int j0 = 0; j0 < n; j0 += BB_VECTOR_WIDTH) {
            const bb_real xj = bb_vload(x + j0), wj = bb_vload(wt + j0);
            const bb_mask live = wj > BB_R(0.0);
            const bb_real delta = az.lo + (az.hi - az.lo) * bb_smoothstep(xj);
            const bb_real w_delta = BB_R(2.0) * (az.hi - az.lo) * bb_smoothstep_d(xj);
            const bb_dielectric_row row = bb_make_dielectric_row(wo, a, eta, r_cap, delta);
            bb_real rr = BB_R(0.0), rc = BB_R(0.0), tr = BB_R(0.0), tc = BB_R(0.0), er = BB_R(0.0), et = BB_R(0.0);
            for (int s = 0; s < BB_DIELECTRIC_QUAD_SEGMENTS; ++s) {
                const bb_real t0 = row.t[s], len = row.t[s + 1] - row.t[s];
                const bb_mask on = live & (len > BB_R(0.0));
                if (bb_all(!on))
                    continue;
                const bb_mask tail = row.t[s + 1] >= row.t[BB_DIELECTRIC_QUAD_SEGMENTS];
                for (unsigned int k = 0; k < n; ++k) {
                    const bb_segment_node node = bb_dielectric_segment_node(t0, len, tail, (bb_real)x[k]);
                    const bb_real jac = node.dt;
                    const bb_rt p = bb_dielectric_quad_point(wo, a, eta, shadowing, transmission_shadowing, g1o, lo, lga_o, row.cos_phi, row.sin_phi,
                                                             node.t);
                    const bb_mask ok = isfinite(p.r) & isfinite(p.t);
                    bad += bb_select((bb_mask)0, (bb_mask)1, on & ~ok);
                    const bb_real pr = bb_select(BB_R(0.0), jac * p.r, on & ok), pt = bb_select(BB_R(0.0), jac * p.t, on & ok);
                    BB_KAHAN_ADD(rr, rc, (bb_real)wt[k] * pr);
                    BB_KAHAN_ADD(tr, tc, (bb_real)wt[k] * pt);
                    if (embedded != 0u) {
                        er += (bb_real)wg[k] * pr;
                        et += (bb_real)wg[k] * pt;
                    }
                }
            }
            BB_KAHAN_ADD(sr, cr, bb_select(BB_R(0.0), wj * w_delta * rr, live));
            BB_KAHAN_ADD(st, ct, bb_select(BB_R(0.0), wj * w_delta * tr, live));
            if (embedded != 0u) {
                const bb_real gj = bb_vload(wg + j0);
                gr += bb_select(BB_R(0.0), gj * w_delta * er, live);
                gt += bb_select(BB_R(0.0), gj * w_delta * et, live);
            }
        }
    }
    piece_r[gid] = bb_lane_sum(sr, cr);
    piece_t[gid] = bb_lane_sum(st, ct);
    bad_count[gid] = bb_lane_count(bad);
    if (embedded != 0u) {
        piece_r[gid + BB_DIELECTRIC_QUAD_PIECES] = bb_lane_sum(gr, BB_R(0.0));
        piece_t[gid + BB_DIELECTRIC_QUAD_PIECES] = bb_lane_sum(gt, BB_R(0.0));
        bad_count[gid + BB_DIELECTRIC_QUAD_PIECES] = 0u;
        piece_r[gid + 2u * BB_DIELECTRIC_QUAD_PIECES] = (bb_scalar)0; /* the unused rule-2 slot */
        piece_t[gid + 2u * BB_DIELECTRIC_QUAD_PIECES] = (bb_scalar)0;
        bad_count[gid + 2u * BB_DIELECTRIC_QUAD_PIECES] = 0u;
    }
}

#endif /* BB_VECTOR_WIDTH */

#elif !defined(BB_VECTOR_WIDTH)

__kernel void BB_ENTRY_DIELECTRIC_REPLICAS(__global const bb_real* cell_mu, __global const bb_real* cell_alpha,
                                  __global const bb_real* cell_eta, __global const bb_real* shifts,
                                  const unsigned int n_points, const unsigned int n_replicas,
                                  const unsigned int n_cells, const int shadowing,
                                  const int transmission_shadowing, __global bb_real* replica_r,
                                  __global bb_real* replica_t,
                                  __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas)
        return;
    const unsigned int cell = gid / n_replicas;
    const unsigned int rep = gid - cell * n_replicas;
    const bb_vec3 wo = bb_dir_from_mu_phi(cell_mu[cell], BB_R(0.0));
    const bb_real alpha = cell_alpha[cell], eta = cell_eta[cell];
    const bb_real s1 = shifts[2 * rep], s2 = shifts[2 * rep + 1];
    bb_real sr = BB_R(0.0), cr = BB_R(0.0), st = BB_R(0.0), ct = BB_R(0.0);
    unsigned int bad = 0;
    for (unsigned int i = 0; i < n_points; ++i) {
        const bb_real u1 = bb_rotate(bb_hammersley_u1(i, n_points), s1);
        const bb_real u2 = bb_rotate(bb_hammersley_u2(i), s2);
        const bb_rt s = bb_rough_dielectric_sample(wo, alpha, alpha, eta, shadowing, transmission_shadowing, u1, u2);
        const int ok = isfinite(s.r) && isfinite(s.t);
        bad += ok ? 0u : 1u;
        /* Kahan-compensated sums */
        bb_real y = (ok ? s.r : BB_R(0.0)) - cr;
        bb_real t = sr + y;
        cr = (t - sr) - y;
        sr = t;
        y = (ok ? s.t : BB_R(0.0)) - ct;
        t = st + y;
        ct = (t - st) - y;
        st = t;
    }
    replica_r[gid] = sr / (bb_real)n_points;
    replica_t[gid] = st / (bb_real)n_points;
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
                                       const int shadowing, const int transmission_shadowing,
                                       __global bb_scalar* replica_r,
                                       __global bb_scalar* replica_t, __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas)
        return;
    const unsigned int cell = gid / n_replicas;
    const unsigned int rep = gid - cell * n_replicas;
    const bb_vec3 wo = bb_dir_from_mu_phi((bb_real)cell_mu[cell], BB_R(0.0));
    const bb_real alpha = (bb_real)cell_alpha[cell], eta = (bb_real)cell_eta[cell];
    /* Per lane: plain sums over blocks of BB_VECTOR_BLOCK steps, Kahan-compensated across blocks. */
    bb_real sr = BB_R(0.0), cr = BB_R(0.0), st = BB_R(0.0), ct = BB_R(0.0);
    bb_mask bad = 0;
    const unsigned int n_steps = n_points / BB_VECTOR_WIDTH;
    __global const bb_scalar* d = disk + (size_t)rep * n_steps * (BB_DISK_VALUES * BB_VECTOR_WIDTH);
    for (unsigned int c0 = 0; c0 < n_steps; c0 += BB_VECTOR_BLOCK) {
        const unsigned int c1 = min(n_steps, c0 + BB_VECTOR_BLOCK);
        bb_real br = BB_R(0.0), bt = BB_R(0.0);
        __attribute__((opencl_unroll_hint(2)))
        for (unsigned int c = c0; c < c1; ++c, d += BB_DISK_VALUES * BB_VECTOR_WIDTH) {
            const bb_vec2 pt = bb_v2(bb_vload(d), bb_vload(d + BB_VECTOR_WIDTH));
            const bb_rt s = bb_rough_dielectric_sample_disk(wo, alpha, alpha, eta, shadowing, transmission_shadowing, pt);
            const bb_mask ok = isfinite(s.r) && isfinite(s.t);
            bad += bb_select((bb_mask)1, (bb_mask)0, ok);
            br += bb_select(BB_R(0.0), s.r, ok);
            bt += bb_select(BB_R(0.0), s.t, ok);
        }
        bb_real y = br - cr, t = sr + y;
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

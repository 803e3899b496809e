/* Directional albedo E(wo) = integral of f(wo, wi) cos(theta_i) over the upper hemisphere.
 *
 * The methods (--method), all from the one shared source:
 *   importance  the model's importance sampler (bb_model_sample: visible normals for GGX and
 *               Beckmann, the cosine for Lambert and Oren-Nayar, the lobe for Phong and Blinn)
 *               driven by a randomised Hammersley set;
 *   qmc         uniform hemisphere sampling (integrands.h) driven by the same point sets;
 *   mc          uniform hemisphere sampling driven by Philox4x32-10 (Random123, -D BB_PHILOX);
 *   quadrature  a Gauss-Legendre product rule (integrands.h), kernel albedo_quadrature.
 * The sampling methods run replicas: each work-item computes one replica of one cell (its own
 * Cranley-Patterson shift, or its own Philox stream) and the host turns the replicas into the
 * mean and its standard error. Non-finite weights are counted, never summed, so that a NaN
 * cannot hide in a table.
 *
 * Two entry points for the sampling methods, chosen by the build options (Engine::build_options):
 *   albedo_replicas       scalar real: one sample per step (GPUs, every method and model);
 *   albedo_replicas_disk  -D BB_VECTOR_WIDTH=W, real a vector of W lanes: importance sampling
 *                         with W samples per step, their disk points bb_disk_polar(u1, u2) and
 *                         sqrt(1 - x^2) read from a table that the host fills once for all cells
 *                         (they do not depend on the cell), the weight in the model's closed form
 *                         (bb_model_disk_weight). Same point set, same shifts, same estimator;
 *                         PoCL compiles it to SIMD code;
 *   albedo_replicas_points  -D BB_VECTOR_WIDTH=W -D BB_VECTOR_POINTS: the same for the other
 *                         models with a branch-free sampler (bb_model_samples_vector), the
 *                         rotated Hammersley points (u1, u2) read from a table in the kernel's
 *                         precision and bb_model_sample evaluated on W lanes; with
 *                         -D BB_VECTOR_UNIFORM the qmc method (uniform hemisphere weights,
 *                         bb_model_evals_vector) on the same points.
 * And two for quadrature (-D BB_QUADRATURE):
 *   albedo_quadrature       scalar real: every rule (GPUs, and the sampler's square of models
 *                           whose sampler has branches);
 *   albedo_quadrature_rows  -D BB_VECTOR_WIDTH=W: the half-vector rule, or with
 *                           -D BB_QUAD_SAMPLER_ROWS the sampler's square (lambert, oren-nayar,
 *                           phong, sheen), with W rows per step, one per lane (same nodes, same
 *                           functions, the same sums to rounding).
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE] [-D BB_VECTOR_WIDTH=W
 * [-D BB_ISOTROPIC=1 | -D BB_VECTOR_POINTS=1 [-D BB_VECTOR_UNIFORM=1] | -D BB_QUAD_SAMPLER_ROWS=1]]
 * [-D BB_PHILOX -I <Random123's include directory>] [-D BB_QUADRATURE: the quadrature kernel
 * alone, a smaller program to build]. */
/* compute_albedo integrates a Smith lobe's specular part alone and adds diffuse=KD's kd in closed
 * form (host/integrate/albedo.cpp): the lobe's sampler, without the mixture's test (smith.h). */
#define BB_SMITH_LOBE_SAMPLER_ONLY
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/sampling.h"

#if !defined(BB_VECTOR_WIDTH) || defined(BB_QUADRATURE) || defined(BB_VECTOR_UNIFORM)
#include "brdfbake/brdf/integrands.h"
#endif


/* Reads the cell's parameters (into every lane of a vector build); 0 if any is not finite. A
 * non-finite parameter would hide behind the models' guards (x > 0 is false for NaN) and turn
 * into zero weights: the kernels count every sample of such a cell as non-finite instead. */
BB_FN unsigned int bb_read_params(__global const bb_scalar* model_p, __global const bb_scalar* fresnel_p,
                                  unsigned int cell, bb_params* p, bb_params* fp) {
    unsigned int ok = 1;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) {
        const bb_scalar a = model_p[cell * BB_MAX_PARAMS + k], b = fresnel_p[k];
        p->v[k] = (bb_real)a;
        fp->v[k] = (bb_real)b;
        ok &= (unsigned int)(isfinite(a) && isfinite(b));
    }
    return ok;
}

/* The first arguments of every albedo kernel: per cell cos(theta_o), phi_o (radians) and
 * BB_MAX_PARAMS model parameters; the BB_MAX_PARAMS Fresnel parameters of the launch. */
#define BB_CELL_ARGS                                                                              \
    __global const bb_scalar *cell_mu, __global const bb_scalar *cell_phi,                        \
        __global const bb_scalar *model_p, __global const bb_scalar *fresnel_p,                   \
        __global const bb_scalar *model_data /* BB_MODEL_DATA_ARG */

/* The prologue of the replica kernels: work-item gid is replica `rep` of cell `cell` (returns
 * beyond the last); declares gid, cell, rep, the cell's parameters p, fp (params_ok) and wo. */
#define BB_REPLICA_PROLOGUE                                                                       \
    const unsigned int gid = (unsigned int)get_global_id(0);                                      \
    if (gid >= n_cells * n_replicas)                                                              \
        return;                                                                                   \
    const unsigned int cell = gid / n_replicas;                                                   \
    const unsigned int rep = gid - cell * n_replicas;                                             \
    bb_params p, fp;                                                                              \
    const unsigned int params_ok = bb_read_params(model_p, fresnel_p, cell, &p, &fp);             \
    p.data = model_data;                                                                          \
    fp.data = model_data;                                                                         \
    const bb_vec3 wo = bb_dir_from_mu_phi((bb_real)cell_mu[cell], (bb_real)cell_phi[cell])

#ifdef BB_QUADRATURE

/* The arguments of both quadrature kernels (albedo_quadrature, albedo_quadrature_rows): `nodes`
 * holds the fine rule's n_fine abscissae in [0, 1], then its weights (summing to 1), then the
 * same for the coarse and the coarsest rule, each array padded to BB_QUAD_PADDED of its length;
 * piece_sum and bad_count have n_cells * BB_QUAD_SLOTS entries. */
#define BB_QUADRATURE_ARGS                                                                        \
    BB_CELL_ARGS, __global const bb_scalar *nodes, const unsigned int n_fine,                     \
        const unsigned int n_coarse, const unsigned int n_coarsest, const unsigned int n_cells,   \
        __global bb_scalar *piece_sum, __global unsigned int *bad_count


/* The prologue of the quadrature kernels: work-item gid is (cell, rule, piece) (returns beyond
 * the last): rule 0 has n_fine nodes per axis, rule 1 n_coarse, rule 2 n_coarsest (the error
 * estimate compares the three); piece 2k + h is half h of the quarter q = k of azimuth offsets
 * (bb_quad_azimuth_node; in the sampler's square the quarter of u2). Declares gid, cell, piece,
 * q, the rule's n abscissae x and weights wt, the cell's p, fp (params_ok), phi_o, wo, dist
 * and copies. Mirror symmetry (bb_quad_mirrored): quarters 0 and 1 count twice (copies = 2),
 * 2 and 3 are empty; so are the halves h = 1 in the sampler's square and where
 * bb_quad_azimuth_node gives no width. An empty piece writes 0 and returns. */
#define BB_QUADRATURE_PROLOGUE                                                                    \
    const unsigned int gid = (unsigned int)get_global_id(0);                                      \
    if (gid >= n_cells * BB_QUAD_SLOTS)                                                           \
        return;                                                                                   \
    const unsigned int cell = gid / BB_QUAD_SLOTS, rule = (gid / BB_QUAD_PIECES) % BB_QUAD_RULES, \
                       piece = gid % BB_QUAD_PIECES, q = piece >> 1;                              \
    const unsigned int n = rule == 0u ? n_fine : (rule == 1u ? n_coarse : n_coarsest);           \
    __global const bb_scalar* x = BB_QUAD_RULE_NODES(nodes, rule, n_fine, n_coarse);              \
    __global const bb_scalar* wt = x + BB_QUAD_PADDED(n);                                         \
    bb_params p, fp;                                                                              \
    const unsigned int params_ok = bb_read_params(model_p, fresnel_p, cell, &p, &fp);             \
    p.data = model_data;                                                                          \
    fp.data = model_data;                                                                         \
    const bb_real phi_o = (bb_real)cell_phi[cell];                                                      \
    const bb_vec3 wo = bb_dir_from_mu_phi((bb_real)cell_mu[cell], phi_o);                            \
    const bb_quad_dist dist = bb_model_quad_dist(BB_MODEL, p);                                    \
    const int mirrored = bb_quad_mirrored(BB_MODEL, p, dist, phi_o);                              \
    BB_QUAD_SPLITS;                                                                               \
    if (bb_quad_piece_empty(BB_MODEL, p, dist, phi_o, piece, kink_delta)) {                         \
        piece_sum[gid] = 0;                                                                       \
        bad_count[gid] = 0u;                                                                      \
        return;                                                                                   \
    }                                                                                             \
    const bb_scalar copies = mirrored ? 2 : 1

/* The kinks each row is split at (integrands.h): `cone`, the sampler's u1 of the mirror cone
 * u_cone (BB_TRAIT_MIRROR_CONE); in half-vector space `cusp`, the Fresnel term's cusp at
 * wo.h = 1, and kink_cos, the cosine where its weight leaves 0 (per row, bb_quad_row_cuts):
 * n_parts parts of the row. Each part gets the rule's n nodes. kink_delta: the azimuth where
 * rows stop crossing kink_cos, which cuts each quarter of an isotropic lobe (bb_quad_kink_delta). */
#define BB_QUAD_SPLITS                                                                            \
    const int cone = dist.kind == BB_QUAD_SAMPLER && bb_model_has_trait(BB_MODEL, BB_TRAIT_MIRROR_CONE); \
    const bb_real u_cone = cone ? bb_quad_sampler_cone_u1(BB_MODEL, p, BB_FRESNEL, fp, wo) : BB_R(1.0); \
    const int cusp = dist.kind != BB_QUAD_SAMPLER && bb_quad_fresnel_cusp(BB_FRESNEL, fp);       \
    const bb_real kink_cos = bb_quad_cell_kink_cos(dist, BB_FRESNEL, fp);                        \
    const int n_parts = 1 + cusp + (bb_all(kink_cos > BB_R(0.0)) ? 2 : 0);                      \
    const bb_real kink_delta = bb_quad_kink_delta(wo, kink_cos)


/* One half-vector row r at azimuth offset delta (bb_make_quad_row), t over [0, t_max] cut at the
 * Fresnel term's cusp and kinks (BB_QUAD_SPLITS: cusp, kink_cos, n_parts), the rule's n nodes on
 * each part: the row's sum; the live lanes' non-finite points (skipped) are added to *bad. Shared
 * by the scalar kernel (live = 1) and the rows kernel (one row per lane). */
BB_FN bb_real bb_quad_halfvector_row(bb_params p, bb_params fp, bb_vec3 wo, bb_quad_dist dist, bb_quad_row r,
                                     bb_real delta, int cusp, bb_real kink_cos, int n_parts,
                                     __global const bb_scalar* x, __global const bb_scalar* wt, unsigned int n,
                                     bb_mask live, bb_mask* bad) {
    bb_real row = BB_R(0.0), row_comp = BB_R(0.0);
    bb_real cut[3];
    bb_quad_row_cuts(r, wo, delta, cusp, kink_cos, cut);
    for (int part = 0; part < n_parts; ++part) {
        const bb_quad_part pt = bb_quad_row_part(cut, n_parts, part, r.t_max);
        for (unsigned int k = 0; k < n; ++k) {
            const bb_real w = bb_quad_halfvector_point(BB_MODEL, p, BB_FRESNEL, fp, wo, dist, r, pt.lo + pt.len * x[k]);
            const bb_mask ok = isfinite(w);
            *bad += bb_select((bb_mask)0, (bb_mask)1, live & ~ok);
            BB_KAHAN_ADD(row, row_comp, bb_select(BB_R(0.0), pt.len * wt[k] * w, ok));
        }
    }
    return row;
}
#endif /* BB_QUADRATURE */

#ifndef BB_VECTOR_WIDTH

#ifdef BB_PHILOX
#include <Random123/philox.h>
#endif

#ifndef BB_QUADRATURE

__kernel void BB_ENTRY_ALBEDO_REPLICAS(BB_CELL_ARGS,
                              __global const bb_real* shifts,     /* 2 per replica */
                              const unsigned int n_points,     /* points per replica */
                              const unsigned int n_replicas,
                              const unsigned int n_cells,
                              const int method,                /* BB_METHOD_* */
                              const unsigned int seed_lo,      /* Philox key (mc) */
                              const unsigned int seed_hi,
                              __global const unsigned int* cell_stream, /* mc: each cell's stream */
                              __global bb_real* replica_mean,     /* n_cells * n_replicas */
                              __global unsigned int* bad_count) /* n_cells * n_replicas */
{
    BB_REPLICA_PROLOGUE;
    const bb_real s1 = shifts[2 * rep], s2 = shifts[2 * rep + 1];
#ifdef BB_PHILOX
    philox4x32_key_t key = {{seed_lo, seed_hi}};
#endif

    bb_real sum = BB_R(0.0), comp = BB_R(0.0);
    unsigned int bad = 0;
    for (unsigned int i = 0; i < n_points; ++i) {
        bb_real u1, u2;
#ifdef BB_PHILOX
        if (method == BB_METHOD_MC) {
            /* Counter (point, replica, cell stream, "albd"): every sample its own stream position;
             * the stream is the cell's identity from its content (the host's cell_identity), so
             * that a cell's value does not depend on the other cells of the launch. */
            philox4x32_ctr_t ctr = {{i, rep, cell_stream[cell], 0x616c6264u}};
            philox4x32_ctr_t r = philox4x32(ctr, key);
            u1 = bb_unit_from_bits(r.v[0]);
            u2 = bb_unit_from_bits(r.v[1]);
        } else
#endif
        {
            u1 = bb_rotate(bb_hammersley_u1(i, n_points), s1);
            u2 = bb_rotate(bb_hammersley_u2(i), s2);
        }
        const bb_real w = bb_albedo_point_weight(method, BB_MODEL, p, BB_FRESNEL, fp, wo, u1, u2);
        const int ok = isfinite(w);
        bad += ok ? 0u : 1u;
        BB_KAHAN_ADD(sum, comp, ok ? w : BB_R(0.0));
    }
    replica_mean[gid] = sum / (bb_real)n_points;
    bad_count[gid] = params_ok ? bad : n_points;
}

#else /* BB_QUADRATURE */

/* Gauss-Legendre product quadrature (integrands.h), one work-item per (cell, rule, piece)
 * (BB_QUADRATURE_PROLOGUE). Writes the piece's share of E; the host adds the pieces. */
__kernel void BB_ENTRY_ALBEDO_QUADRATURE(BB_QUADRATURE_ARGS) {
    BB_QUADRATURE_PROLOGUE;

    bb_real sum = BB_R(0.0), comp = BB_R(0.0);
    unsigned int bad = 0;
    for (unsigned int j = 0; j < n; ++j) {
        const bb_real s = ((bb_real)q + x[j]) * BB_R(0.25); /* fraction of the full turn */
        bb_real row = BB_R(0.0), row_comp = BB_R(0.0), scale;
        if (dist.kind == BB_QUAD_SAMPLER) {
            if (bb_quad_sampler_is_cosine(BB_MODEL)) {
                const bb_real cos_s = bb_cos(BB_2PI * s), sin_s = bb_sin(BB_2PI * s);
                /* c = cos(theta_i) over [0, mu_o] and [mu_o, 1]; u1 = 1 - c^2, du1 = 2c dc */
                for (int piece = 0; piece < 2; ++piece) {
                    const bb_real lo = piece == 0 ? BB_R(0.0) : wo.z, len = piece == 0 ? wo.z : BB_R(1.0) - wo.z;
                    for (unsigned int k = 0; k < n; ++k) {
                        /* wi from c directly (not through u1 = 1 - c^2, which rounds to 1
                         * for c < 2.4e-4 in float): the weight is pi f, the pdf being c/pi */
                        const bb_real c = lo + len * x[k];
                        const bb_real sn = bb_safe_sqrt(bb_sin2_from_cos(c));
                        const bb_vec3 wi = bb_v3(sn * cos_s, sn * sin_s, c);
                        const bb_real w = BB_PI * bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, wi);
                        const int ok = isfinite(w);
                        bad += ok ? 0u : 1u;
                        BB_KAHAN_ADD(row, row_comp, ok ? BB_R(2.0) * c * len * wt[k] * w : BB_R(0.0));
                    }
                }
            } else {
                /* u1 over [0, u_cone] and [u_cone, 1] for a mirror cone (BB_QUAD_SPLITS), else [0, 1] */
                for (int part = 0; part < 1 + cone; ++part) {
                    const bb_real lo = part == 0 ? BB_R(0.0) : u_cone, len = part == 0 ? u_cone : BB_R(1.0) - u_cone;
                    for (unsigned int k = 0; k < n; ++k) {
                        const bb_real w = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, lo + len * x[k], s).weight;
                        const int ok = isfinite(w);
                        bad += ok ? 0u : 1u;
                        BB_KAHAN_ADD(row, row_comp, ok ? len * wt[k] * w : BB_R(0.0));
                    }
                }
            }
            scale = BB_R(0.25);
        } else {
            const bb_quad_azimuth az = bb_quad_azimuth_node(dist, phi_o, piece, x[j], kink_delta);
            const bb_quad_row r = bb_make_quad_row(dist, wo, phi_o, az.delta);
            bb_mask row_bad = 0;
            row = bb_quad_halfvector_row(p, fp, wo, dist, r, az.delta, cusp, kink_cos, n_parts, x, wt, n, 1, &row_bad);
            bad += (unsigned int)row_bad;
            scale = az.ddelta; /* pi/2 for a whole quarter in delta */
        }
        BB_KAHAN_ADD(sum, comp, wt[j] * scale * row);
    }
    piece_sum[gid] = copies * sum;
    bad_count[gid] = params_ok ? bad : n * n;
}

#endif /* BB_QUADRATURE */

#else /* BB_VECTOR_WIDTH */

/* The unroll hint below is honoured when PoCL compiles the work-group function; the earlier
 * clBuildProgram pass cannot apply it and would print "loop not unrolled" on every cold build. */
#pragma clang diagnostic ignored "-Wpass-failed"

/* -D BB_ISOTROPIC=1: every cell of the launch is isotropic (bb_model_disk_isotropic). */
#ifndef BB_ISOTROPIC
#define BB_ISOTROPIC 0
#endif

#ifdef BB_QUADRATURE

/* The rules of albedo_quadrature (the half-vector rule of ggx, beckmann, torrance-sparrow,
 * blinn-phong; with -D BB_QUAD_SAMPLER_ROWS the sampler's square) with one row of the rule per lane: work-item (cell, rule, piece) as there, its rows j taken W at a
 * time (lane l is row j0 + l: its azimuth node, bb_quad_azimuth_node and bb_make_quad_row in
 * vector form), and the radial nodes k one at a time for all W rows (t = t_max(row) x[k]). The
 * same nodes, weights and functions as the scalar kernel, so the same sum to rounding. Each
 * array of `nodes` is padded to a multiple of W (BB_QUAD_PADDED), the padding with weight 0 (and
 * abscissa 1/2): such lanes are neither summed nor counted. */
__kernel void BB_ENTRY_ALBEDO_QUADRATURE_ROWS(BB_QUADRATURE_ARGS) {
    BB_QUADRATURE_PROLOGUE;

    bb_real sum = BB_R(0.0), comp = BB_R(0.0);
    bb_mask bad = 0;
#ifdef BB_QUAD_SAMPLER_ROWS
    /* -D BB_QUAD_SAMPLER_ROWS: the sampler's unit square, for the models whose sampler and
     * evaluation are branch-free (the host defines it for them only): lane l is
     * the row u2 = s of abscissa j0 + l, as in albedo_quadrature; the nodes u1 (or c) one at a
     * time for all W rows. */
    for (unsigned int j0 = 0; j0 < n; j0 += BB_VECTOR_WIDTH) {
        const bb_real xj = bb_vload(x + j0), wj = bb_vload(wt + j0);
        const bb_mask live = wj > BB_R(0.0);
        const bb_real s = ((bb_real)q + xj) * BB_R(0.25); /* fraction of the full turn */
        bb_real row = BB_R(0.0), row_comp = BB_R(0.0);
        if (bb_quad_sampler_is_cosine(BB_MODEL)) {
            const bb_real cos_s = bb_cos(BB_2PI * s), sin_s = bb_sin(BB_2PI * s);
            for (int part = 0; part < 2; ++part) {
                const bb_real lo = part == 0 ? BB_R(0.0) : wo.z, len = part == 0 ? wo.z : BB_R(1.0) - wo.z;
                for (unsigned int k = 0; k < n; ++k) {
                    const bb_real c = lo + len * (bb_real)x[k];
                    const bb_real sn = bb_safe_sqrt(bb_sin2_from_cos(c));
                    const bb_vec3 wi = bb_v3(sn * cos_s, sn * sin_s, c);
                    const bb_real w = BB_PI * bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, wi);
                    const bb_mask ok = isfinite(w);
                    bad += bb_select((bb_mask)0, (bb_mask)1, live & ~ok);
                    BB_KAHAN_ADD(row, row_comp, bb_select(BB_R(0.0), BB_R(2.0) * c * len * (bb_real)wt[k] * w, ok));
                }
            }
        } else {
            for (int part = 0; part < 1 + cone; ++part) {
                const bb_real lo = part == 0 ? BB_R(0.0) : u_cone, len = part == 0 ? u_cone : BB_R(1.0) - u_cone;
                for (unsigned int k = 0; k < n; ++k) {
                    const bb_real w = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, lo + len * (bb_real)x[k], s).weight;
                    const bb_mask ok = isfinite(w);
                    bad += bb_select((bb_mask)0, (bb_mask)1, live & ~ok);
                    BB_KAHAN_ADD(row, row_comp, bb_select(BB_R(0.0), len * (bb_real)wt[k] * w, ok));
                }
            }
        }
        BB_KAHAN_ADD(sum, comp, bb_select(BB_R(0.0), wj * BB_R(0.25) * row, live));
    }
#else
    for (unsigned int j0 = 0; j0 < n; j0 += BB_VECTOR_WIDTH) {
        const bb_real xj = bb_vload(x + j0), wj = bb_vload(wt + j0);
        const bb_mask live = wj > BB_R(0.0);
        const bb_quad_azimuth az = bb_quad_azimuth_node(dist, phi_o, piece, xj, kink_delta);
        const bb_quad_row r = bb_make_quad_row(dist, wo, phi_o, az.delta);
        /* Not unrolled (bb_quad_halfvector_row): 4x unrolling saved ~15% of this loop's time (5-7 ms
         * of the 64x64 table at --tolerance 1e-5) but cost ~0.1 s more of PoCL's cold compile. */
        const bb_real row = bb_quad_halfvector_row(p, fp, wo, dist, r, az.delta, cusp, kink_cos, n_parts, x, wt, n, live, &bad);
        const bb_real scale = az.ddelta;
        BB_KAHAN_ADD(sum, comp, bb_select(BB_R(0.0), wj * scale * row, live));
    }
#endif
    const unsigned int n_bad = bb_lane_count(bad);
    piece_sum[gid] = copies * bb_lane_sum(sum, comp);
    bad_count[gid] = params_ok ? n_bad : n * n;
}

#else /* BB_QUADRATURE */

/* Two vector entry points from one body:
 *   albedo_replicas_disk    (GGX) the table holds W x, W y, W h of the disk points per step and
 *                           the weight is the model's closed form (bb_model_disk_weight);
 *   albedo_replicas_points  (-D BB_VECTOR_POINTS: the other models with a branch-free sampler,
 *                           bb_model_samples_vector) the table holds W u1, W u2 of the rotated
 *                           Hammersley points per step and the weight is bb_model_sample's. */
#ifdef BB_VECTOR_POINTS
#define BB_VECTOR_KERNEL BB_ENTRY_ALBEDO_REPLICAS_POINTS
#define BB_STEP (BB_POINTS_VALUES * BB_VECTOR_WIDTH)
#else
#define BB_VECTOR_KERNEL BB_ENTRY_ALBEDO_REPLICAS_DISK
#define BB_STEP (BB_DISK_VALUES * BB_VECTOR_WIDTH)
#endif

__kernel void BB_VECTOR_KERNEL(BB_CELL_ARGS,
                               __global const bb_scalar* disk, /* per replica: n_points / W steps of BB_STEP values */
                               const unsigned int n_points,    /* a multiple of W */
                               const unsigned int n_replicas,
                               const unsigned int n_cells,
                               __global bb_scalar* replica_mean,
                               __global unsigned int* bad_count) {
    BB_REPLICA_PROLOGUE;
#ifndef BB_VECTOR_POINTS
    const bb_disk_cell dc = bb_model_disk_cell(BB_MODEL, p, wo, BB_ISOTROPIC);
#endif

    /* Per lane: plain sums over blocks of BB_VECTOR_BLOCK steps (at most 32 terms, exact to a few
     * ulps), the blocks added with Kahan compensation (no loop-carried compensation per sample). */
    bb_real sum = BB_R(0.0), comp = BB_R(0.0);
    bb_mask bad = 0;
    const unsigned int n_chunks = n_points / BB_VECTOR_WIDTH;
    __global const bb_scalar* d = disk + (size_t)rep * n_chunks * BB_STEP;
    for (unsigned int c0 = 0; c0 < n_chunks; c0 += BB_VECTOR_BLOCK) {
        const unsigned int c1 = min(n_chunks, c0 + BB_VECTOR_BLOCK);
        bb_real block = BB_R(0.0);
        /* Unrolled: the body is one long dependency chain (two square roots and a division
         * in sequence), and four independent steps in flight keep the units busy (issue 9:
         * x1.35 in float, x1.3 in double on the development machine; 8 gave no more). */
        __attribute__((opencl_unroll_hint(4)))
        for (unsigned int c = c0; c < c1; ++c, d += BB_STEP) {
#if defined(BB_VECTOR_POINTS) && defined(BB_VECTOR_UNIFORM)
            const bb_real w = bb_uniform_hemisphere_weight(BB_MODEL, p, BB_FRESNEL, fp, wo, bb_vload(d), bb_vload(d + BB_VECTOR_WIDTH));
#elif defined(BB_VECTOR_POINTS)
            const bb_real w = bb_model_sample(BB_MODEL, p, BB_FRESNEL, fp, wo, bb_vload(d), bb_vload(d + BB_VECTOR_WIDTH)).weight;
#else
            const bb_vec2 pt = bb_v2(bb_vload(d), bb_vload(d + BB_VECTOR_WIDTH));
            const bb_real w = bb_model_disk_weight(BB_MODEL, dc, BB_FRESNEL, fp, pt, bb_vload(d + 2 * BB_VECTOR_WIDTH),
                                                BB_ISOTROPIC);
#endif
            const bb_mask ok = isfinite(w);
            bad += bb_select((bb_mask)1, (bb_mask)0, ok);
            block += bb_select(BB_R(0.0), w, ok);
        }
        BB_KAHAN_ADD(sum, comp, block);
    }
    const unsigned int n_bad = bb_lane_count(bad);
    replica_mean[gid] = bb_lane_sum(sum, comp) / (bb_scalar)n_points;
    bad_count[gid] = params_ok ? n_bad : n_points;
}

#endif /* BB_QUADRATURE */

#endif /* BB_VECTOR_WIDTH */

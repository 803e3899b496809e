/* Directional albedo of the multiple-scattering Smith microsurface (brdf/random_walk.h, [HHdD16]),
 * conductor or rough dielectric (a cell whose BB_SMITH_WALK_ETA is > 0), by random walks: each
 * work-item runs one replica of one cell, `n_walks` walks from the cell's view wo, and writes five
 * replica means, BB_WALK_SUMS per item:
 *   0  the weight escaped above (the albedo E(wo), or the dielectric's R, every order up to the limit),
 *   1  its first order (the single-scattering albedo, the height-correlated Smith lobe's),
 *   2  the weight cut off by the bounce limit (BB_SMITH_BOUNCES of the cell's parameters),
 *   3  the dielectric's weight escaped below (T; 0 for a conductor),
 *   4  its first order.
 * The host (host/integrate/random_walk.cpp) turns the replicas into means and error estimates.
 * A walk that meets a non-finite number is counted in bad_count and adds nothing.
 *
 * A second entry, BB_ENTRY_WALK_EVAL (below), estimates f(wo, wi) by next-event estimation.
 *
 * Build options: -D BB_MODEL=<BB_MODEL_GGX or BB_MODEL_BECKMANN> -D BB_FRESNEL=<kind>
 * [-D BB_REAL_DOUBLE] -D BB_PHILOX -I <Random123's include directory>. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/model_registry.h"
#include "brdfbake/brdf/random_walk.h"

#if BB_MODEL == BB_MODEL_BECKMANN
#define BB_WALK_DIST BB_SMITH_BECKMANN
#else
#define BB_WALK_DIST BB_SMITH_GGX
#endif

/* What both entries read first: work-item gid's unit (a cell, or a pair) and replica, the unit's
 * parameters and the Fresnel term's (ok = 0 if one is not finite), its bounce limit and whether it
 * is the dielectric walk. */
typedef struct {
    unsigned int unit, rep, ok;
    bb_params p, fp;
    int bounces, dielectric;
} bb_walk_item;

bb_walk_item bb_walk_item_load(unsigned int gid, unsigned int n_replicas, __global const bb_scalar* model_p,
                               __global const bb_scalar* fresnel_p) {
    bb_walk_item it;
    it.unit = gid / n_replicas;
    it.rep = gid - it.unit * n_replicas;
    it.ok = 1;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) {
        it.p.v[k] = (bb_real)model_p[it.unit * BB_MAX_PARAMS + k];
        it.fp.v[k] = (bb_real)fresnel_p[k];
        it.ok &= (unsigned int)(isfinite(it.p.v[k]) && isfinite(it.fp.v[k]));
    }
    it.bounces = (int)it.p.v[BB_SMITH_BOUNCES];
    it.dielectric = it.p.v[BB_SMITH_WALK_ETA] > BB_R(0.0);
    return it;
}

__kernel void BB_ENTRY_WALK_ALBEDO(__global const bb_scalar* cell_mu, __global const bb_scalar* cell_phi,
                                   __global const bb_scalar* model_p, __global const bb_scalar* fresnel_p,
                                   const unsigned int n_walks,    /* walks per replica */
                                   const unsigned int n_replicas, const unsigned int n_cells,
                                   const unsigned int seed_lo, /* Philox key */
                                   const unsigned int seed_hi,
                                   __global const unsigned int* cell_stream, /* each cell's stream */
                                   __global bb_scalar* sums,                 /* BB_WALK_SUMS per item */
                                   __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas) return;
    const bb_walk_item it = bb_walk_item_load(gid, n_replicas, model_p, fresnel_p);
    const unsigned int cell = it.unit, rep = it.rep, ok = it.ok;
    const bb_vec3 wo = bb_dir_from_mu_phi((bb_real)cell_mu[cell], (bb_real)cell_phi[cell]);
    const bb_vec3 none = bb_v3(BB_R(0.0), BB_R(0.0), BB_R(0.0)); /* no next-event target */
    philox4x32_key_t key = {{seed_lo, seed_hi}};
    bb_real sum[BB_WALK_SUMS], comp[BB_WALK_SUMS];
    for (int k = 0; k < BB_WALK_SUMS; ++k) sum[k] = comp[k] = BB_R(0.0);
    unsigned int bad = 0;
    for (unsigned int i = 0; i < n_walks && ok; ++i) {
        const bb_walk_result r =
            it.dielectric ? bb_walk_dielectric(BB_WALK_DIST, it.p, wo, none, it.bounces, key, i, rep, cell_stream[cell])
                          : bb_walk_conductor(BB_WALK_DIST, it.p, BB_FRESNEL, it.fp, wo, none, it.bounces, key, i, rep,
                                              cell_stream[cell]);
        bad += (unsigned int)r.bad;
        BB_KAHAN_ADD(sum[0], comp[0], r.energy);
        BB_KAHAN_ADD(sum[1], comp[1], r.single);
        BB_KAHAN_ADD(sum[2], comp[2], r.cutoff);
        BB_KAHAN_ADD(sum[3], comp[3], r.transmitted);
        BB_KAHAN_ADD(sum[4], comp[4], r.single_t);
    }
    const bb_real n = (bb_real)n_walks;
    for (int k = 0; k < BB_WALK_SUMS; ++k) sums[BB_WALK_SUMS * gid + k] = sum[k] / n;
    bad_count[gid] = ok ? bad : n_walks;
}

/* f(wo, wi) wi.z by the walks' next-event estimation (brdf/random_walk.h): each work-item runs one
 * replica of one pair, `n_walks` walks from the pair's wo towards its wi (both unit vectors above
 * the surface, xyz in `dirs`, six per pair), and writes BB_WALK_EVAL_SUMS replica means: the
 * estimate of every order up to the bounce limit and its first order. A dielectric's wi may lie
 * below the surface: the transmitted f_t(wo, wi) |wi.z| (a conductor's is 0). */
__kernel void BB_ENTRY_WALK_EVAL(__global const bb_scalar* dirs, __global const bb_scalar* model_p,
                                 __global const bb_scalar* fresnel_p, const unsigned int n_walks,
                                 const unsigned int n_replicas, const unsigned int n_pairs, const unsigned int seed_lo,
                                 const unsigned int seed_hi, __global const unsigned int* pair_stream,
                                 __global bb_scalar* sums, __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_pairs * n_replicas) return;
    const bb_walk_item it = bb_walk_item_load(gid, n_replicas, model_p, fresnel_p);
    const unsigned int pair = it.unit, rep = it.rep, ok = it.ok;
    __global const bb_scalar* d = dirs + 6 * pair;
    const bb_vec3 wo = bb_v3((bb_real)d[0], (bb_real)d[1], (bb_real)d[2]);
    const bb_vec3 wi = bb_v3((bb_real)d[3], (bb_real)d[4], (bb_real)d[5]);
    philox4x32_key_t key = {{seed_lo, seed_hi}};
    bb_real sum[BB_WALK_EVAL_SUMS], comp[BB_WALK_EVAL_SUMS];
    for (int k = 0; k < BB_WALK_EVAL_SUMS; ++k) sum[k] = comp[k] = BB_R(0.0);
    unsigned int bad = 0;
    const int lit = wo.z > BB_R(0.0) && (wi.z > BB_R(0.0) || (it.dielectric && wi.z < BB_R(0.0)));
    for (unsigned int i = 0; i < n_walks && ok && lit; ++i) {
        const bb_walk_result r =
            it.dielectric ? bb_walk_dielectric(BB_WALK_DIST, it.p, wo, wi, it.bounces, key, i, rep, pair_stream[pair])
                          : bb_walk_conductor(BB_WALK_DIST, it.p, BB_FRESNEL, it.fp, wo, wi, it.bounces, key, i, rep,
                                              pair_stream[pair]);
        const int finite = bb_isfinite(r.f_cos) && !r.bad;
        bad += (unsigned int)!finite;
        BB_KAHAN_ADD(sum[0], comp[0], finite ? r.f_cos : BB_R(0.0));
        BB_KAHAN_ADD(sum[1], comp[1], finite ? r.f_cos_single : BB_R(0.0));
    }
    const bb_real n = (bb_real)n_walks;
    for (int k = 0; k < BB_WALK_EVAL_SUMS; ++k) sums[BB_WALK_EVAL_SUMS * gid + k] = sum[k] / n;
    bad_count[gid] = ok ? bad : n_walks;
}

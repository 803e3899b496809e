/* The volumetric sheen layer of [ZBC22] by random walks (brdf/sheen_volume.h): each work-item runs
 * one replica of one cell, `n_walks` walks from the cell's view wo = (sqrt(1 - mu^2), 0, mu), and
 * writes BB_SHEEN_SUMS replica means:
 *   0  R, the share of walks that left through the top (the layer's reflectance),
 *   1  R1, those that left through the top after one scattering (the first order),
 *   2  T, through the bottom,
 *   3  T0, through the bottom without scattering,
 *   4  the share the bounce limit cut off (bounces < 0: the share the paper's rule stopped and
 *      counted by direction, brdf/sheen_volume.h),
 * and, when n_bins > 0, the lobe's histogram of the top exits after two or more scatterings in
 * BB_SHEEN_LOBE_THETA x BB_SHEEN_LOBE_PHI bins (theta in [0, pi/2] and |phi| in [0, pi] uniform; the
 * lobe is symmetric about phi = 0), summed per replica: with next_flight = 1 every scattering n >= 2
 * adds its next-flight tally (the probability that the walk leaves the top in its new direction
 * before it scatters again, brdf/sheen_volume.h bb_sheen_next_flight) to the bin of its direction;
 * with next_flight = 0 each actual exit adds 1 (analog counts; the same expectation). The first
 * order has a closed form (integrate/sheen_volume.h sheen_single_density). The host
 * (host/integrate/sheen_volume.cpp) turns the replicas into means and error estimates. A walk that
 * meets a non-finite number is counted in bad_count; `flights` gets the mean free flights a walk (its
 * cost: a grazing view of a smooth layer takes ~1/mu of them).
 *
 * Build options: [-D BB_REAL_DOUBLE] -D BB_PHILOX -I <Random123's include directory>. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/sheen_volume.h"

/* The bins' edges: cos((k + 1) pi / 32) in theta over [0, pi/2], cos((k + 1) pi / 16) in |phi| over [0, pi]
 * (BB_SHEEN_LOBE_THETA = BB_SHEEN_LOBE_PHI = 16), k = 0..14, descending. */
#if BB_SHEEN_LOBE_THETA != 16 || BB_SHEEN_LOBE_PHI != 16
#error "kSheenCosTheta and kSheenCosPhi hold the edges of 16 x 16 bins: recompute them for the new bin counts"
#endif
__constant bb_real kSheenCosTheta[15] = {
    BB_R(0.9951847266721969), BB_R(0.9807852804032304), BB_R(0.9569403357322088), BB_R(0.9238795325112867),
    BB_R(0.881921264348355), BB_R(0.8314696123025452), BB_R(0.773010453362737), BB_R(0.7071067811865476),
    BB_R(0.6343932841636455), BB_R(0.5555702330196023), BB_R(0.4713967368259978), BB_R(0.38268343236508984),
    BB_R(0.29028467725446233), BB_R(0.19509032201612833), BB_R(0.09801714032956077)};
__constant bb_real kSheenCosPhi[15] = {
    BB_R(0.9807852804032304), BB_R(0.9238795325112867), BB_R(0.8314696123025452), BB_R(0.7071067811865476),
    BB_R(0.5555702330196023), BB_R(0.38268343236508984), BB_R(0.19509032201612833), BB_R(6.123233995736766e-17),
    BB_R(-0.1950903220161282), BB_R(-0.3826834323650897), BB_R(-0.555570233019602), BB_R(-0.7071067811865475),
    BB_R(-0.8314696123025453), BB_R(-0.9238795325112867), BB_R(-0.9807852804032304)};

/* The number of edges c[0..14] (descending) above v: the bin of the angle whose cosine (times the
 * scale) is v, by bisection (no inverse trigonometry: the next-flight tallies bin every upward turn). */
static int sheen_edges_above(bb_real v, bb_real scale, __constant const bb_real* c) {
    int lo = 0, hi = 15;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (v < c[mid] * scale)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The histogram bin of a unit direction w pointing up: theta = acos(w.z), |phi| = atan2(|w.y|, w.x). */
static int sheen_lobe_bin(bb_vec3 w) {
    const int it = sheen_edges_above(w.z, BB_R(1.0), kSheenCosTheta);
    const int ip = sheen_edges_above(w.x, bb_sqrt(w.x * w.x + w.y * w.y), kSheenCosPhi);
    return it * BB_SHEEN_LOBE_PHI + ip;
}

__kernel void BB_ENTRY_SHEEN_VOLUME(__global const bb_scalar* cell_mu, __global const bb_scalar* cell_alpha,
                                    __global const int* cell_bounces,
                                    const unsigned int n_walks, /* walks per replica */
                                    const unsigned int n_replicas, const unsigned int n_cells,
                                    const unsigned int seed_lo, /* Philox key */
                                    const unsigned int seed_hi,
                                    __global const unsigned int* cell_stream, /* each cell's stream */
                                    const unsigned int n_bins,                /* 0 or the lobe's bins */
                                    const unsigned int next_flight,           /* the lobe's estimator */
                                    __global bb_scalar* sums,                 /* BB_SHEEN_SUMS per item */
                                    __global bb_scalar* hist,                 /* n_bins per item */
                                    __global bb_scalar* flights,              /* per item: flights a walk */
                                    __global unsigned int* bad_count) {
    const unsigned int gid = (unsigned int)get_global_id(0);
    if (gid >= n_cells * n_replicas) return;
    const unsigned int cell = gid / n_replicas, rep = gid - cell * n_replicas;
    const bb_real s = bb_sheen_volume_sigma((bb_real)cell_alpha[cell]);
    const bb_vec3 wo = bb_dir_from_mu_phi((bb_real)cell_mu[cell], BB_R(0.0));
    const int bounces = cell_bounces[cell];
    philox4x32_key_t key = {{seed_lo, seed_hi}};
    __global bb_scalar* h = hist + (size_t)gid * n_bins;
    for (unsigned int b = 0; b < n_bins; ++b) h[b] = (bb_scalar)0;
    unsigned int count[BB_SHEEN_SUMS] = {0u, 0u, 0u, 0u, 0u};
    unsigned int bad = 0;
    bb_real flown = BB_R(0.0);
    for (unsigned int i = 0; i < n_walks; ++i) {
        bb_sheen_walk r = bb_sheen_walk_start(wo, bounces);
        while (!r.done)
            if (bb_sheen_walk_step(&r, s, key, i, rep, cell_stream[cell]) && next_flight && n_bins > 0 &&
                r.scatterings >= 2 && r.w.z > BB_R(0.0)) {
                const bb_real p = bb_sheen_next_flight(r, s);
                if (p > BB_R(0.0)) h[sheen_lobe_bin(r.w)] += (bb_scalar)p;
            }
        flown += (bb_real)r.flights;
        bad += (unsigned int)(r.exit == BB_SHEEN_EXIT_BAD);
        count[0] += (unsigned int)(r.exit == BB_SHEEN_EXIT_TOP);
        count[1] += (unsigned int)(r.exit == BB_SHEEN_EXIT_TOP && r.scatterings == 1);
        count[2] += (unsigned int)(r.exit == BB_SHEEN_EXIT_BOTTOM);
        count[3] += (unsigned int)(r.exit == BB_SHEEN_EXIT_BOTTOM && r.scatterings == 0);
        count[4] += (unsigned int)(r.exit == BB_SHEEN_EXIT_CUTOFF || r.truncated); /* cut off, or stopped by the paper's rule */
        if (n_bins > 0 && !next_flight && r.exit == BB_SHEEN_EXIT_TOP && r.scatterings >= 2)
            h[sheen_lobe_bin(r.w)] += (bb_scalar)1;
    }
    const bb_real n = (bb_real)n_walks;
    for (int k = 0; k < BB_SHEEN_SUMS; ++k) sums[BB_SHEEN_SUMS * gid + k] = (bb_real)count[k] / n;
    flights[gid] = flown / n;
    bad_count[gid] = bad;
}

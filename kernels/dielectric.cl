/* Reflected and transmitted energy fractions of a rough GGX dielectric interface per cell
 * (mu_o, alpha, eta), one randomised-Hammersley replica per work-item, as kernels/albedo.cl
 * does for BRDFs. Build options: [-D BB_REAL_DOUBLE]. */
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/brdf/sampling.h"

__kernel void dielectric_replicas(__global const real* cell_mu, __global const real* cell_alpha,
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

/* Directional albedo E(wo) = integral of f(wo, wi) cos(theta_i) over the upper hemisphere.
 *
 * Estimator: importance sampling of the model (bb_model_sample) driven by a randomised
 * Hammersley set. Each work-item computes one replica of one cell: the n-point set rotated by
 * its own Cranley-Patterson shift. The host turns the replicas into the mean and its standard
 * error. Non-finite weights are counted, never summed, so that a NaN cannot hide in a table.
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. */
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/sampling.h"

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

/* Reciprocity and sanity scan of f over a dense grid of direction pairs.
 *
 * Work-item (i, o) takes theta_i = theta[i], theta_o = theta[o] and loops over the azimuths
 * (phi_o over n_phi_o values, the difference phi_i - phi_o over n_phi values). It records the
 * worst relative reciprocity error |f(wo,wi) - f(wi,wo)| / max(f(wo,wi), f(wi,wo)) and where it
 * occurred, the number of non-finite values, and the smallest value (negative values are a
 * violation). Pairs where both values are 0 have error 0.
 *
 * Build options: -D BB_MODEL=<id> -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"

__kernel void BB_ENTRY_RECIPROCITY_SCAN(__global const bb_real* theta, const unsigned int n_theta, const unsigned int n_phi,
                               const unsigned int n_phi_o, __global const bb_real* model_p,
                               __global const bb_real* fresnel_p,
                               __global const bb_scalar* model_data, /* BB_MODEL_DATA_ARG */
                               __global bb_real* max_rel,        /* n_theta * n_theta */
                               __global bb_real* max_rel_phi,    /* phi_i - phi_o of the worst pair */
                               __global bb_real* min_value,      /* smallest finite f */
                               __global unsigned int* nonfinite) {
    const unsigned int i = (unsigned int)get_global_id(0);
    const unsigned int o = (unsigned int)get_global_id(1);
    if (i >= n_theta || o >= n_theta)
        return;
    bb_params p, fp;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) {
        p.v[k] = model_p[k];
        fp.v[k] = fresnel_p[k];
    }
    p.data = model_data;
    const bb_real mu_i = cos(theta[i]), mu_o = cos(theta[o]);
    bb_real worst = BB_R(0.0), worst_phi = BB_R(0.0), lowest = BB_REAL_MAX;
    unsigned int bad = 0;
    for (unsigned int a = 0; a < n_phi_o; ++a) {
        const bb_real phi_o = BB_2PI * ((bb_real)a + BB_R(0.5)) / (bb_real)n_phi_o;
        const bb_vec3 wo = bb_dir_from_mu_phi(mu_o, phi_o);
        for (unsigned int b = 0; b < n_phi; ++b) {
            const bb_real dphi = BB_2PI * (bb_real)b / (bb_real)n_phi;
            const bb_vec3 wi = bb_dir_from_mu_phi(mu_i, phi_o + dphi);
            const bb_real f1 = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wo, wi);
            const bb_real f2 = bb_model_eval(BB_MODEL, p, BB_FRESNEL, fp, wi, wo);
            const int ok = isfinite(f1) && isfinite(f2);
            bad += ok ? 0u : 2u - (unsigned int)(isfinite(f1) != 0) - (unsigned int)(isfinite(f2) != 0);
            if (!ok)
                continue;
            lowest = fmin(lowest, fmin(f1, f2));
            const bb_real m = fmax(fabs(f1), fabs(f2));
            const bb_real rel = m > BB_R(0.0) ? fabs(f1 - f2) / m : BB_R(0.0);
            if (rel > worst) {
                worst = rel;
                worst_phi = dphi;
            }
        }
    }
    const unsigned int k = o * n_theta + i;
    max_rel[k] = worst;
    max_rel_phi[k] = worst_phi;
    min_value[k] = lowest;
    nonfinite[k] = bad;
}

/* Fresnel curves: F, Rs and Rp of Fresnel terms of one kind at a list of incidence cosines.
 *
 * Dimension 0 runs over the n cosines, dimension 1 over the parameter sets (one per wavelength
 * for a spectral colour: one launch for the whole spectrum); set s reads fresnel_p[s *
 * BB_MAX_PARAMS ...] and writes out[3 * (s * n + i) ...].
 *
 * The host passes cos(theta) rather than theta: it computes the cosine in double (as
 * sin(90 deg - theta), exact at grazing), so that a float kernel sees cos(89.999 deg) with full
 * relative precision instead of the rounding error of a float angle.
 *
 * Build options: -D BB_FRESNEL=<kind> [-D BB_REAL_DOUBLE]. */
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/fresnel.h"

__kernel void BB_ENTRY_FRESNEL_CURVE(__global const bb_real* cos_theta, /* n values in [-1, 1] */
                            __global const bb_real* fresnel_p, /* BB_MAX_PARAMS per set */
                            const unsigned int n,
                            __global bb_real* out)             /* 3 per value and set: F, Rs, Rp */
{
    const unsigned int i = (unsigned int)get_global_id(0);
    const unsigned int set = (unsigned int)get_global_id(1);
    if (i >= n)
        return;
    bb_params fp;
    for (int k = 0; k < BB_MAX_PARAMS; ++k)
        fp.v[k] = fresnel_p[set * BB_MAX_PARAMS + k];
    out += 3 * ((size_t)set * n);
    const bb_real c = cos_theta[i];
    const bb_fresnel_sp r = bb_fresnel_eval_sp(BB_FRESNEL, fp, c);
    out[3 * i + 0] = bb_fresnel_eval(BB_FRESNEL, fp, c);
    out[3 * i + 1] = r.rs;
    out[3 * i + 2] = r.rp;
}

// The baseline's inner loop, compiled once per flavour (baseline_*.cpp) with the shared GGX
// header included inside a namespace of its own, so that the double and the float builds of
// the shared math (different `real`) never meet. Define BASELINE_NS and BASELINE_FN first,
// and BB_HOST_REAL_FLOAT for the float build.
#include <cmath>
#include <cstdint>
#include <vector>

#include <omp.h>

namespace BASELINE_NS {
#include "brdfbake/brdf/ggx.h"
#include "brdfbake/brdf/sampling.h"

// Replica means and non-finite counts of every (cell, replica), cell-major: exactly the work
// items of kernels/albedo.cl.
inline void BASELINE_FN(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                        std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                        std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    const long n_items = long(mus.size()) * long(replicas);
    means.assign(size_t(n_items), 0.0);
    bad.assign(size_t(n_items), 0);
    const unsigned n = unsigned(points);
#pragma omp parallel for schedule(dynamic, 1)
    for (long item = 0; item < n_items; ++item) {
        const long cell = item / replicas, rep = item - cell * replicas;
        bb_params p, fp;
        for (int k = 0; k < BB_MAX_PARAMS; ++k) p.v[k] = fp.v[k] = BB_R(0.0);
        p.v[BB_GGX_ALPHA_X] = p.v[BB_GGX_ALPHA_Y] = real(alphas[size_t(cell)]);
        p.v[BB_GGX_SHADOWING] = correlated ? BB_R(1.0) : BB_R(0.0);
        const bb_vec3 wo = bb_dir_from_mu_phi(real(mus[size_t(cell)]), BB_R(0.0));
        const real s1 = real(shifts[2 * size_t(rep)]), s2 = real(shifts[2 * size_t(rep) + 1]);
        // Summed in double: the float flavour's 2^16-term sums stay exact to ~1e-12 without a
        // compensated (loop-carried, unvectorisable) sum.
        double sum = 0.0;
        std::uint64_t nb = 0;
#pragma omp simd reduction(+ : sum, nb)
        for (unsigned i = 0; i < n; ++i) {
            const real u1 = bb_rotate(bb_hammersley_u1(i, n), s1);
            const real u2 = bb_rotate(bb_hammersley_u2(i), s2);
            const real w = bb_ggx_sample(p, BB_FRESNEL_NONE, fp, wo, u1, u2).weight;
            const bool ok = std::isfinite(w);
            nb += ok ? 0 : 1;
            sum += ok ? double(w) : 0.0;
        }
        means[size_t(item)] = sum / double(n);
        bad[size_t(item)] = nb;
    }
}
}  // namespace BASELINE_NS

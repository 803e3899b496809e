// Baseline driver: replica shifts, flavour dispatch, mean and error estimate (as compute_albedo).
#include "baseline.h"

#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <omp.h>

#include "baseline_flags.h"
#include "baseline_kernels.h"

namespace brdfbake {
namespace baseline {

// The same Philox4x32-10 stream as host/albedo.cpp's replica_shifts: counter (r, "albd", 0, 0),
// key = the seed's two halves, 53-bit doubles from two words each.
std::vector<double> replica_shifts(unsigned replicas, std::uint64_t seed) {
    using Philox = r123::Philox4x32;
    Philox rng;
    Philox::key_type key = {{std::uint32_t(seed), std::uint32_t(seed >> 32)}};
    std::vector<double> shifts;
    for (unsigned r = 0; r < replicas; ++r) {
        Philox::ctr_type ctr = {{r, 0x616c6264u, 0, 0}};
        const Philox::ctr_type out = rng(ctr, key);
        shifts.push_back(r123::u01<double>(std::uint64_t(out[0]) << 32 | out[1]));
        shifts.push_back(r123::u01<double>(std::uint64_t(out[2]) << 32 | out[3]));
    }
    for (double& s : shifts)
        if (s >= 1.0) s = 0.0;
    return shifts;
}

Result albedo_table(const Request& req) {
    if (req.mu.size() != req.alpha.size()) throw std::invalid_argument("baseline: mu and alpha differ in length");
    if (req.replicas < 2 || req.samples < req.replicas) throw std::invalid_argument("baseline: too few samples");
    const std::uint64_t points = req.samples / req.replicas;
    if (req.fast_math && req.kernel_arithmetic)
        throw std::invalid_argument("baseline: the kernel-arithmetic flavour is strict only");
    std::vector<double> shifts = replica_shifts(req.replicas, req.seed);
    if (req.single)  // the float kernel reads its shifts as float
        for (double& s : shifts) s = double(float(s));
    std::vector<double> means;
    std::vector<std::uint64_t> bad;
    auto fn = req.kernel_arithmetic ? (req.single ? replicas_kernel_arith_float : replicas_kernel_arith_double)
              : req.single          ? (req.fast_math ? replicas_fast_float : replicas_strict_float)
                                    : (req.fast_math ? replicas_fast_double : replicas_strict_double);
    const auto t0 = std::chrono::steady_clock::now();
    fn(req.mu, req.alpha, req.correlated, points, req.replicas, shifts, means, bad);
    Result r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.threads = omp_get_max_threads();
    const double eps = req.single ? 1.1920929e-7 : 2.220446049250313e-16;
    const unsigned R = req.replicas;
    for (size_t c = 0; c < req.mu.size(); ++c) {
        double sum = 0.0;
        for (unsigned k = 0; k < R; ++k) {
            sum += means[c * R + k];
            r.non_finite += bad[c * R + k];
        }
        const double mean = sum / R;
        double ss = 0.0;
        for (unsigned k = 0; k < R; ++k) ss += (means[c * R + k] - mean) * (means[c * R + k] - mean);
        r.value.push_back(mean);
        r.error.push_back(3.0 * std::sqrt(ss / (R - 1) / R) + 8.0 * eps * std::max(std::fabs(mean), 1e-3));
    }
    return r;
}

std::string compile_flags() { return BRDFBAKE_BASELINE_FLAGS; }

// Counted from baseline_impl.h's loop bodies (common subexpressions once):
//   closed form: t2 = s1 h + s y (3), t3 = sqrt(max(0, 1 - x^2 - t2^2)) (6), n (9), L = |n|^2
//     (5), z = 2 (wo.n) n.z - wo.z L (7), q = sqrt(a^2 L^2 + (1 - a^2) z^2) (6), the weight
//     2 c0 z / ((2 c0 - 1) z + q) (4), the horizon select (1), finiteness and sums (5)      46
//   kernel arithmetic: t2 with sqrt(1 - x^2) (7), t3 (4), n (9), normalise (11), clamped
//     wo.wh (5), reflect (6), G1(wi) (14), correlated G2 and / G1(wo) (9), finiteness and
//     sums (5)                                                                              70
double flops_per_sample(bool kernel_arithmetic) { return kernel_arithmetic ? 70.0 : 46.0; }

}  // namespace baseline
}  // namespace brdfbake

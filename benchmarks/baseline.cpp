// Baseline driver: compute_albedo's replica shifts, flavour dispatch (tuned and plain loops), mean and error
// estimate (as compute_albedo).
#include "baseline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <omp.h>

#include "baseline_flags.h"
#include "baseline_kernels.h"
#include "integrate/replicas.h"

namespace brdfbake {
namespace baseline {

Result albedo_table(const Request& req) {
    if (req.mu.size() != req.alpha.size()) throw std::invalid_argument("baseline: mu and alpha differ in length");
    if (req.replicas < 2 || req.samples < req.replicas) throw std::invalid_argument("baseline: too few samples");
    const std::uint64_t points = req.samples / req.replicas;
    if (req.kernel_arithmetic && (req.fast_math || req.plain))
        throw std::invalid_argument("baseline: the kernel-arithmetic flavour is strict and tuned only");
    // compute_albedo's Cranley-Patterson shifts (host/integrate/replicas.cpp).
    std::vector<double> shifts = brdfbake::replica_shifts(req.replicas, req.seed);
    if (req.single)  // the float kernel reads its shifts as float
        for (double& s : shifts) s = double(float(s));
    std::vector<double> means;
    std::vector<std::uint64_t> bad;
    auto fn = req.kernel_arithmetic ? (req.single ? replicas_kernel_arith_float : replicas_kernel_arith_double)
              : req.plain ? (req.single ? (req.fast_math ? replicas_plain_fast_float : replicas_plain_strict_float)
                                        : (req.fast_math ? replicas_plain_fast_double : replicas_plain_strict_double))
              : req.single ? (req.fast_math ? replicas_fast_float : replicas_strict_float)
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
        // As compute_albedo's estimate (summarize in host/integrate/replicas.cpp): 3 standard errors
        // of the replica means, 3 |E| / N for the mass the N points may not have seen, and the
        // floating-point bound 8 eps max(|E|, 1e-3).
        const double n_total = double(points * R);
        r.error.push_back(3.0 * std::sqrt(ss / (R - 1) / R) + 3.0 * std::fabs(mean) / n_total +
                          8.0 * eps * std::max(std::fabs(mean), 1e-3));
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
// Counted from baseline_plain_impl.h's loop body, as written (wo and the basis as general
// vectors; loop invariants such as 1 - s and 1 + Lambda(wo) once per cell, not per sample):
//   the rotated point: u1 = rot((i + 1/2)/n + shift) (5), u2 = rot(ri 2^-24 + shift) (4)     9
//   r = sqrt(u1), phi = 2 pi u2 (2), t1 = r cos, t2 = r sin (2), sqrt(max(0, 1 - t1^2)) (4),
//     the blend (3), t3 = sqrt(max(0, 1 - t1^2 - t2^2)) (5), Nh = t1 T1 + t2 T2 + t3 Vh (15),
//     unstretch (3), normalise (10)                                                        44
//   reflect: wo.m (5), 2 (wo.m) m - wo (7); Lambda(wi) (10), G2 correlated (2) and separable
//     (2) and the select (1), / G1(wo) (1), the horizon select (1)                         29
//   finiteness and sums (5)                                                                  5
// 87 flops, plus one sin and one cos that are NOT counted (a range reduction and a polynomial
// each, in libmvec's vector form with -ffast-math or glibc's scalar sincos without): the figure
// is a lower bound of the work. With -ffast-math g++ also drops the terms of wo.y = 0 and
// T1.z = 0, which the strict build must keep (0 x Inf is NaN).
double flops_per_sample(bool kernel_arithmetic, bool plain) {
    return plain ? 87.0 : kernel_arithmetic ? 70.0 : 46.0;
}

}  // namespace baseline
}  // namespace brdfbake

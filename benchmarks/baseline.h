// The C++ OpenMP baselines the benchmarks compare the kernels against (issue 9), and the
// FMA-throughput probe that gives the machine's peak.
//
// Both baselines compute exactly the estimator of kernels/albedo.cl for GGX (visible-normal
// importance sampling, Fresnel none), written independently of the shared headers: per cell,
// `replicas` copies of the n-point Hammersley set, each rotated by its own Cranley-Patterson
// shift from Philox4x32-10 keyed by the seed (the very shifts compute_albedo uses), the replica
// means turned into the mean, 3 standard errors + the floating-point bound. They are compiled
// with -O3 -march=native -fopenmp (benchmarks/CMakeLists.txt), one OpenMP thread per core.
//
// The *tuned* baseline (baseline_impl.h) is a hand-tuned vectorised loop: the cell-independent
// work (the disk points and sqrt(1 - x^2)) is tabulated once per call as the kernel does, and the
// weight is evaluated in a closed form with two square roots and one division per sample. Three
// flavours of one source:
//   strict       the kernel's semantics: NaN/Inf weights counted, no -ffast-math
//                (-fno-math-errno -fno-trapping-math, which change no value);
//   fastmath     -ffast-math: approximate reciprocal square roots and divisions, and every
//                value assumed finite, so non-finite samples go unnoticed. A yardstick, not an
//                equal;
//   kernel arithmetic  strict, but the weight computed with the operations of the shared
//                headers (four square roots and four divisions per sample): what g++ makes of
//                the kernel's arithmetic, to tell the compiler's share from the arithmetic's.
// The *plain* baseline (baseline_plain_impl.h, `plain`) is the issue's "plain C++ OpenMP loop of
// the same estimator": the textbook algorithm per sample (the rotated Hammersley point, a sin and
// a cos, Heitz 2018 listing 1, reflection, Smith G2/G1 with the textbook Lambda), nothing
// tabulated, in two flavours:
//   strict       as above; glibc has no vector sin/cos without -ffast-math, so the points loop
//                runs scalar (one sincos call per sample);
//   fastmath     -ffast-math as in the measurement (860 M samples/s there): libmvec's
//                vector sin and cos, the loop vectorised.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace brdfbake {
namespace baseline {

struct Request {
    std::vector<double> mu;     // cos(theta_o) per cell
    std::vector<double> alpha;  // GGX alpha per cell (isotropic)
    bool correlated = true;     // height-correlated G2, else separable
    std::uint64_t samples = 1u << 16;  // per cell, split over the replicas
    unsigned replicas = 16;
    std::uint64_t seed = 0x62726466u;  // AlbedoRequest's default seed
    bool single = false;        // float arithmetic (as a --precision float kernel), else double
    bool fast_math = false;     // the -ffast-math flavour
    bool kernel_arithmetic = false;  // the weight with the shared headers' operations (strict)
    bool plain = false;         // the plain textbook loop (baseline_plain_impl.h), else the tuned one
};

struct Result {
    std::vector<double> value, error;  // per cell
    std::uint64_t non_finite = 0;      // samples with a NaN/Inf weight (strict flavour only)
    double seconds = 0.0;              // wall time of the integration (threads included)
    int threads = 0;
};

/// The albedo table of `request` on all cores. Throws std::invalid_argument for a bad request
/// (kernel_arithmetic with fast_math or plain, too few samples).
Result albedo_table(const Request& request);

/// Peak fused-multiply-add throughput of all cores in GFLOP/s (an FMA counts as 2 flops),
/// measured for about `seconds` with independent FMA chains in the widest vectors the compiler
/// targets (-march=native).
struct Peak {
    double gflops_float = 0.0, gflops_double = 0.0;
    int threads = 0;
    int vector_bits = 0;
};
Peak fma_peak(double seconds = 0.25);

/// What the baseline was compiled with, for the report.
std::string compile_flags();

/// Flops per sample of the inner loop, counted from its source as benchmarks/harness/bench.cpp counts the
/// kernel's (+, -, *, /, sqrt, min/max and compare-select 1, fma 2; the tabulated work and the
/// per-cell work left out; the plain loop's sin and cos left out too, baseline.cpp).
double flops_per_sample(bool kernel_arithmetic, bool plain = false);

}  // namespace baseline
}  // namespace brdfbake

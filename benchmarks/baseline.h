// The plain C++ OpenMP baseline the benchmarks compare the kernels against (issue 9), and the
// FMA-throughput probe that gives the machine's peak.
//
// The baseline computes exactly the estimator of kernels/albedo.cl for GGX (visible-normal
// importance sampling, Fresnel none), written independently of the shared headers as a
// vectorised loop (baseline_impl.h): per cell, `replicas` copies of the n-point Hammersley
// set, each rotated by its own Cranley-Patterson shift from Philox4x32-10 keyed by the seed
// (the very shifts compute_albedo uses), the replica means turned into the mean, 3 standard
// errors + the floating-point bound. The cell-independent work (the disk points) is tabulated
// once per call as the kernel does, and the weight is evaluated in a closed form with two
// square roots and one division per sample. It is compiled with -O3 -march=native -fopenmp
// (benchmarks/CMakeLists.txt), one OpenMP thread per core, in three flavours of one source:
//   strict       the kernel's semantics: NaN/Inf weights counted, no -ffast-math
//                (-fno-math-errno -fno-trapping-math, which change no value);
//   fastmath     -ffast-math as in the measurement: approximate reciprocal square roots
//                and divisions, and every value assumed finite, so non-finite samples go
//                unnoticed. A yardstick, not an equal;
//   kernel arithmetic  strict, but the weight computed with the operations of the shared
//                headers (four square roots and four divisions per sample): what g++ makes of
//                the kernel's arithmetic, to tell the compiler's share from the arithmetic's.
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
};

struct Result {
    std::vector<double> value, error;  // per cell
    std::uint64_t non_finite = 0;      // samples with a NaN/Inf weight (strict flavour only)
    double seconds = 0.0;              // wall time of the integration (threads included)
    int threads = 0;
};

/// The albedo table of `request` on all cores. Throws std::invalid_argument for a bad request
/// (fast_math and kernel_arithmetic together, too few samples).
Result albedo_table(const Request& request);

/// The Cranley-Patterson shifts of compute_albedo (two per replica), in double.
std::vector<double> replica_shifts(unsigned replicas, std::uint64_t seed);

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

/// Flops per sample of the inner loop, counted from its source as host/bench.cpp counts the
/// kernel's (+, -, *, /, sqrt, min/max and compare-select 1, fma 2; the tabulated work and the
/// per-cell work left out).
double flops_per_sample(bool kernel_arithmetic);

}  // namespace baseline
}  // namespace brdfbake

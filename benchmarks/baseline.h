// The plain C++ OpenMP baseline the benchmarks compare the kernels against (issue 9), and the
// FMA-throughput probe that gives the machine's peak.
//
// The baseline computes exactly the estimator of kernels/albedo.cl for GGX (visible-normal
// importance sampling, Fresnel none), written independently of the shared headers as a
// vectorisable loop (baseline_impl.h): per cell, `replicas`
// copies of the n-point Hammersley set, each rotated by its own Cranley-Patterson shift from
// Philox4x32-10 keyed by the seed (the very shifts compute_albedo uses), the replica means
// turned into the mean, 3 standard errors + the floating-point bound. It is compiled with
// -O3 -march=native -fopenmp (benchmarks/CMakeLists.txt), one OpenMP thread per core, in two
// flavours of the same source:
//   strict    the kernel's semantics: NaN/Inf weights counted, no -ffast-math;
//   fastmath  -ffast-math as in the measurement: approximate reciprocal square roots
//             and divisions, and every value assumed finite, so non-finite samples go
//             unnoticed. A yardstick, not an equal.
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
};

struct Result {
    std::vector<double> value, error;  // per cell
    std::uint64_t non_finite = 0;      // samples with a NaN/Inf weight (strict flavour only)
    double seconds = 0.0;              // wall time of the integration (threads included)
    int threads = 0;
};

/// The albedo table of `request` on all cores. Throws std::runtime_error if the float flavour
/// is not available.
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

}  // namespace baseline
}  // namespace brdfbake

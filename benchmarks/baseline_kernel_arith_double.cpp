// Baseline row: the kernel's arithmetic (BASELINE_KERNEL_ARITHMETIC, baseline_impl.h), strict,
// double (flags in benchmarks/CMakeLists.txt): the shared headers' operations per sample,
// vectorised by g++, to separate the compiler's share of the kernel's speed from the arithmetic's.

#define BASELINE_KERNEL_ARITHMETIC 1
#define BASELINE_NS bb_kernel_arith_double
#define BASELINE_FN replicas_kernel_arith_double
#include "baseline_impl.h"
#include "baseline_kernels.h"

static_assert(sizeof(bb_kernel_arith_double::real) == sizeof(double), "baseline_impl.h ignores BB_HOST_REAL_FLOAT");

namespace brdfbake {
namespace baseline {
void replicas_kernel_arith_double(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                 std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                 std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    bb_kernel_arith_double::replicas_kernel_arith_double(mus, alphas, correlated, points, replicas, shifts, means, bad);
}
}  // namespace baseline
}  // namespace brdfbake

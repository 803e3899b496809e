// Baseline flavour: fast, float (flags in benchmarks/CMakeLists.txt): real = float
// (BB_HOST_REAL_FLOAT, baseline_impl.h).
#define BB_HOST_REAL_FLOAT 1
#define BASELINE_NS bb_fast_float
#define BASELINE_FN replicas_fast_float
#include "baseline_impl.h"
#include "baseline_kernels.h"

static_assert(sizeof(bb_fast_float::real) == sizeof(float), "baseline_impl.h ignores BB_HOST_REAL_FLOAT");

namespace brdfbake {
namespace baseline {
void replicas_fast_float(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                 std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                 std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    bb_fast_float::replicas_fast_float(mus, alphas, correlated, points, replicas, shifts, means, bad);
}
}  // namespace baseline
}  // namespace brdfbake

// Baseline flavour: fast, double (flags in benchmarks/CMakeLists.txt).
#define BASELINE_NS bb_fast_double
#define BASELINE_FN replicas_fast_double
#include "baseline_impl.h"
#include "baseline_kernels.h"

namespace brdfbake {
namespace baseline {
void replicas_fast_double(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                 std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                 std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    bb_fast_double::replicas_fast_double(mus, alphas, correlated, points, replicas, shifts, means, bad);
}
}  // namespace baseline
}  // namespace brdfbake

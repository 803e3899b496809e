// A baseline flavour's entry point (declared in baseline_kernels.h): the loop of the impl header
// just included, in namespace BASELINE_NS, exported as brdfbake::baseline::BASELINE_FN. Included
// once per flavour file, at the end of baseline_impl.h and baseline_plain_impl.h.
#include "baseline_kernels.h"

namespace brdfbake {
namespace baseline {
void BASELINE_FN(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                 std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                 std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    BASELINE_NS::BASELINE_FN(mus, alphas, correlated, points, replicas, shifts, means, bad);
}
}  // namespace baseline
}  // namespace brdfbake

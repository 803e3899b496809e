// The flavours of the tuned (baseline_*.cpp) and plain (baseline_plain_*.cpp) baseline loops,
// each compiled with its own flags.
#pragma once
#include <cstdint>
#include <vector>

namespace brdfbake {
namespace baseline {
#define BB_BASELINE_DECLARE(name)                                                                       \
    void name(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,      \
              std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,              \
              std::vector<double>& means, std::vector<std::uint64_t>& bad);
BB_BASELINE_DECLARE(replicas_strict_double)
BB_BASELINE_DECLARE(replicas_fast_double)
BB_BASELINE_DECLARE(replicas_strict_float)
BB_BASELINE_DECLARE(replicas_fast_float)
BB_BASELINE_DECLARE(replicas_kernel_arith_double)
BB_BASELINE_DECLARE(replicas_kernel_arith_float)
BB_BASELINE_DECLARE(replicas_plain_strict_double)
BB_BASELINE_DECLARE(replicas_plain_fast_double)
BB_BASELINE_DECLARE(replicas_plain_strict_float)
BB_BASELINE_DECLARE(replicas_plain_fast_float)
#undef BB_BASELINE_DECLARE
}  // namespace baseline
}  // namespace brdfbake

// Stand-in for the float flavours while brdf/compat.h offers no host float `real`.
#include <stdexcept>

#include "baseline_kernels.h"

namespace brdfbake {
namespace baseline {
void replicas_strict_float(const std::vector<double>&, const std::vector<double>&, bool, std::uint64_t, unsigned,
                           const std::vector<double>&, std::vector<double>&, std::vector<std::uint64_t>&) {
    throw std::runtime_error("the float baseline needs BB_HOST_REAL_FLOAT in brdf/compat.h");
}
void replicas_fast_float(const std::vector<double>& a, const std::vector<double>& b, bool c, std::uint64_t d,
                         unsigned e, const std::vector<double>& f, std::vector<double>& g,
                         std::vector<std::uint64_t>& h) {
    replicas_strict_float(a, b, c, d, e, f, g, h);
}
}  // namespace baseline
}  // namespace brdfbake

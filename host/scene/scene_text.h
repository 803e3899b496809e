// Small text helpers the scene reader, the planner and the plan report share.
#pragma once

#include <string>
#include <vector>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/fresnel_terms.h"

namespace brdfbake {
namespace scene_text {

inline std::string join(const std::vector<std::string>& v, const std::string& sep = ", ") {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
}

/// Whether a Fresnel spec names a conductor term (exact, approximate or measured), by its registry kind.
inline bool is_conductor_fresnel(const std::string& fresnel) {
    const int kind = fresnel_kind_of(fresnel);
    return kind == BB_FRESNEL_CONDUCTOR || kind == BB_FRESNEL_CONDUCTOR_APPROX;
}

}  // namespace scene_text
}  // namespace brdfbake

// Small text helpers the scene reader, the planner and the plan report share.
#pragma once

#include <string>
#include <vector>

namespace brdfbake {
namespace scene_text {

inline std::string join(const std::vector<std::string>& v, const std::string& sep = ", ") {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
}

/// The name of a Fresnel spec ("metal:Au" is not key=value, so not parse_spec).
inline std::string fresnel_name(const std::string& fresnel) { return fresnel.substr(0, fresnel.find(':')); }

inline bool is_conductor_fresnel(const std::string& fresnel) {
    const std::string name = fresnel_name(fresnel);
    return name == "conductor" || name == "conductor-approx" || name == "metal" || name == "nk";
}

}  // namespace scene_text
}  // namespace brdfbake

// Helpers the scene and glTF tests share: the test data folder, finding a planned table, texel
// centres, scratch folders, error messages.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "brdfbake/error.h"
#include "scene/scene.h"

namespace testing {
namespace scene {

using namespace brdfbake;

inline std::string data(const std::string& name) {
    const std::string here = __FILE__;
    return here.substr(0, here.find_last_of('/')) + "/data/" + name;
}

inline const PlannedTable* find_kind(const Plan& p, const std::string& kind, const std::string& model = "") {
    for (const auto& t : p.tables)
        if (t.request.kind == kind && (model.empty() || t.request.model == model)) return &t;
    return nullptr;
}

/// Texel-centre coordinate i of an axis of n texels over [lo, hi].
inline double centre(double lo, double hi, int n, int i) { return lo + (hi - lo) * (i + 0.5) / n; }

/// A scratch directory of this test process, removed if it exists.
inline std::string fresh_tmp_dir(const std::string& name) {
    const std::string dir = "/tmp/brdfbake-scene-" + std::to_string(::getpid()) + "-" + name;
    std::system(("rm -rf " + dir).c_str());
    return dir;
}

inline bool contains(const std::vector<std::string>& v, const std::string& part) {
    return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.find(part) != std::string::npos; });
}

inline std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}


}  // namespace scene
}  // namespace testing

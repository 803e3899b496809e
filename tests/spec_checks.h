// Checks of a resolved model spec, shared by test_spec.cpp and test_models.cpp.
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "brdfbake/spec.h"

namespace testing {

/// Resolves `spec` and checks its model id, the values of the given parameter slots and its
/// canonical string; returns the resolved model for further checks.
inline brdfbake::ModelConfig check_resolves(const std::string& spec, int id,
                                            const std::vector<std::pair<int, double>>& slot_values,
                                            const std::string& canonical) {
    INFO(spec);
    const brdfbake::ModelConfig m = brdfbake::resolve_model(spec);
    CHECK(m.id == id);
    for (const auto& s : slot_values) {
        INFO("slot " << s.first);
        CHECK(m.params[s.first] == s.second);
    }
    CHECK(m.canonical == canonical);
    return m;
}

}  // namespace testing

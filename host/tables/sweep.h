// The roughness sweep of a table: which parameter slots of a model hold the alpha that a table's
// roughness axis overwrites per texel. One place for `brdfbake lut` and the scene planner.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "brdfbake/spec.h"

namespace brdfbake {

/// The parameter slots that hold alpha_x and alpha_y of a model whose roughness tables sweep.
/// Throws Error saying why a model has none (not a microfacet model; Torrance-Sparrow with the
/// Blinn distribution has an exponent instead).
std::vector<int> sweep_slots(const ModelConfig& model);

/// A model spec without its roughness, resolved with a placeholder alpha that a table overwrites
/// per texel; `canonical` leaves the placeholder out ("ggx" -> "ggx:shadowing=correlated").
/// Throws Error for an unknown model or key, or a model without a roughness to sweep.
ModelConfig sweep_model(const std::string& spec_without_alpha);

/// sweep_model, or nothing where it throws (a model without a roughness to sweep, or a bad spec).
std::optional<ModelConfig> try_sweep_model(const std::string& spec_without_alpha);

}  // namespace brdfbake

// The roughness sweep of a table: a model spec resolved without its roughness, which a table's
// roughness axis sets per texel in the slots the model registry names (roughness_slots in
// brdfbake/spec.h). One place for `brdfbake lut` and the scene planner.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "brdfbake/spec.h"

namespace brdfbake {

/// A model spec without its roughness, resolved with a placeholder alpha that a table overwrites
/// per texel; `canonical` leaves the placeholder out ("ggx" -> "ggx:shadowing=correlated").
/// Throws Error for an unknown model or key, or a model without a roughness to sweep. `simulated`:
/// a scattering=multiple spec is taken (lut albedo's walks), else refused (resolve_model).
ModelConfig sweep_model(const std::string& spec_without_alpha, bool simulated = false);

/// sweep_model, or nothing where it throws (a model without a roughness to sweep, or a bad spec).
std::optional<ModelConfig> try_sweep_model(const std::string& spec_without_alpha);

}  // namespace brdfbake

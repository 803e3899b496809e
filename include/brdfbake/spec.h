// Model and Fresnel specifications: `name:key=value,key=value`, parsed, checked
// against the registry of known models, and resolved to the parameter block the kernels take.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace brdfbake {

/// A spec string split into its name and its key=value pairs, in the order given.
struct Spec {
    std::string name;
    std::vector<std::pair<std::string, std::string>> keys;
};

/// Splits `name:key=value,...`; throws Error on a malformed string or a repeated key.
Spec parse_spec(const std::string& text);

/// Parameters as the shared BRDF headers take them (bb_params): BB_MAX_PARAMS slots.
using ParamBlock = std::array<double, 8>;

/// A model spec resolved against the registry.
struct ModelConfig {
    int id = 0;                 // BB_MODEL_* of brdf/models.h
    std::string name;           // spec name, e.g. "ggx"
    std::string canonical;      // spec with every parameter spelled out, e.g. "ggx:alpha=0.5,shadowing=correlated"
    ParamBlock params{};        // slots as the model header defines them
    bool anisotropic = false;   // albedo depends on phi_o
    bool uses_fresnel = false;  // the model multiplies by a Fresnel term
};

/// A Fresnel spec resolved against the registry.
struct FresnelConfig {
    int kind = 0;           // BB_FRESNEL_* of brdf/fresnel.h
    std::string canonical;  // e.g. "none", "schlick:f0=0.04"
    ParamBlock params{};
};

/// Resolves a model spec; throws Error naming the problem (unknown model or key, value out of
/// range, not a finite number).
ModelConfig resolve_model(const std::string& text);

/// Resolves a Fresnel spec; throws Error as resolve_model does. `wavelength_nm` is the
/// --wavelength option (0 when not given), needed by measured metals (metal:Al, nk:FILE).
FresnelConfig resolve_fresnel(const std::string& text, double wavelength_nm = 0.0);

/// Names of the known models, for help texts and error messages.
std::vector<std::string> model_names();

/// Parses a finite floating-point number; `what` names it in the error message.
double parse_number(const std::string& text, const std::string& what);

}  // namespace brdfbake

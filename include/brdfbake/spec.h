// Model and Fresnel specifications: `name:key=value,key=value`, parsed, checked
// against the registry of known models, and resolved to the parameter block the kernels take.
#pragma once

#include <array>
#include <functional>
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

/// What a table's roughness axis (its alpha) sets in a model (ModelTraits::roughness_axis): a
/// microfacet model's alpha itself, in the registry's ALPHA_X and ALPHA_Y slots; a model without
/// them may name one key that a stated mapping of alpha drives (oren-nayar's sigma, the Phong
/// lobes' exponent n: host/models/spec.cpp, roughness_axis_of). Tables state a mapped axis in
/// their header (attribute roughness_axis).
struct RoughnessAxis {
    const char* key = nullptr;                // the spec key the axis sets; nullptr: no roughness axis
    const char* mapping = "";                 // the mapping with its source, as table headers state it
    double (*value)(double alpha) = nullptr;  // the key's value at a table alpha; nullptr: alpha itself
    double alpha_lo = 0.0, alpha_hi = 0.0;    // the alphas the mapping covers (a mapped axis: tables
                                              // compute alpha below lo at lo, refuse above hi)
    int slot = -1;                            // the mapped key's parameter slot
};

/// A model's entry in the model registry (brdf/model_registry.h, one row of its table), as the
/// host sees it.
struct ModelTraits {
    int id;                        // BB_MODEL_* of brdf/model_registry.h
    const char* name;              // spec name, e.g. "ggx"
    const char* example;           // an example spec, for the generic tests
    bool uses_fresnel;             // multiplies by the Fresnel term of --fresnel
    bool halfvector_quadrature;    // the quadrature runs in half-vector space (else the sampler's square)
    bool cosine_sampler;           // the sampler is the cosine warp
    bool delta;                    // a delta lobe: the albedo is analytic
    bool samples_disk;             // the vector path albedo_replicas_disk
    bool samples_vector;           // the vector path albedo_replicas_points (importance)
    bool evals_vector;             // the vector path albedo_replicas_points (qmc)
    bool reciprocal;               // f(wo, wi) = f(wi, wo)
    int alpha_x_slot, alpha_y_slot;  // the slots a roughness axis sweeps; -1: none
    int exponent_slot;             // a sampler-space cosine-power lobe's exponent N; -1: none
    bool kinked_quadrature;        // the quadrature's error estimate never assumes geometric convergence
    bool energy_conserving_example;  // the example's albedo is at most 1
    bool stochastic;               // its value is an estimate: sampling methods only, never quadrature
    bool measured;                 // a measured table: tables are E(mu_o) and Eavg of it alone (no roughness)
    bool diffuse_key;              // takes diffuse=KD (brdf/smith.h): compute_albedo adds kd in closed form
    bool layer_walk;               // a layer's walk without pointwise f (BB_TRAIT_LAYER_WALK, integrate/sheen_volume.h)
    /// Why these parameters have no roughness to sweep although the model has alpha slots
    /// (torrance-sparrow with d=blinn), or nullptr.
    const char* (*roughness_refusal)(const ParamBlock& params);
    /// The planner's cost of one of its samples relative to GGX's (`plan`'s and `bake`'s estimates,
    /// host/scene/calibration.h); 1 unless measured to differ by more than 1.5x.
    double sample_cost;
    /// What a table's roughness axis sets (RoughnessAxis; key nullptr: the model has none).
    RoughnessAxis roughness_axis;
};

/// Every registered model, in the order of the registry's table.
const std::vector<ModelTraits>& model_registry();

/// The registry entry of a model id; throws Error for an unknown id.
const ModelTraits& model_traits(int id);

/// A model spec resolved against the registry.
struct ModelConfig {
    int id = 0;                 // BB_MODEL_* of brdf/models.h
    std::string name;           // spec name, e.g. "ggx"
    std::string canonical;      // spec with every parameter spelled out, e.g. "ggx:alpha=0.5,shadowing=correlated"
    ParamBlock params{};        // slots as the model header defines them
    bool anisotropic = false;   // albedo depends on phi_o
    bool uses_fresnel = false;  // the model multiplies by a Fresnel term
    /// The slot of the Smith shadowing choice (BB_SMITH_* of brdf/smith.h) of the Smith microfacet
    /// lobes (ggx, beckmann), which their resolver sets; -1: the model has none.
    int smith_shadowing_slot = -1;
    /// Its value is a random-walk estimate (ggx and beckmann with scattering=multiple,
    /// brdf/random_walk.h): only resolve_model_simulated returns such a configuration.
    bool simulated = false;
    /// The simulated rough dielectric (scattering=multiple with eta=E): reflected and transmitted
    /// energy, the exact dielectric Fresnel term of eta at every bounce (no --fresnel).
    bool dielectric_walk = false;

    /// The model's registry entry.
    const ModelTraits& traits() const { return model_traits(id); }
};

/// The parameter slots that a roughness axis (a table's alpha) sweeps: alpha_x's and alpha_y's.
/// Throws Error when the model has none ("model 'lambert' has no roughness alpha to sweep; ...").
std::vector<int> roughness_slots(const ModelConfig& model);

/// The parameters with a table's roughness alpha set through the model's roughness axis (its
/// alpha slots, or its mapped key at value(alpha)); throws Error as roughness_slots does.
ParamBlock with_roughness(const ModelConfig& model, ParamBlock params, double alpha);

/// The roughness axis of the model a spec names (its registry entry's; key nullptr for an unknown name).
RoughnessAxis roughness_axis_of_spec(const std::string& spec_text);

/// A Fresnel spec resolved against the registry.
struct FresnelConfig {
    int kind = 0;           // BB_FRESNEL_* of brdf/fresnel.h
    std::string canonical;  // e.g. "none", "schlick:f0=0.04"
    ParamBlock params{};
    /// BB_FRESNEL_TABLE: the node values of the tabulated curve (brdf/fresnel.h); empty otherwise.
    std::vector<double> curve;
};

/// F(cos) of a resolved term in double on the host, a tabulated curve included.
double fresnel_value(const FresnelConfig& f, double cos_theta);

/// Resolves a model spec; throws Error naming the problem (unknown model or key, value out of
/// range, not a finite number).
/// A simulated configuration (ModelConfig::simulated: scattering=multiple) is refused with one
/// line naming it: albedo, check, lobe, lut albedo and compensation take one, through
/// resolve_model_simulated.
ModelConfig resolve_model(const std::string& text);

/// Resolves as resolve_model, simulated configurations included.
ModelConfig resolve_model_simulated(const std::string& text);

/// Resolves a Fresnel spec; throws Error as resolve_model does. `wavelength_nm` is the
/// --wavelength option (0 when not given), needed by measured metals (metal:Al, nk:FILE).
FresnelConfig resolve_fresnel(const std::string& text, double wavelength_nm = 0.0);
/// resolve_fresnel of one spec at many wavelengths: a measured term's file or embedded table is
/// read once, here, not once per wavelength.
std::function<FresnelConfig(double wavelength_nm)> fresnel_over_wavelengths(const std::string& text);

/// Names of the known models, for help texts and error messages.
std::vector<std::string> model_names();

/// Parses a finite floating-point number; `what` names it in the error message.
double parse_number(const std::string& text, const std::string& what);

}  // namespace brdfbake

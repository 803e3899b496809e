// Lookup tables computed on the device: directional albedo, average albedo and the split-sum
// terms, over (mu_o, alpha); their grid conventions and the engines' presets.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/engine.h"
#include "brdfbake/table.h"

namespace brdfbake {

struct LutRequest {
    std::string kind;             // a TableKind's name (brdfbake/table_kinds.h): albedo, eavg, dfg, ...
    std::string model;            // model spec without the swept alpha, e.g. "ggx:shadowing=correlated"
    std::string fresnel = "none"; // albedo and eavg only
    double wavelength_nm = 0.0;   // a Fresnel term that depends on it: 0 gives the colour channels R, G, B
    /// Those channels: "srgb" (linear sRGB from the spectrum, CIE 1931 2-degree observer, D65),
    /// "acescg", or "wavelengths" (R, G, B at 650, 550, 450 nm: --rgb-wavelengths).
    std::string colour = "srgb";
    int width = 32;               // mu texels (albedo, dfg) or alpha texels (eavg)
    int height = 32;              // alpha texels (albedo, dfg); 1 for eavg
    std::string mu_map = "linear";      // linear: mu = u; sqrt: u = sqrt(mu), mu = u^2; sqrt-one-minus: u = sqrt(1 - mu)
    std::string alpha_map = "alpha";    // alpha: alpha = v; roughness: v = sqrt(alpha), alpha = v^2
    double alpha_lo = 0.0, alpha_hi = 1.0;  // range of the roughness-axis coordinate
    int depth = 16;               // eta texels (dielectric)
    double eta_lo = 1.0, eta_hi = 3.0;  // eta range (in eta, whatever the mapping): 0 < lo < hi <= 100
    /// The eta axis coordinate: linear (w = eta), f0 (w = ((eta - 1)/(eta + 1))^2, the reflectance
    /// at normal incidence) or cycles (w = sqrt((eta - 1)/(eta + 1)) = F0^(1/4), Cycles' glass
    /// tables); f0 and cycles need eta >= 1 (the inside view is the kind's 1/eta channels).
    std::string eta_map = "linear";
    /// Film thickness range in nanometres of the thin-film table's z axis (KHR_materials_iridescence's
    /// defaults 100 and 400): 0 <= lo <= hi <= 100000 (lo = hi with one texel).
    double thickness_lo = 100.0, thickness_hi = 400.0;
    /// Where the texels sit on every axis: centres ((i + 0.5)/N) or edges (i/(N - 1)).
    Texels texels = Texels::Centre;
    double mu_lo = 0.0, mu_hi = 1.0;  // range of the mu-axis coordinate (u of the mu mapping)
    /// A texel whose mu is below this is computed at it (mu = 0 has no direction to integrate
    /// from); the header says so where it happens.
    double mu_floor = 1e-4;
    /// The axes in their stored order x, y[, z], by name (mu or sqrt_mu, alpha or roughness, eta,
    /// f0 or cycles_z); empty: the kind's order (mu, roughness axis, eta).
    std::vector<std::string> axes;
    std::vector<std::string> flip;  // axes stored from their upper end (texel 0 at hi)
    std::uint64_t samples = 1u << 18;   // per texel (per mu node for eavg)
    Method method = Method::Importance; // with a fixed sample count; the dielectric tables: importance or quadrature
    ToleranceRequest tolerance;         // tolerance.tolerance > 0: refine every texel to it instead
    Precision precision = Precision::Float;
    /// gen-schlick and gen-schlick-ior: the quantity the table holds. ratio: s = E_w / E, exact
    /// for the model's own G2; cycles: Blender Cycles' estimator, E_w of the masking-only lobe
    /// (the model must have shadowing=masking; --preset cycles then sets it), not divided by E.
    /// sheen-ltc: ratio, the walks to the end (1000 scatterings, the rest reported as cut off);
    /// cycles, the paper's precomputation (brdf/sheen_volume.h: 16 scatterings, a walk still
    /// inside counted by its direction), the walks Cycles' table_sheen_ltc was fitted to.
    std::string estimator = "ratio";
    /// The ltc kind's channels: empty, its own (m00 ... distance_error); "three": three.js's
    /// ltc_1 (M^-1 / M^-1_11 packed) and ltc_2 (magnitude, fresnel, 0, 0) (docs/ltc_presets.md).
    std::string packing;
};

/// Sets width, height and depth from 1 to 3 sizes as `--size` reads them: N is NxN (N for a
/// 1D kind), WxH, and WxHxD for a kind with an eta axis (depth H when not given). Throws Error
/// for too many sizes or a 1D kind given a height. request.kind must be set first.
void set_lut_size(LutRequest& request, const std::vector<int>& sizes);

/// Checks a request without touching the device (kind, model, ranges, sizes, and the kind's own
/// checks in its registry entry, brdfbake/table_kinds.h); throws Error.
void validate_lut(const LutRequest& request);

/// Computes the table, its axes arranged as the request asks (arrange_axes). Throws Error for
/// bad input or non-finite results.
Table compute_lut(Engine& engine, const LutRequest& request);

/// The table compute_lut(request) returns, without values or errors, at no cost (a validated
/// request): its kind, its channels (the kind's value_channels), its model, and its axes arranged
/// as compute_lut arranges them: names, sizes, texels, and the ranges of the mu, alpha and eta
/// axes (a kind's own z axis, gen-schlick's cycles_z and thin-film's thickness_nm: name and size
/// only, range 0 to 1). What check_table_format reads: `lut -o FILE` refuses a format that cannot
/// hold the table before the compute.
Table lut_table_shape(const LutRequest& request);

/// The table kinds of the registry (brdfbake/table_kinds.h).
enum class TableKindId;

/// A preset's layout for one table kind: the request it writes for that kind.
struct PresetLayout {
    TableKindId kind;
    /// Every setting of the table but its kind and estimator (size, model, texels, ranges,
    /// mappings, axes, flips, precision, samples or tolerance).
    LutRequest settings;
    /// The model when the request asks for Blender Cycles' estimator (--estimator cycles of the
    /// gen-schlick kinds: Cycles' own tables hold the masking-only lobe); empty: settings.model.
    std::string cycles_estimator_model;
};

/// A preset: the settings that make a table replace one an engine ships (host/tables/presets.cpp;
/// README "Drop-in tables" says where each convention comes from). A row of data: one layout per
/// table kind it has a layout for.
struct LutPreset {
    std::string name;         // --preset NAME
    std::string engine;       // "glTF Sample Viewer", "Blender Cycles", ...
    std::string ships;        // the file or symbol the engine ships
    std::string extension;    // the file format the engine loads: "png", "h", "exr"
    bool half = false;        // an EXR of half floats (the engine's texture is 16-bit float)
    std::string summary;      // the layout in one line
    std::vector<PresetLayout> layouts;  // the first is the default kind
    std::vector<std::string> kinds;     // the layouts' kind names, in order (from the table-kind registry)

    /// The layout for the table kind of that name, or nullptr.
    const PresetLayout* layout(const std::string& kind) const;
    /// Replaces the request by the preset's layout for request.kind (the default layout, the
    /// first, for a kind without one of its own); the kind and the estimator stay.
    void apply(LutRequest& request) const;
};

/// Every preset, in help order.
const std::vector<LutPreset>& lut_presets();
/// The preset of that name; throws Error "unknown preset 'X'; known: ...".
const LutPreset& lut_preset(const std::string& name);

/// The options of `brdfbake lut` as a user gives them (the command line, and Python's lut(), which
/// initializes the fields in their order): an empty field was not given. apply_preset turns them
/// into a request.
struct LutSettings {
    std::optional<std::string> kind, preset, model, estimator, fresnel;
    std::optional<double> wavelength_nm;
    std::optional<std::vector<int>> size;  // N, W x H or W x H x D (set_lut_size)
    std::optional<std::string> mu_map, alpha_map, eta_map, texels;
    std::optional<std::vector<double>> alpha_range, eta_range, mu_range;  // LO, HI each
    std::optional<double> mu_floor;
    std::optional<std::vector<std::string>> axes, flip;
    std::optional<double> samples, tolerance, max_samples;
    std::optional<std::string> method, precision;
    std::optional<bool> half;
    std::optional<std::string> colour;  // --colour-space, or "wavelengths" for --rgb-wavelengths
    std::optional<std::vector<double>> thickness_range;  // LO, HI nm: the thin-film table's z axis
    std::optional<double> thickness_step;  // nm: the thin-film table's depth from its thickness range
};

/// Texels on every axis of a table without --size or a preset.
constexpr int kDefaultLutTexels = 32;

/// A request with what its files need beside it.
struct LutSetup {
    LutRequest request;
    bool half = false;  // EXR channels as half floats (--half, or the preset's engine texture)
};

/// The one merge of a preset and the options given beside it, for the command line and Python:
/// the preset's layout for the kind (the preset's first kind when none is given), then every
/// option given overrides its field; without a preset, the options over LutRequest's defaults
/// (--model required, kDefaultLutTexels on every axis). The method options (samples, tolerance, method, max_samples) count as one:
/// any of them given replaces the preset's, the others at their defaults. Throws Error with the
/// command line's messages; the request is then checked by validate_lut.
LutSetup apply_preset(const LutSettings& given);

}  // namespace brdfbake

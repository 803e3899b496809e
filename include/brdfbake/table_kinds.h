// The table kinds: one registry entry per kind with everything the rest of brdfbake asks about
// it (its axes and channels, the Fresnel term it holds, how it is validated and computed, and how
// the scene planner sizes and merges it). `brdfbake lut`, `plan`, `bake` and the bake index
// query this registry; none of them compares kind names.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "brdfbake/table.h"

namespace brdfbake {

enum class TableKindId { Albedo, Eavg, Dfg, Dielectric, Conductor, DfgMs, SheenAlbedo, DielectricEavg, GenSchlick, GenSchlickIor, DfgF82, SheenViewer, Ltc, SheenLtc, ThinFilm };

/// 1 whatever the request: the integrations per cell of most kinds.
int one_per_request(const LutRequest&);
/// {"E"} whatever the request: the value channel of most kinds.
std::vector<std::string> one_value_channel(const LutRequest&);
/// The request's Fresnel term at its wavelength: the Fresnel term of most kinds.
FresnelConfig request_fresnel(const LutRequest& r);

struct TableKind {
    using Programs = std::vector<std::string> (*)(const LutRequest&);
    using Compute = Table (*)(Engine&, const LutRequest&, const ModelConfig& swept_model, const FresnelConfig&);

    /// An entry with what most kinds share (one value channel, one integration per cell, the
    /// request's Fresnel term, no checks of its own); each kind then sets what differs.
    TableKind(TableKindId id, std::string name, std::string description, Programs kernel_programs, Compute compute)
        : id(id), name(std::move(name)), description(std::move(description)), kernel_programs(kernel_programs),
          compute(compute) {}

    TableKindId id;
    std::string name;         // the command-line and file spelling: "albedo", "dfg-ms", ...
    std::string description;  // one line for help texts

    // Axes. A 2D kind has x = mu and y = the roughness axis; a 1D kind has x = the roughness
    // axis only; eta_axis adds a z axis (3D, z-slices stacked along y): the eta axis, named by
    // --eta-map (eta, f0 or cycles_z), or the kind's own z axis where own_z_axis names it.
    bool one_dimensional = false;
    bool eta_axis = false;
    /// The name of the kind's own z axis, which --eta-map and --eta-range do not reach (the
    /// generalized-Schlick kinds: "cycles_z"); empty: the z axis is the eta axis.
    std::string own_z_axis;
    /// Integration cells per texel: 48 mu nodes (32 + 16 Gauss-Legendre) for the average albedo,
    /// 2 sides of the interface for the dielectric.
    int cells_per_texel = 1;

    // The Fresnel term.
    bool fresnel_factored_out = false;  // the table takes no --fresnel (the split-sum kinds)
    /// The table bakes the lobe's own Fresnel in (conductor); the other kinds hold F = 1, factor
    /// it out, or have eta as an axis, so that one table serves every Fresnel.
    bool bakes_lobe_fresnel = false;
    /// A Fresnel term that depends on the wavelength, without --wavelength, gives the table colour
    /// channels (conductor): --colour-space and --rgb-wavelengths apply to it, and to no other.
    bool spectral_colour = false;
    std::string plan_fresnel;  // the Fresnel in the table, in words (plan text); empty: the request's

    // What a lobe must have for this kind: an index of refraction (every kind with an eta axis),
    // a conductor Fresnel term; lobe_requirement says it (a scene's "tables" error).
    bool needs_conductor_fresnel = false;
    /// A Fresnel term this kind takes, for the tests and the bench that run every kind; empty: "none".
    std::string example_fresnel;
    /// The one model whose lobes this kind serves (a scene lobe of that model takes this kind by
    /// default, and only such lobes can take it); empty: any model.
    std::string required_model;
    std::string lobe_requirement;

    // The planner.
    bool tileable = false;     // `bake` may compute it in tiles along the roughness axis
    /// The kind writes Blender Cycles' estimator with LutRequest::estimator = "cycles" (the
    /// generalized-Schlick kinds; sheen-ltc: the paper's 16-scattering walks that Cycles' table
    /// fits); every other kind takes only "ratio", the default.
    bool cycles_estimator = false;
    double sample_cost = 1.0;  // the cost of one sample relative to an albedo sample
    /// Its cells are random walks (sheen-ltc): --samples walks a texel, no --tolerance; `bench`
    /// times it at a fixed walk count and reports its error without holding it to a tolerance.
    bool simulated = false;

    /// The value channels' names as the kind's compute names them (the error channel comes on
    /// top): the planner counts them, and lut_table_shape gives them to the writers' checks before
    /// the compute (a three.js file refuses 3 channels, a PNG more than 4).
    std::vector<std::string> (*value_channels)(const LutRequest&) = one_value_channel;
    /// The table's "model" attribute where it is not the request's swept model (sheen-ltc: the
    /// layer its walks simulate); empty: the model's canonical spec.
    std::string table_model;
    /// Integrations per cell (the split-sum kinds integrate twice, a measured conductor per RGB wavelength).
    int (*integrations)(const LutRequest&) = one_per_request;
    /// The names of the passes of a table that integrates its cells several times, one per
    /// integration in the order the kind runs them ("E (F = 1)", "B (F = Schlick, f0 = 0)");
    /// nullptr: one pass. Progress shows "pass k of n: NAME" (brdfbake/progress.h).
    std::vector<std::string> (*pass_names)(const LutRequest&) = nullptr;
    /// The kernel programs the table builds ("albedo|MODEL|FRESNEL-KIND", "dielectric|MODEL").
    Programs kernel_programs;
    /// The Fresnel term validation resolves (a measured conductor without --wavelength: at 650 nm).
    FresnelConfig (*fresnel)(const LutRequest&) = request_fresnel;
    /// The kind's own checks, after the common ones of validate_lut; throws Error.
    void (*validate)(const LutRequest&, const ModelConfig& swept_model, const FresnelConfig&) = nullptr;
    /// Computes the table of a validated request.
    Compute compute;
};

/// Pass names of a kind that integrates once per z slice: `first` (unless empty), then
/// "EACH at z slice k of N" for each of `slices`.
inline std::vector<std::string> z_slice_pass_names(const std::string& first, const std::string& each, int slices) {
    std::vector<std::string> names;
    if (!first.empty()) names.push_back(first);
    for (int k = 1; k <= slices; ++k)
        names.push_back(each + " at z slice " + std::to_string(k) + " of " + std::to_string(slices));
    return names;
}

/// Every kind, in help order.
const std::vector<const TableKind*>& table_kinds();
/// The kind of that name, or nullptr.
const TableKind* find_table_kind(const std::string& name);
/// The kind of that name; throws Error "unknown table kind 'X'; known: ...".
const TableKind& table_kind(const std::string& name);
const TableKind& table_kind(TableKindId id);
/// "albedo, eavg, ...": the kinds' names for messages.
std::string table_kind_names();
/// A table file read back (read_table_file, brdfbake/table.h: every format check) whose kind is
/// one brdfbake writes: a registry kind or the map of `brdfbake reciprocity`. Throws Error
/// "'PATH': its kind 'X' is not a table brdfbake writes (known: ...)" for any other.
Table read_table(const std::string& path);
/// The names of the axes a request of this kind gets, in the kind's order (mu or sqrt_mu unless
/// 1D, alpha or roughness, then the z axis: the kind's own or eta, f0, cycles_z by --eta-map):
/// what --axes and --flip take.
std::vector<std::string> table_axis_names(const TableKind& kind, const LutRequest& r);

}  // namespace brdfbake

// Scenes and the table plan: what a scene's materials need, merged into the fewest tables.
//
// A scene is either a brdfbake scene file (JSON) or a glTF 2.0 file (.gltf / .glb); both become
// the same list of materials, each a list of lobes with the model, Fresnel and parameter ranges
// that decide its tables. make_plan() turns that into the minimal set of LutRequests: one per
// (kind, model, Fresnel-in-the-table), with the roughness (and eta) ranges of every lobe that
// shares it merged. The kinds and their rules come from the table-kind registry
// (brdfbake/table_kinds.h). docs/scenes.md documents the schema, the glTF mapping and the rules.
//
// The code by responsibility: scene_parse.cpp (scene files), gltf_scene.cpp (glTF), needs.cpp
// (which tables a lobe needs), planner.cpp (make_plan), plan_report.cpp (plan_text, plan_json).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"

namespace brdfbake {

/// A closed interval of a parameter; lo == hi for a single value.
struct Interval {
    double lo = 0.0;
    double hi = 0.0;
};

/// One lobe of a material whose energy needs tables (a metal's specular, a glass interface,
/// a clear coat).
struct Lobe {
    std::string role;                // "metal", "specular", "dielectric", "transmission", "clearcoat", ...
    std::string model;               // canonical model spec without alpha: "ggx:shadowing=correlated"
    std::string model_name;          // "ggx"
    std::string fresnel = "none";    // the lobe's Fresnel (canonical spec, or a glTF description)
    double wavelength_nm = 0.0;      // for measured metals (metal:Au, nk:FILE)
    Interval alpha;                  // alpha (= roughness^2) range the material uses
    std::optional<Interval> eta;     // relative index of refraction range (dielectric lobes)
    std::optional<Interval> thickness;  // film thickness range in nm (thin-film lobes: KHR_materials_iridescence)
    std::vector<const TableKind*> kinds;  // table kinds the lobe needs (registry entries)
};

struct SceneMaterial {
    std::string name;
    std::vector<Lobe> lobes;         // empty: the material needs no table
    std::vector<std::string> notes;  // why no table, or what approximation was made
};

/// How tables are sized and computed; defaults chosen so that the example scene bakes in a few
/// seconds on two cores (docs/scenes.md). The scene file's "settings" and the command line
/// override them.
struct SceneSettings {
    std::uint64_t samples = 1u << 14;  // per texel
    int mu_texels = 32;                // mu axis (always the full [0, 1])
    int alpha_texels = 32;             // texels over the full roughness-axis coordinate [0, 1]
    double eta_step = 0.05;            // eta-axis spacing for a range of indices
    /// Thin-film tables: at most this many nm between thickness slices; a range [lo, hi] gets
    /// ceil((hi - lo) / thickness_step) + 1 slices (at most 256): 16 for glTF's 100-400 nm.
    double thickness_step = 20.0;
    std::string mu_map = "linear";     // see LutRequest
    std::string alpha_map = "roughness";
    /// The sheen lobes' tables: "charlie" (the Charlie albedo, the default) or "ltc" (the LTC sheen of
    /// Zeltner et al. 2022: the sheen-ltc table, a, b and R per mu and roughness; docs/sheen_ltc.md).
    std::string sheen_model = "charlie";
    Precision precision = Precision::Float;
    std::string table_format = "exr";  // exr, csv or h
    bool half = false;                 // half-float EXR channels
    /// Command line only (docs/scenes.md, "Overrides and engine layouts"):
    std::vector<std::string> tables;   // --tables: every lobe's tables are the listed kinds it can take
    std::string preset;                // --preset: the preset's kinds (of its model) in the engine's layout
    std::string target;                // --target gltf: the glTF renderers' LUT set
    bool size_from_command_line = false;  // --size given: engine-layout tables take it too
};

struct Scene {
    std::string path;
    std::string source;                 // "brdfbake scene" or "glTF 2.0"
    std::vector<SceneMaterial> materials;
    std::vector<std::string> warnings;  // what was not modelled, each naming the feature and where
    SceneSettings settings;
};

/// The largest relative index of refraction a scene's dielectric lobe is planned at: a JSON scene's
/// "eta" must lie in (1, kSceneEtaMax]; a glTF ior above it is planned at it, with a warning. The
/// dielectric tables' eta axis (up to 100) then always has room for its half-texel margin.
constexpr double kSceneEtaMax = 10.0;

/// Reads a scene by its extension: .json (brdfbake scene), .gltf or .glb (glTF 2.0).
/// Throws Error naming the file and the problem.
Scene load_scene(const std::string& path);

/// A brdfbake scene file's text; `path` names it in messages. Throws Error.
Scene parse_scene_json(const std::string& text, const std::string& path);

/// A glTF 2.0 file (.gltf or .glb) mapped to brdfbake materials (docs/scenes.md). Throws Error.
Scene load_gltf_scene(const std::string& path);

/// The canonical spec of a model with its roughness left out ("ggx" -> "ggx:shadowing=correlated"),
/// the form tables are keyed by. Throws Error for an unknown model or key.
std::string model_without_alpha(const std::string& spec);

/// Checks every setting's range (after the scene file and the command line set them); throws Error.
void check_settings(const SceneSettings& s);

/// The tables a lobe needs unless the scene names them: the dielectric table for a lobe with an
/// index of refraction, else albedo and eavg.
std::vector<const TableKind*> default_lobe_kinds(const Lobe& lobe);

/// The kind a scene's "tables" list names for `lobe`, checked against what the lobe has (an index
/// of refraction, a conductor Fresnel); throws Error prefixed with `ctx`.
const TableKind& lobe_table_kind(const std::string& name, const Lobe& lobe, const std::string& ctx);

/// The note for a lobe whose alpha starts below the kernels' floor BB_ALPHA_MIN: it is planned at
/// the floor (alpha 0, the smooth limit, included: a texel centre is never at 0).
std::string alpha_floor_note(double alpha_lo);

/// The kinds' names, in order.
std::vector<std::string> kind_names(const std::vector<const TableKind*>& kinds);

/// One table of the plan.
struct PlannedTable {
    const TableKind* kind = nullptr;     // the registry entry of request.kind
    std::string file;                    // file name inside the bake folder
    LutRequest request;                  // eta axis: see eta_lo, eta_hi, depth and apply_eta_axis
    double eta_lo = 0.0, eta_hi = 0.0;   // eta axis of kinds with one (TableKind::eta_axis)
    int depth = 1;
    Interval alpha;                      // the scene's merged alpha range (before texel padding)
    std::optional<Interval> eta;         // the scene's merged eta range
    /// The first and last texel centres as parameters (alpha; eta), and whether each sits exactly
    /// on the scene's extreme (false where the axis had to stop at 0 or at eta 1: the centre is
    /// then the nearest the axis can hold, and values between the extreme and it are clamped).
    Interval alpha_centres, eta_centres;
    bool alpha_lo_exact = true, alpha_hi_exact = true, eta_lo_exact = true, eta_hi_exact = true;
    std::string layout;                  // an engine's layout (--preset, --target): its summary; empty: the scene's
    bool half = false;                   // half-float EXR channels
    std::vector<std::string> serves;     // "material (role)"
    std::vector<std::string> materials;  // material names
    std::uint64_t cells = 0;             // integration cells (texels, or texels x quadrature nodes)
    std::uint64_t samples_total = 0;     // samples x cells (x integrations)
    double est_seconds = 0.0;            // integrating, writing the file and its preview
    double idle_compute_seconds = 0.0;   // its parts on idle cores: integrating (parallel)
    double idle_preview_seconds = 0.0;   // and the preview (one thread); table_estimate
    std::uint64_t est_memory = 0;        // bytes, host and device, while computing
    std::uint64_t file_bytes = 0;        // estimated size on disk
    std::string key;                     // canonical request text (hashed)
    std::string hash;                    // 16 hex digits of FNV-1a over key
    std::string unavailable;             // why this build cannot compute it (empty: it can)
};

struct Plan {
    std::string scene;
    std::string source;
    std::vector<PlannedTable> tables;
    std::vector<std::string> models;          // models whose kernels the bake builds
    std::vector<SceneMaterial> materials;     // the scene's materials, as mapped
    std::vector<std::string> no_table;        // materials that need no table
    std::vector<std::string> warnings;
    int programs = 0;                         // kernel programs the bake builds (model x Fresnel kind)
    double build_seconds = 0.0;               // estimated kernel build time (first run; PoCL caches)
    bool cold_builds = false;                 // PoCL's kernel cache was found cold: builds compile
    double slowdown = 1.0;                    // how much slower than idle cores the estimates assume
    double startup_seconds = 0.0;             // process, device and folder set-up
    int report_checks = 0;                    // lobe checks of the bake report (index.html)
    double report_seconds = 0.0;              // their estimated time (bake --no-report skips them)
    double samples_per_second = 0.0;          // throughput the estimates assume
    std::string throughput_basis;             // where that number comes from
    SceneSettings settings;
};

struct Calibration;  // scene/calibration.h

/// The minimal set of tables for a scene. Throws Error for a lobe that cannot be tabulated.
/// Estimates from `calibration` where it has figures for this machine, else the built-in ones.
Plan make_plan(const Scene& scene, const Calibration* calibration = nullptr);

/// A table's estimate when the machine runs `slowdown` times slower than on idle cores (the
/// plan's is table_estimate(t, plan.slowdown); a bake re-estimates with the slowdown it measures).
double table_estimate(const PlannedTable& t, double slowdown);

/// The plan as text (--format table) or as one JSON object (--format json).
std::string plan_text(const Plan& plan);

/// Warnings as a person reads them: those that differ only in the material they name ("material
/// 'X': REST") become one line, "REST (N materials: X, Y, Z)"; the others stay as they are, in
/// their order. The index keeps every warning; plan, bake and the report show these.
std::vector<std::string> grouped_warnings(const std::vector<std::string>& warnings);
std::string plan_json(const Plan& plan);

/// Copies the eta axis of a planned table of a kind with one (dielectric) into its request.
void apply_eta_axis(const PlannedTable& t, LutRequest& request);

}  // namespace brdfbake

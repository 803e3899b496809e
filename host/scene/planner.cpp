// The planner: a scene's table needs merged into the fewest tables, each sized, named, keyed and
// estimated by its kind's registry entry (brdfbake/table_kinds.h).
#include <algorithm>
#include <functional>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>
#include <unordered_set>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/version.h"
#include "engine/hash.h"
#include "models/key_reader.h"
#include "scene/calibration.h"
#include "scene/scene.h"
#include "scene/scene_text.h"
#include "tables/lut_common.h"

namespace brdfbake {

namespace {

using scene_text::join;

/// An axis of `n` texels (texel centres) over [lo, hi] of a coordinate whose first and last texel
/// centres fall on c_lo and c_hi; a single value gets one texel centred on it. The half-texel
/// margins stay within [floor, ceil]: a single value near either gets a narrower texel, and a range
/// whose margin would cross one starts (or ends) the axis there, keeping the centre at its other
/// end on the scene's value; the centre at the stopped end is then inside the scene's range, and
/// lo_exact (hi_exact) false.
struct AxisPlan {
    double lo, hi;
    int n;
    double first, last;  // the first and last texel centres
    bool lo_exact, hi_exact;
};

AxisPlan plan_axis(double c_lo, double c_hi, int n_full_range, double full_width, double floor, double ceil, int max_n) {
    const double w = c_hi - c_lo;
    const double tiny = 1e-12 * std::max(1.0, std::fabs(c_hi));
    const double h0 = 0.5 * full_width / n_full_range;
    if (w <= tiny) {
        const double h = std::min({h0, c_lo - floor, ceil - c_lo});
        if (h > tiny) return {c_lo - h, c_lo + h, 1, c_lo, c_lo, true, true};
        // On the floor or the ceiling itself: one texel of the usual width inside the axis.
        const double lo = c_lo - floor <= tiny ? floor : std::max(floor, ceil - 2 * h0);
        const double hi = std::min(ceil, lo + 2 * h0);
        const double mid = 0.5 * (lo + hi);
        return {lo, hi, 1, mid, mid, false, false};
    }
    int n = int(std::ceil(n_full_range * w / full_width - 1e-9)) + 1;
    n = std::max(2, std::min(n, std::max(2, max_n)));
    const double pad = w / (2.0 * (n - 1));
    double lo = c_lo - pad, hi = c_hi + pad;
    const bool lo_out = lo < floor - tiny, hi_out = hi > ceil + tiny;
    if (lo_out && hi_out) {
        lo = floor;
        hi = ceil;
    } else if (lo_out) {
        lo = floor;  // the last centre stays on c_hi
        hi = std::min(ceil, floor + (c_hi - floor) * n / (n - 0.5));
    } else if (hi_out) {
        hi = ceil;  // the first centre stays on c_lo
        lo = std::max(floor, (c_lo * n - ceil * 0.5) / (n - 0.5));
    }
    lo = std::max(lo, floor);
    hi = std::min(hi, ceil);
    const double first = lo + (hi - lo) * 0.5 / n, last = lo + (hi - lo) * (n - 0.5) / n;
    const double tol = 1e-9 * std::max(1.0, std::fabs(c_hi));
    return {lo, hi, n, first, last, std::fabs(first - c_lo) <= tol, std::fabs(last - c_hi) <= tol};
}

/// The largest alpha `model` takes (sheen's fit ends at 1, GGX goes to 10), tried at a few values
/// from the top; 0 when none is taken.
double largest_alpha(const std::string& model) {
    const RoughnessAxis axis = roughness_axis_of_spec(model);
    if (axis.value) return axis.alpha_hi;  // a mapped axis (oren-nayar's sigma, Phong's n) ends there
    for (double a : {10.0, 9.0, 4.0, 1.0}) {
        try {
            resolve_model(model + (model.find(':') == std::string::npos ? ":" : ",") + "alpha=" + format_number(a));
            return a;
        } catch (const Error&) {
        }
    }
    return 0.0;
}

/// The largest eta a table's eta axis takes (validate_lut: 0 < lo < hi <= 100).
constexpr double kEtaAxisMax = 100.0;

double alpha_coordinate(double alpha, const std::string& map) { return map == "roughness" ? std::sqrt(alpha) : alpha; }
double alpha_of_coordinate(double c, const std::string& map) { return map == "roughness" ? c * c : c; }

/// Texel centre i of an axis of n texels over [lo, hi].
double centre_of(double lo, double hi, int n, int i) { return lo + (hi - lo) * (i + 0.5) / n; }

const TableKind& table_kind_by_name(const std::string& name) {
    const TableKind* k = find_table_kind(name);
    if (!k) throw Error("internal error: no table kind '" + name + "'");
    return *k;
}

/// --tables: every lobe's tables become the listed kinds it can take (a dielectric table needs an
/// index of refraction, ...); a lobe that can take none keeps none, and a warning names it.
void override_lobe_kinds(std::vector<SceneMaterial>& materials, const std::vector<std::string>& names,
                         std::vector<std::string>& warnings) {
    for (const auto& n : names)
        if (!find_table_kind(n)) throw Error("--tables: unknown table kind '" + n + "' (known: " + table_kind_names() + ")");
    bool any = false;
    std::vector<std::string> without;
    for (auto& m : materials)
        for (auto& l : m.lobes) {
            l.kinds.clear();
            for (const auto& n : names) {
                try {
                    const TableKind* k = &lobe_table_kind(n, l, "--tables");
                    if (std::find(l.kinds.begin(), l.kinds.end(), k) == l.kinds.end()) l.kinds.push_back(k);
                } catch (const Error&) {
                    // this lobe cannot take that kind
                }
            }
            if (l.kinds.empty()) without.push_back(m.name + " (" + l.role + ")");
            any = any || !l.kinds.empty();
        }
    if (!any) throw Error("--tables " + join(names, ",") + ": no lobe of the scene can take these table kinds");
    if (!without.empty())
        warnings.push_back("--tables " + join(names, ",") + ": no listed kind fits " + join(without) + "; planned without a table");
}

std::string hex64(std::uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
    return b;
}

std::string g17(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

// The cost model of `plan`'s estimates, checked against `bake`'s wall time by
// benchmarks/plan_estimates.sh (docs/scenes.md, "Estimates"; the measurements:
// benchmarks/results/plan-estimates-2c-shared.md). A table costs its samples at its rate, plus the
// fixed costs of a table, its preview and the bake. The rates and fixed costs are this machine's
// where a calibration file has them (scene/calibration.h: what earlier bakes measured), the
// built-in figures (builtin_figures) otherwise; there, a table's rate is GGX albedo's divided by
// its kind's cost per sample (the registry's sample_cost) and its model's (below).

/// The fixed figures the estimates use: the calibration's where it has them, else the built-in ones.
struct Figures {
    const Calibration* calibration = nullptr;  // nullptr: built-in figures only
    double program = builtin_figures::kSecondsPerProgram;
    double check = builtin_figures::kSecondsPerReportCheck;
    /// How much slower than on idle cores parallel stages (the kernels) and single-threaded ones
    /// (start-up, builds, previews) run now (calibration.h).
    double parallel = 1.0, serial = 1.0;
    bool cold = false;  // PoCL's kernel cache is cold: builds cost a compile each

    explicit Figures(const Calibration* c) {
        if (c) {
            parallel = c->slowdown;
            serial = serial_slowdown(c->slowdown);
            cold = c->cold_cache;
        }
        if (!c || !c->applies()) return;
        calibration = c;
        if (c->build_seconds_per_program.known()) program = c->build_seconds_per_program.value;
        if (c->report_check_seconds.known()) check = c->report_check_seconds.value;
    }
};

/// What a group of lobes needs: one table per (kind, model, Fresnel in the table).
struct Group {
    const TableKind* kind = nullptr;
    std::string model, model_name, fresnel;
    double wavelength = 0.0;
    Interval alpha;
    std::optional<Interval> eta;
    std::optional<Interval> thickness;  // thin-film tables: the lobes' film thickness range (nm)
    std::vector<std::string> serves, materials;
    std::unordered_set<std::string> serves_seen, materials_seen;  // for adding each once, fast
    bool transmission = false;  // serves a lobe that transmits
};

/// Appends `x` unless `seen` has it (a list of a scene's many materials stays linear to build).
void add_once(std::vector<std::string>& list, std::unordered_set<std::string>& seen, const std::string& x) {
    if (seen.insert(x).second) list.push_back(x);
}

/// The scene's table needs grouped: one group per (kind, model, Fresnel in the table), with the
/// roughness (and eta) ranges of its lobes merged; materials without lobes go to plan.no_table.
std::vector<Group> group_needs(const std::vector<SceneMaterial>& materials, Plan& plan) {
    std::vector<Group> groups;
    std::map<std::tuple<const TableKind*, std::string, std::string, double>, size_t> index;
    for (const auto& m : materials) {
        if (m.lobes.empty()) {
            plan.no_table.push_back(m.name + (m.notes.empty() ? "" : " (" + m.notes.front() + ")"));
            continue;
        }
        for (const auto& lobe : m.lobes) {
            for (const TableKind* kind : lobe.kinds) {
                // Which Fresnel the table itself holds: albedo and eavg are computed with F = 1 (the
                // lobe's Fresnel enters at render time through its hemispherical average), the
                // split-sum kinds factor it out, a dielectric table has eta as an axis; only a
                // conductor table bakes the lobe's own Fresnel in.
                const std::string fresnel = kind->bakes_lobe_fresnel ? lobe.fresnel : "none";
                const double wl = kind->bakes_lobe_fresnel ? lobe.wavelength_nm : 0.0;
                const auto [at, added] = index.emplace(std::make_tuple(kind, lobe.model, fresnel, wl), groups.size());
                if (added) {
                    Group g;
                    g.kind = kind;
                    g.model = lobe.model;
                    g.model_name = lobe.model_name;
                    g.fresnel = fresnel;
                    g.wavelength = wl;
                    g.alpha = lobe.alpha;
                    if (kind->eta_axis) g.eta = lobe.eta;
                    g.thickness = lobe.thickness;
                    groups.push_back(std::move(g));
                }
                Group& g = groups[at->second];
                if (!added) {
                    g.alpha.lo = std::min(g.alpha.lo, lobe.alpha.lo);
                    g.alpha.hi = std::max(g.alpha.hi, lobe.alpha.hi);
                    if (kind->eta_axis && lobe.eta) {
                        g.eta->lo = std::min(g.eta->lo, lobe.eta->lo);
                        g.eta->hi = std::max(g.eta->hi, lobe.eta->hi);
                    }
                    if (g.thickness && lobe.thickness)
                        g.thickness = Interval{std::min(g.thickness->lo, lobe.thickness->lo),
                                               std::max(g.thickness->hi, lobe.thickness->hi)};
                }
                g.transmission = g.transmission || lobe.role == "transmission";
                add_once(g.serves, g.serves_seen, m.name + " (" + lobe.role + ")");
                add_once(g.materials, g.materials_seen, m.name);
            }
        }
    }
    return groups;
}

/// Whether the model `name` is a measured table (no roughness axis).
bool measured_model(const std::string& name) {
    for (const ModelTraits& t : model_registry())
        if (name == t.name) return t.measured;
    return false;
}

/// A measured model's file name without folder and extension ("paint" for file=a/paint.binary).
std::string measured_file_stem(const std::string& model) {
    for (const auto& kv : parse_spec(model).keys)
        if (kv.first == "file") {
            std::string f = kv.second.substr(kv.second.find_last_of('/') + 1);
            return f.substr(0, f.find('.'));
        }
    return "";
}

/// One table in `preset`'s layout for `kind` and `model`, serving the groups `take` selects.
PlannedTable engine_table(const LutPreset& preset, const SceneSettings& s, const std::string& kind,
                          const std::string& model, const std::string& file, const std::vector<Group>& groups,
                          const std::function<bool(const Group&)>& take) {
    PlannedTable t;
    t.kind = &table_kind_by_name(kind);
    LutRequest& r = t.request;
    r.kind = kind;
    preset.apply(r);
    r.model = model_without_alpha(model);
    if (!(r.tolerance.tolerance > 0)) r.samples = s.samples;
    if (s.size_from_command_line) {
        if (t.kind->one_dimensional) r.width = s.alpha_texels;
        else {
            r.width = s.mu_texels;
            r.height = s.alpha_texels;
        }
    }
    const int n = t.kind->one_dimensional ? r.width : r.height;
    const bool edge = r.texels == Texels::Edge;
    const double first = edge ? r.alpha_lo : centre_of(r.alpha_lo, r.alpha_hi, n, 0);
    const double last = edge ? r.alpha_hi : centre_of(r.alpha_lo, r.alpha_hi, n, n - 1);
    t.alpha_centres = {alpha_of_coordinate(first, r.alpha_map), alpha_of_coordinate(last, r.alpha_map)};
    t.alpha = {alpha_of_coordinate(r.alpha_lo, r.alpha_map), alpha_of_coordinate(r.alpha_hi, r.alpha_map)};
    t.layout = preset.engine + " (preset " + preset.name + "): " + preset.summary +
               (s.size_from_command_line ? "; size from the command line" : "");
    t.half = preset.half;
    t.file = file;
    if (t.kind->eta_axis) {  // the preset's eta axis (apply_eta_axis copies it back)
        t.eta_lo = r.eta_lo;
        t.eta_hi = r.eta_hi;
        t.depth = r.depth;
    }
    std::unordered_set<std::string> serves_seen, materials_seen;
    for (const Group& g : groups)
        if (take(g)) {
            for (const auto& x : g.serves) add_once(t.serves, serves_seen, x);
            for (const auto& x : g.materials) add_once(t.materials, materials_seen, x);
        }
    return t;
}

/// The engine layouts: --target gltf bakes the glTF renderers' set; --preset NAME gives the tables
/// of the preset's kinds (of its model) in the engine's layout instead of the scene's. The groups
/// they serve leave `groups`.
std::vector<PlannedTable> plan_engine_tables(const SceneSettings& s, std::vector<Group>& groups, Plan& plan) {
    std::vector<PlannedTable> out;
    if (s.target.empty() && s.preset.empty()) return out;
    const LutPreset& preset = lut_preset(s.target.empty() ? s.preset : s.target);
    if (s.target == "gltf") {
        // The glTF Sample Viewer's LUTs: the split-sum GGX table for every GGX lobe, the sheen
        // tables (lut_charlie: the ashikhmin visibility of its IBL; lut_sheen_E: the charlie
        // visibility of KHR_materials_sheen's albedo scaling; docs/models.md) when a sheen is
        // present, and the scene's dielectric tables where a lobe transmits.
        LutRequest dfg;  // the preset's split-sum table, of its model
        dfg.kind = "dfg";
        preset.apply(dfg);
        const std::string dfg_model = model_without_alpha(dfg.model);
        out.push_back(engine_table(preset, s, dfg.kind, dfg_model, "lut_ggx." + preset.extension, groups,
                                   [&](const Group& g) { return g.model == dfg_model; }));
        const TableKind& sheen = table_kind(TableKindId::SheenViewer);  // the viewer's sheen LUTs
        auto is_sheen = [&](const Group& g) { return g.model_name == sheen.required_model; };
        if (std::any_of(groups.begin(), groups.end(), is_sheen)) {
            out.push_back(engine_table(preset, s, sheen.name, sheen.required_model + ":visibility=ashikhmin",
                                       "lut_charlie." + preset.extension, groups, is_sheen));
            out.push_back(engine_table(preset, s, sheen.name, sheen.required_model + ":visibility=charlie",
                                       "lut_sheen_E." + preset.extension, groups, is_sheen));
        }
        groups.erase(std::remove_if(groups.begin(), groups.end(),
                                    [](const Group& g) { return !(g.kind->eta_axis && g.transmission); }),
                     groups.end());
        return out;
    }
    std::vector<std::string> preset_models;  // "kind: model", for the warning below
    for (const std::string& kind : preset.kinds) {
        // The preset's model for this kind (Cycles' glass tables use its transmission shadowing,
        // its other tables the default).
        LutRequest probe;
        probe.kind = kind;
        preset.apply(probe);
        const std::string preset_model = model_without_alpha(probe.model);
        preset_models.push_back(kind + ": " + preset_model);
        auto ours = [&](const Group& g) { return g.kind->name == kind && g.model == preset_model; };
        if (std::none_of(groups.begin(), groups.end(), ours)) continue;
        out.push_back(engine_table(preset, s, kind, preset_model, preset.name + "-" + kind + "." + preset.extension,
                                   groups, ours));
        groups.erase(std::remove_if(groups.begin(), groups.end(), ours), groups.end());
    }
    if (out.empty())
        plan.warnings.push_back("--preset " + preset.name + ": no table of the scene is of the preset's kinds and "
                                "models (" + join(preset_models) + "); the scene's tables are planned as usual");
    return out;
}

/// File names (without extension): kind-model, with the model's non-default keys (and a
/// conductor's Fresnel) where they tell two tables apart, and a short hash where even that does not.
std::vector<std::string> table_names(const std::vector<Group>& groups) {
    auto sanitize = [](std::string x) {
        for (char& c : x)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '-';
        return x;
    };
    std::vector<std::string> names;
    for (const auto& g : groups) {
        std::string n = g.kind->name + "-" + g.model_name;
        if (measured_model(g.model_name))  // the file's name, not its folder
            n += "-" + sanitize(measured_file_stem(g.model));
        else if (g.model != model_without_alpha(g.model_name) && g.model.find(':') != std::string::npos)
            n += "-" + sanitize(g.model.substr(g.model.find(':') + 1));
        if (g.kind->bakes_lobe_fresnel) n += "-" + sanitize(g.fresnel) + (g.wavelength > 0 ? "-" + format_number(g.wavelength) + "nm" : "");
        names.push_back(n);
    }
    std::map<std::string, int> name_count;
    for (const auto& n : names) ++name_count[n];
    for (size_t i = 0; i < names.size(); ++i)
        if (name_count[names[i]] > 1) names[i] += "-" + hex64(fnv1a(groups[i].model + "|" + groups[i].fresnel)).substr(0, 6);
    return names;
}

/// Sizes, estimates, file name, request key and hash of a table whose request is set, and whether
/// this build can compute it; then adds it to the plan.
void finish_table(Plan& plan, const Figures& figures, PlannedTable t, const std::string& file, bool half,
                  const std::string& model_name) {
    const LutRequest& r = t.request;
    const TableKind& kind = *t.kind;
    t.half = half;
    const std::uint64_t texels = std::uint64_t(r.width) * r.height * t.depth;
    t.cells = texels * std::uint64_t(kind.cells_per_texel);
    t.samples_total = t.cells * r.samples * std::uint64_t(kind.integrations(r));
    t.idle_compute_seconds =
        table_seconds(figures.calibration, kind.name, model_name, precision_name(r.precision), double(t.samples_total));
    t.idle_preview_seconds = preview_seconds(figures.calibration, double(texels));
    t.est_seconds = table_estimate(t, figures.parallel);
    const std::uint64_t channels = kind.value_channels(r).size() + 1;  // values + error
    // Per cell: ~170 B of device buffers (float; 16 replicas) and ~470 B on the host while the
    // kernel runs; the finished table holds doubles.
    t.est_memory = t.cells * 640 + texels * channels * 8;
    const std::string ext = file.substr(file.find_last_of('.') + 1);
    if (ext == "exr") t.file_bytes = texels * channels * (half ? 2 : 4) + 2048;
    else if (ext == "png") t.file_bytes = texels * 4 * 2 + 1024;
    else t.file_bytes = texels * channels * 26 + 1024;
    t.file = file;

    std::ostringstream k;
    k << "brdfbake " << BRDFBAKE_VERSION << "; kind=" << r.kind << "; model=" << r.model << "; fresnel=" << r.fresnel
      << "; wavelength_nm=" << g17(r.wavelength_nm) << "; size=" << r.width << "x" << r.height;
    if (kind.eta_axis) k << "x" << t.depth << "; eta_range=" << g17(t.eta_lo) << "," << g17(t.eta_hi);
    if (kind.id == TableKindId::ThinFilm) k << "; thickness_range=" << g17(r.thickness_lo) << "," << g17(r.thickness_hi);
    k << "; mu_map=" << r.mu_map << "; alpha_map=" << r.alpha_map << "; alpha_range=" << g17(r.alpha_lo) << ","
      << g17(r.alpha_hi) << "; samples=" << r.samples << "; precision=" << precision_name(r.precision)
      << "; format=" << ext << (half ? "-half" : "");
    if (!t.layout.empty()) k << "; layout=" << t.layout;
    t.key = k.str();
    t.hash = hex64(fnv1a(t.key));

    try {
        LutRequest check = r;
        apply_eta_axis(t, check);
        validate_lut(check);
    } catch (const Error& e) {
        t.unavailable = e.what();
    }
    if (!t.unavailable.empty())
        plan.warnings.push_back("table '" + t.file + "' (for " + join(t.materials) + "): cannot be computed by "
                                "this build: " + t.unavailable);
    if (std::find(plan.models.begin(), plan.models.end(), model_name) == plan.models.end())
        plan.models.push_back(model_name);
    plan.tables.push_back(std::move(t));
}

/// The table of a group in the scene's layout: its request, and its roughness (and eta) axis
/// placed so that the first and last texel centres fall on the group's range.
PlannedTable group_table(const Group& g, const SceneSettings& s) {
    PlannedTable t;
    t.kind = g.kind;
    LutRequest& r = t.request;
    r.kind = g.kind->name;
    r.model = g.model;
    r.fresnel = g.fresnel;
    r.wavelength_nm = g.wavelength;
    r.mu_map = s.mu_map;
    r.alpha_map = s.alpha_map;
    r.samples = s.samples;
    r.precision = s.precision;
    t.alpha = g.alpha;
    t.eta = g.eta;
    t.serves = g.serves;
    t.materials = g.materials;
    if (measured_model(g.model_name)) {  // E(mu) along mu, Eavg one texel (kind_albedo.cpp)
        r.width = g.kind->one_dimensional ? 1 : s.mu_texels;
        r.height = 1;
        return t;
    }

    // Texel centres never hold alpha below the floor (the kernels' BB_ALPHA_MIN): the scene's
    // alpha 0 is planned there, the nearest a texel centre computes to the smooth limit.
    const double alpha_floor = double(BB_ALPHA_MIN);
    const double c_lo = alpha_coordinate(std::max(g.alpha.lo, alpha_floor), s.alpha_map);
    const double c_hi = std::max(c_lo, alpha_coordinate(g.alpha.hi, s.alpha_map));
    // The axis stops where the tables' roughness axis does (coordinate 3) or the model's alpha
    // range ends (sheen: 1), whichever is first.
    const double top = largest_alpha(g.model);
    const double ceil = top > 0 ? std::min(3.0, alpha_coordinate(top, s.alpha_map)) : 3.0;
    if (c_hi > ceil)
        throw Error("alpha up to " + format_number(g.alpha.hi) + " (" + join(g.materials) +
                    ") is beyond the tables' roughness axis, which stops at coordinate " + format_number(ceil));
    const AxisPlan a = plan_axis(c_lo, c_hi, s.alpha_texels, 1.0, 0.0, ceil, s.alpha_texels);
    r.alpha_lo = a.lo;
    r.alpha_hi = a.hi;
    t.alpha_centres = {alpha_of_coordinate(a.first, s.alpha_map), alpha_of_coordinate(a.last, s.alpha_map)};
    t.alpha_lo_exact = a.lo_exact && g.alpha.lo >= alpha_floor;
    t.alpha_hi_exact = a.hi_exact && g.alpha.hi >= alpha_floor;
    if (g.kind->one_dimensional) {
        r.width = a.n;
        r.height = 1;
    } else {
        r.width = s.mu_texels;
        r.height = a.n;
    }
    if (g.kind->eta_axis && g.thickness) {  // the thin-film table: slices at most thickness_step apart, or one
        r.thickness_lo = g.thickness->lo;
        r.thickness_hi = g.thickness->hi;
        t.depth = std::min(256, tables::thickness_slices(g.thickness->lo, g.thickness->hi, s.thickness_step));
        apply_eta_axis(t, r);
    } else if (g.kind->eta_axis) {
        const AxisPlan e = plan_axis(g.eta->lo, g.eta->hi, 1, s.eta_step, 1.0, kEtaAxisMax, 64);
        t.eta_lo = e.lo;
        t.eta_hi = e.hi;
        t.depth = e.n;
        t.eta_centres = {e.first, e.last};
        t.eta_lo_exact = e.lo_exact;
        t.eta_hi_exact = e.hi_exact;
        apply_eta_axis(t, r);
    }
    return t;
}

/// The kernel programs the bake builds and the lobe checks of its report, with their estimates.
void estimate_builds_and_report(Plan& plan, const Figures& figures) {
    // Programs: one albedo kernel per (model, Fresnel kind) and one dielectric kernel per model.
    std::set<std::string> programs;
    for (const auto& t : plan.tables)
        for (const std::string& p : t.kind->kernel_programs(t.request)) programs.insert(p);
    plan.programs = int(programs.size());
    plan.startup_seconds = figures.serial * builtin_figures::kStartupSeconds;
    // The bake report checks each lobe with a table at both ends of its roughness range; it builds
    // two programs per (model, Fresnel) of the lobes it checks (the scan and the albedo kernel).
    std::set<std::string> checks, checked_lobes;
    for (const auto& m : plan.materials)
        for (const auto& lobe : m.lobes)
            if (!lobe.kinds.empty()) {
                checked_lobes.insert(lobe.model + "|" + lobe.fresnel);
                for (double a : {lobe.alpha.lo, lobe.alpha.hi})
                    checks.insert(lobe.model + "|" + lobe.fresnel + "|" + std::to_string(a));
            }
    plan.report_checks = int(checks.size());
    plan.report_seconds = figures.parallel * figures.check * plan.report_checks;
    plan.cold_builds = figures.cold;
    if (!figures.cold) {
        plan.build_seconds = figures.serial * figures.program * plan.programs;
        return;
    }
    // A cold cache: every program compiles (the report's too), once per process the compiler starts.
    const int report_programs = 2 * int(checked_lobes.size());
    plan.build_seconds = figures.serial * (builtin_figures::kColdStartSeconds +
                                           builtin_figures::kColdSecondsPerProgram * plan.programs);
    plan.report_seconds += figures.serial * builtin_figures::kColdSecondsPerProgram * report_programs;
}

}  // namespace

void apply_eta_axis(const PlannedTable& t, LutRequest& request) {
    const TableKind* kind = t.kind ? t.kind : find_table_kind(t.request.kind);
    if (!kind || !kind->eta_axis) return;
    request.eta_lo = t.eta_lo;
    request.eta_hi = t.eta_hi;
    request.depth = t.depth;
}

double table_estimate(const PlannedTable& t, double slowdown) {
    return slowdown * t.idle_compute_seconds + serial_slowdown(slowdown) * t.idle_preview_seconds;
}

Plan make_plan(const Scene& scene, const Calibration* calibration) {
    check_settings(scene.settings);
    const SceneSettings& s = scene.settings;
    Plan plan;
    plan.scene = scene.path;
    plan.source = scene.source;
    plan.warnings = scene.warnings;
    plan.settings = s;
    const Figures figures(calibration);
    // GGX albedo's rate: the seconds of a large table's samples, its fixed part aside.
    const std::string albedo = table_kind(TableKindId::Albedo).name, precision = precision_name(s.precision);
    plan.samples_per_second = 1e9 / (table_seconds(figures.calibration, albedo, "ggx", precision, 2e9) -
                                     table_seconds(figures.calibration, albedo, "ggx", precision, 1e9));
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    if (figures.calibration)
        plan.throughput_basis = "calibrated on this machine from " + std::to_string(calibration->bakes) + " bake" +
                                (calibration->bakes == 1 ? "" : "s") + " (" + calibration->path +
                                "; built-in figures where it has none; docs/scenes.md)";
    else
        plan.throughput_basis = std::to_string(cores) + " hardware threads x 1.05e9 on idle cores, built-in (PoCL, float, "
                                "measured on the development machine; a bake calibrates them: docs/scenes.md)";
    if (calibration && !calibration->warning.empty()) plan.warnings.push_back(calibration->warning);

    plan.materials = scene.materials;
    if (s.sheen_model == "ltc")  // the sheen lobes' table is the LTC sheen's (docs/sheen_ltc.md, "Scenes")
        for (auto& m : plan.materials)
            for (auto& l : m.lobes)
                if (l.model_name == table_kind(TableKindId::SheenLtc).required_model) {
                    l.kinds = {&table_kind(TableKindId::SheenLtc)};
                    m.notes.push_back("sheen_model ltc: the sheen's table is sheen-ltc (a, b, R of the LTC sheen of "
                                      "Zeltner et al. 2022), not its Charlie albedo");
                }
    if (!s.tables.empty()) override_lobe_kinds(plan.materials, s.tables, plan.warnings);
    std::vector<Group> groups = group_needs(plan.materials, plan);
    std::vector<PlannedTable> engine_tables = plan_engine_tables(s, groups, plan);
    const std::vector<std::string> names = table_names(groups);
    for (size_t i = 0; i < groups.size(); ++i)
        finish_table(plan, figures, group_table(groups[i], s), names[i] + "." + s.table_format, s.half, groups[i].model_name);
    for (auto& t : engine_tables) {
        const std::string file = t.file;
        const std::string model_name = t.request.model.substr(0, t.request.model.find(':'));
        const bool half = t.half;
        finish_table(plan, figures, std::move(t), file, half, model_name);
    }
    estimate_builds_and_report(plan, figures);
    plan.slowdown = figures.parallel;
    // Idle-core seconds times how much slower the machine runs now (calibration.h).
    if (figures.parallel > 1.0) {
        plan.samples_per_second /= figures.parallel;
        char shared[200];
        std::snprintf(shared, sizeof shared,
                      "; times %.1f: the machine runs %.1fx slower than on idle cores now (%.1fx single-threaded stages)",
                      figures.parallel, figures.parallel, figures.serial);
        plan.throughput_basis += shared;
    }
    return plan;
}

}  // namespace brdfbake

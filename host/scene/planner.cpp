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

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/version.h"
#include "models/key_reader.h"
#include "scene/scene.h"
#include "scene/scene_text.h"

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

std::uint64_t fnv1a(const std::string& s) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

std::string g17(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

/// Samples per second the estimates assume: PoCL on one core of the development machine (AMD
/// EPYC, float, GGX albedo on the vector path, which `bake` uses; 2 shared cores under load;
/// benchmarks/results/scene-estimates-amd-epyc-2c.md) times the hardware threads.
constexpr double kSamplesPerSecondPerCore = 5.0e7;

/// A cold kernel build and first launch on PoCL (docs/scenes.md: 0.35 to 0.55 s for GGX).
constexpr double kSecondsPerProgram = 0.5;

/// Per table: launches, assembling and writing the file (measured: 0.01 to 0.1 s), and the preview
/// picture bake writes beside it (MathGL: 0.3 to 0.8 s on the shared development machine).
constexpr double kSecondsPerTable = 0.05;
constexpr double kSecondsPerPreview = 0.4;

/// Starting the process, the device and the bake folder (measured: about 0.3 s).
constexpr double kStartupSeconds = 0.3;

/// One lobe check of the bake report (host/plot/bake_report.cpp: 24 directions x 2^14 samples and
/// 16^3 reciprocity pairs; measured: 4 checks add 1.3 s of CPU to examples/scene.json's bake).
constexpr double kSecondsPerReportCheck = 0.35;

}  // namespace

void apply_eta_axis(const PlannedTable& t, LutRequest& request) {
    const TableKind* kind = t.kind ? t.kind : find_table_kind(t.request.kind);
    if (!kind || !kind->eta_axis) return;
    request.eta_lo = t.eta_lo;
    request.eta_hi = t.eta_hi;
    request.depth = t.depth;
}

Plan make_plan(const Scene& scene) {
    check_settings(scene.settings);
    const SceneSettings& s = scene.settings;
    Plan plan;
    plan.scene = scene.path;
    plan.source = scene.source;
    plan.warnings = scene.warnings;
    plan.settings = s;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    plan.samples_per_second = kSamplesPerSecondPerCore * cores;
    plan.throughput_basis = std::to_string(cores) + " hardware threads x 5.0e7 (PoCL, float, measured; docs/scenes.md)";

    // Group the needs: one table per (kind, model, Fresnel in the table).
    struct Group {
        const TableKind* kind = nullptr;
        std::string model, model_name, fresnel;
        double wavelength = 0.0;
        Interval alpha;
        std::optional<Interval> eta;
        std::vector<std::string> serves, materials;
        bool transmission = false;  // serves a lobe that transmits
    };
    std::vector<Group> groups;
    std::vector<SceneMaterial> materials = scene.materials;
    if (!s.tables.empty()) override_lobe_kinds(materials, s.tables, plan.warnings);
    plan.materials = materials;
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
                auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
                    return g.kind == kind && g.model == lobe.model && g.fresnel == fresnel && g.wavelength == wl;
                });
                if (it == groups.end()) {
                    Group g;
                    g.kind = kind;
                    g.model = lobe.model;
                    g.model_name = lobe.model_name;
                    g.fresnel = fresnel;
                    g.wavelength = wl;
                    g.alpha = lobe.alpha;
                    if (kind->eta_axis) g.eta = lobe.eta;
                    groups.push_back(g);
                    it = groups.end() - 1;
                } else {
                    it->alpha.lo = std::min(it->alpha.lo, lobe.alpha.lo);
                    it->alpha.hi = std::max(it->alpha.hi, lobe.alpha.hi);
                    if (kind->eta_axis && lobe.eta) {
                        it->eta->lo = std::min(it->eta->lo, lobe.eta->lo);
                        it->eta->hi = std::max(it->eta->hi, lobe.eta->hi);
                    }
                }
                it->transmission = it->transmission || lobe.role == "transmission";
                const std::string serve = m.name + " (" + lobe.role + ")";
                if (std::find(it->serves.begin(), it->serves.end(), serve) == it->serves.end())
                    it->serves.push_back(serve);
                if (std::find(it->materials.begin(), it->materials.end(), m.name) == it->materials.end())
                    it->materials.push_back(m.name);
            }
        }
    }

    // The engine layouts: --target gltf bakes the glTF renderers' set; --preset NAME gives the
    // tables of the preset's kinds (of its model) in the engine's layout instead of the scene's.
    std::vector<PlannedTable> engine_tables;
    if (!s.target.empty() || !s.preset.empty()) {
        const LutPreset& preset = lut_preset(s.target.empty() ? s.preset : s.target);
        // One table in the preset's layout for `kind` and `model`, serving what `take` selects.
        auto engine_table = [&](const std::string& kind, const std::string& model, const std::string& file,
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
            for (const Group& g : groups)
                if (take(g)) {
                    for (const auto& x : g.serves)
                        if (std::find(t.serves.begin(), t.serves.end(), x) == t.serves.end()) t.serves.push_back(x);
                    for (const auto& x : g.materials)
                        if (std::find(t.materials.begin(), t.materials.end(), x) == t.materials.end()) t.materials.push_back(x);
                }
            engine_tables.push_back(std::move(t));
        };
        if (s.target == "gltf") {
            // The glTF Sample Viewer's LUTs: the split-sum GGX table for every GGX lobe, the sheen
            // tables (lut_charlie: the ashikhmin visibility of its IBL; lut_sheen_E: the charlie
            // visibility of KHR_materials_sheen's albedo scaling; docs/models.md) when a sheen is
            // present, and the scene's dielectric tables where a lobe transmits.
            const std::string ggx = model_without_alpha("ggx");
            engine_table("dfg", "ggx", "lut_ggx." + preset.extension, [&](const Group& g) { return g.model == ggx; });
            const bool sheen = std::any_of(groups.begin(), groups.end(), [](const Group& g) { return g.model_name == "sheen"; });
            if (sheen) {
                auto is_sheen = [](const Group& g) { return g.model_name == "sheen"; };
                engine_table("sheen-albedo", "sheen:visibility=ashikhmin", "lut_charlie." + preset.extension, is_sheen);
                engine_table("sheen-albedo", "sheen:visibility=charlie", "lut_sheen_E." + preset.extension, is_sheen);
            }
            groups.erase(std::remove_if(groups.begin(), groups.end(),
                                        [](const Group& g) { return !(g.kind->eta_axis && g.transmission); }),
                         groups.end());
        } else {
            std::vector<std::string> preset_models;  // "kind: model", for the warning below
            for (const std::string& kind : preset.kinds) {
                // The preset's model for this kind (Cycles' glass tables use its transmission
                // shadowing, its other tables the default).
                LutRequest probe;
                probe.kind = kind;
                preset.apply(probe);
                const std::string preset_model = model_without_alpha(probe.model);
                preset_models.push_back(kind + ": " + preset_model);
                auto ours = [&](const Group& g) { return g.kind->name == kind && g.model == preset_model; };
                if (std::none_of(groups.begin(), groups.end(), ours)) continue;
                engine_table(kind, preset_model, preset.name + "-" + kind + "." + preset.extension, ours);
                groups.erase(std::remove_if(groups.begin(), groups.end(), ours), groups.end());
            }
            if (engine_tables.empty())
                plan.warnings.push_back("--preset " + preset.name + ": no table of the scene is of the preset's kinds and "
                                        "models (" + join(preset_models) + "); the scene's tables are planned as usual");
        }
    }
    // File names: kind-model, with the model's non-default keys (and a conductor's Fresnel) where
    // they tell two tables apart, and a short hash where even that does not.
    auto sanitize = [](std::string x) {
        for (char& c : x)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '-';
        return x;
    };
    std::vector<std::string> names;
    for (const auto& g : groups) {
        std::string n = g.kind->name + "-" + g.model_name;
        if (g.model != model_without_alpha(g.model_name) && g.model.find(':') != std::string::npos)
            n += "-" + sanitize(g.model.substr(g.model.find(':') + 1));
        if (g.kind->bakes_lobe_fresnel) n += "-" + sanitize(g.fresnel) + (g.wavelength > 0 ? "-" + format_number(g.wavelength) + "nm" : "");
        names.push_back(n);
    }
    std::map<std::string, int> name_count;
    for (const auto& n : names) ++name_count[n];
    // Sizes, estimates, file name, request key and hash of a table whose request is set, and
    // whether this build can compute it.
    auto finish = [&](PlannedTable t, const std::string& file, bool half, const std::string& model_name) {
        const LutRequest& r = t.request;
        const TableKind& kind = *t.kind;
        t.half = half;
        const std::uint64_t texels = std::uint64_t(r.width) * r.height * t.depth;
        t.cells = texels * std::uint64_t(kind.cells_per_texel);
        t.samples_total = t.cells * r.samples * std::uint64_t(kind.integrations(r));
        t.est_seconds = double(t.samples_total) * kind.sample_cost / plan.samples_per_second + kSecondsPerTable +
                        kSecondsPerPreview;
        const int channels = kind.value_channels(r) + 1;  // values + error
        // Per cell: ~170 B of device buffers (float; 16 replicas) and ~470 B on the host while
        // the kernel runs; the finished table holds doubles.
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
    };

    for (const auto& g : groups) {
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
        const int n_alpha = a.n;
        if (g.kind->one_dimensional) {
            r.width = n_alpha;
            r.height = 1;
        } else {
            r.width = s.mu_texels;
            r.height = n_alpha;
        }
        if (g.kind->eta_axis) {
            const AxisPlan e = plan_axis(g.eta->lo, g.eta->hi, 1, s.eta_step, 1.0, kEtaAxisMax, 64);
            t.eta_lo = e.lo;
            t.eta_hi = e.hi;
            t.depth = e.n;
            t.eta_centres = {e.first, e.last};
            t.eta_lo_exact = e.lo_exact;
            t.eta_hi_exact = e.hi_exact;
            apply_eta_axis(t, r);
        }
        std::string name = names[size_t(&g - groups.data())];
        if (name_count[name] > 1) name += "-" + hex64(fnv1a(g.model + "|" + g.fresnel)).substr(0, 6);
        finish(std::move(t), name + "." + s.table_format, s.half, g.model_name);
    }
    for (auto& t : engine_tables) {
        const std::string file = t.file;
        const std::string model_name = t.request.model.substr(0, t.request.model.find(':'));
        const bool half = t.half;
        finish(std::move(t), file, half, model_name);
    }
    // Programs: one albedo kernel per (model, Fresnel kind) and one dielectric kernel per model.
    std::set<std::string> programs;
    for (const auto& t : plan.tables)
        for (const std::string& p : t.kind->kernel_programs(t.request)) programs.insert(p);
    plan.programs = int(programs.size());
    plan.build_seconds = kSecondsPerProgram * plan.programs;
    plan.startup_seconds = kStartupSeconds;
    // The bake report checks each lobe with a table at both ends of its roughness range.
    std::set<std::string> checks;
    for (const auto& m : plan.materials)
        for (const auto& lobe : m.lobes)
            if (!lobe.kinds.empty())
                for (double a : {lobe.alpha.lo, lobe.alpha.hi})
                    checks.insert(lobe.model + "|" + lobe.fresnel + "|" + std::to_string(a));
    plan.report_checks = int(checks.size());
    plan.report_seconds = kSecondsPerReportCheck * plan.report_checks;
    return plan;
}

}  // namespace brdfbake

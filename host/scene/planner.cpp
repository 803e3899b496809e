// The planner: a scene's table needs merged into the fewest tables, each sized, named, keyed and
// estimated by its kind's registry entry (brdfbake/table_kinds.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/version.h"
#include "models/key_reader.h"
#include "scene/scene.h"
#include "scene/scene_text.h"

namespace brdfbake {

namespace {

using scene_text::join;

/// Axis of `n` texels whose first and last texel centres fall on c_lo and c_hi (a single value
/// gets one texel centred on it). Returns {lo, hi, n} of the coordinate range.
struct AxisPlan {
    double lo, hi;
    int n;
};

AxisPlan plan_axis(double c_lo, double c_hi, int n_full_range, double full_width, double floor, int max_n) {
    const double w = c_hi - c_lo;
    if (w <= 1e-12 * std::max(1.0, std::fabs(c_hi))) {
        const double h = 0.5 * full_width / n_full_range;
        const double lo = std::max(floor, c_lo - h);
        return {lo, std::max(c_hi + h, lo + 2 * h), 1};
    }
    int n = int(std::ceil(n_full_range * w / full_width - 1e-9)) + 1;
    n = std::max(2, std::min(n, std::max(2, max_n)));
    const double pad = w / (2.0 * (n - 1));
    return {std::max(floor, c_lo - pad), c_hi + pad, n};
}

double alpha_coordinate(double alpha, const std::string& map) { return map == "roughness" ? std::sqrt(alpha) : alpha; }

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
/// EPYC, float, GGX importance sampling; docs/scenes.md) times the hardware threads.
constexpr double kSamplesPerSecondPerCore = 1.0e7;

/// A cold kernel build and first launch on PoCL (docs/scenes.md: 0.35 to 0.55 s for GGX).
constexpr double kSecondsPerProgram = 0.5;

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
    plan.materials = scene.materials;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    plan.samples_per_second = kSamplesPerSecondPerCore * cores;
    plan.throughput_basis = std::to_string(cores) + " hardware threads x 1.0e7 (PoCL, float, measured; docs/scenes.md)";

    // Group the needs: one table per (kind, model, Fresnel in the table).
    struct Group {
        const TableKind* kind = nullptr;
        std::string model, model_name, fresnel;
        double wavelength = 0.0;
        Interval alpha;
        std::optional<Interval> eta;
        std::vector<std::string> serves, materials;
    };
    std::vector<Group> groups;
    for (const auto& m : scene.materials) {
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
                const std::string serve = m.name + " (" + lobe.role + ")";
                if (std::find(it->serves.begin(), it->serves.end(), serve) == it->serves.end())
                    it->serves.push_back(serve);
                if (std::find(it->materials.begin(), it->materials.end(), m.name) == it->materials.end())
                    it->materials.push_back(m.name);
            }
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

        const double c_lo = alpha_coordinate(std::max(g.alpha.lo, 0.0), s.alpha_map);
        const double c_hi = alpha_coordinate(g.alpha.hi, s.alpha_map);
        const AxisPlan a = plan_axis(c_lo, c_hi, s.alpha_texels, 1.0, 0.0, s.alpha_texels);
        if (a.hi > 3.0)
            throw Error("alpha up to " + format_number(g.alpha.hi) + " (" + join(g.materials) +
                        ") is beyond the tables' roughness axis, which stops at coordinate 3");
        r.alpha_lo = a.lo;
        r.alpha_hi = a.hi;
        const int n_alpha = a.n;
        if (g.kind->one_dimensional) {
            r.width = n_alpha;
            r.height = 1;
        } else {
            r.width = s.mu_texels;
            r.height = n_alpha;
        }
        if (g.kind->eta_axis) {
            const AxisPlan e = plan_axis(g.eta->lo, g.eta->hi, 1, s.eta_step, 1.0, 64);
            t.eta_lo = e.lo;
            t.eta_hi = e.hi;
            t.depth = e.n;
            apply_eta_axis(t, r);
        }
        const std::uint64_t texels = std::uint64_t(r.width) * r.height * t.depth;
        t.cells = texels * std::uint64_t(g.kind->cells_per_texel);
        t.samples_total = t.cells * s.samples * std::uint64_t(g.kind->integrations(r));
        t.est_seconds = double(t.samples_total) * g.kind->sample_cost / plan.samples_per_second;
        const int channels = g.kind->value_channels(r) + 1;  // values + error
        // Per cell: ~170 B of device buffers (float; 16 replicas) and ~470 B on the host while
        // the kernel runs; the finished table holds doubles.
        t.est_memory = t.cells * 640 + texels * channels * 8;
        if (s.table_format == "exr") t.file_bytes = texels * channels * (s.half ? 2 : 4) + 2048;
        else t.file_bytes = texels * channels * 26 + 1024;

        std::string name = names[size_t(&g - groups.data())];
        if (name_count[name] > 1) name += "-" + hex64(fnv1a(g.model + "|" + g.fresnel)).substr(0, 6);
        t.file = name + "." + s.table_format;

        std::ostringstream k;
        k << "brdfbake " << BRDFBAKE_VERSION << "; kind=" << r.kind << "; model=" << r.model << "; fresnel=" << r.fresnel
          << "; wavelength_nm=" << g17(r.wavelength_nm) << "; size=" << r.width << "x" << r.height;
        if (g.kind->eta_axis) k << "x" << t.depth << "; eta_range=" << g17(t.eta_lo) << "," << g17(t.eta_hi);
        k << "; mu_map=" << r.mu_map << "; alpha_map=" << r.alpha_map << "; alpha_range=" << g17(r.alpha_lo) << ","
          << g17(r.alpha_hi) << "; samples=" << r.samples << "; precision=" << precision_name(r.precision)
          << "; format=" << s.table_format << (s.half ? "-half" : "");
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
        if (std::find(plan.models.begin(), plan.models.end(), g.model_name) == plan.models.end())
            plan.models.push_back(g.model_name);
        plan.tables.push_back(std::move(t));
    }
    // Programs: one albedo kernel per (model, Fresnel kind) and one dielectric kernel per model.
    std::set<std::string> programs;
    for (const auto& t : plan.tables)
        for (const std::string& p : t.kind->kernel_programs(t.request)) programs.insert(p);
    plan.programs = int(programs.size());
    plan.build_seconds = kSecondsPerProgram * plan.programs;
    return plan;
}

}  // namespace brdfbake

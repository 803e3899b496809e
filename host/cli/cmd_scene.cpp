// `brdfbake plan SCENE` and `brdfbake bake SCENE -o DIR`: the tables a scene needs, and baking
// them (progress on stderr, an index of what was written and for which materials, tables
// already up to date skipped). docs/scenes.md describes both.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/output.h"
#include "brdfbake/progress.h"
#include "brdfbake/spec.h"
#include "brdfbake/table.h"
#include "brdfbake/version.h"
#include "cli/cli.h"
#include "plot/bake_report.h"
#include "plot/plot.h"
#include "scene/bake.h"
#include "scene/scene.h"

namespace brdfbake {
namespace {

using json = nlohmann::ordered_json;  // keys in the order written: a readable index
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Command-line overrides of the scene's settings (0 or empty: not given).
struct SceneOptions {
    std::string scene;
    std::int64_t samples = 0;
    int mu_texels = 0;
    int alpha_texels = 0;
    std::string precision;
    std::string table_format;
    bool half = false;
    std::string size;                 // MUxALPHA or N
    std::string sheen_model;          // the sheen lobes' tables: charlie or ltc
    std::vector<std::string> tables;  // table kinds replacing every lobe's
    std::string mu_map, alpha_map;
    double eta_step = 0.0;
    std::string preset, target;
};

/// --size: N (N mu texels and N over the full roughness axis) or MUxALPHA.
void parse_scene_size(const std::string& text, SceneSettings& s) {
    int mu = 0, alpha = 0;
    char x = 0, rest = 0;
    const int n = std::sscanf(text.c_str(), "%5d%c%5d%c", &mu, &x, &alpha, &rest);
    const bool digits = !text.empty() && text.find_first_not_of("0123456789x") == std::string::npos;
    if (!digits || !(n == 1 || (n == 3 && x == 'x')))
        throw Error("--size: '" + text + "' is not N or MUxALPHA (mu texels x texels of the full roughness axis, "
                    "e.g. 32x32)");
    s.mu_texels = mu;
    s.alpha_texels = n == 1 ? mu : alpha;
    s.size_from_command_line = true;
}

void add_scene_options(CLI::App* cmd, SceneOptions& o) {
    cmd->add_option("scene", o.scene, "scene: a brdfbake scene file (.json) or glTF 2.0 (.gltf, .glb)")->required();
    // 0 is these options' "not given"; given, they must be positive.
    cmd->add_option("--samples", o.samples, "samples per texel (default: the scene's settings, else 16384)")
        ->check(kPositive);
    cmd->add_option("--mu-texels", o.mu_texels, "texels along mu (default 32)")->check(kPositive);
    cmd->add_option("--alpha-texels", o.alpha_texels,
                    "texels over the full roughness axis [0, 1]; a scene's range gets its share (default 32)")
        ->check(kPositive);
    cmd->add_option("--precision", o.precision, "kernel arithmetic (default float)")
        ->check(CLI::IsMember({"float", "double"}));
    cmd->add_option("--table-format", o.table_format, "table files: exr (default), csv or h")
        ->check(CLI::IsMember({"exr", "csv", "h"}));
    cmd->add_flag("--half", o.half, "half-float EXR channels");
    cmd->add_option("--size", o.size,
                    "N or MUxALPHA: mu texels x texels of the full roughness axis (a scene's range gets its share); "
                    "with --preset or --target, the size of the engine tables too");
    cmd->add_option("--tables", o.tables, "table kinds for every lobe, replacing the scene's and the defaults "
                                          "(each lobe takes those it can; comma-separated)")
        ->delimiter(',');
    cmd->add_option("--sheen-model", o.sheen_model,
                    "the sheen lobes' tables: charlie (its albedo, the default) or ltc (the sheen-ltc table of "
                    "Zeltner et al. 2022: a, b, R)")
        ->check(CLI::IsMember({"charlie", "ltc"}));
    cmd->add_option("--mu-map", o.mu_map, "mu axis coordinate (default linear)")->check(CLI::IsMember({"linear", "sqrt"}));
    cmd->add_option("--alpha-map", o.alpha_map, "roughness axis coordinate (default roughness)")
        ->check(CLI::IsMember({"alpha", "roughness"}));
    cmd->add_option("--eta-step", o.eta_step, "eta spacing of a range of indices (default 0.05)")->check(kPositive);
    std::vector<std::string> presets;
    for (const LutPreset& p : lut_presets()) presets.push_back(p.name);
    cmd->add_option("--preset", o.preset,
                    "an engine's layout (as lut --preset) for the scene's tables of the preset's kinds and model")
        ->check(CLI::IsMember(presets));
    cmd->add_option("--target", o.target,
                    "gltf: the tables glTF renderers load: lut_ggx (split-sum GGX), lut_charlie and lut_sheen_E when "
                    "a material has KHR_materials_sheen, and the scene's dielectric tables for transmission")
        ->check(CLI::IsMember({"gltf"}))
        ->excludes(cmd->get_option("--preset"));
}

/// How much slower than on idle cores the machine runs now (scene/calibration.h): a GGX albedo
/// table of 2^28 samples timed after a first run of 2^20 that builds its kernel (about 0.2 s of
/// CPU; at 2^27 the measured factor spread 3 to 11 within two minutes at load 13). That build
/// says whether PoCL's kernel cache is cold (Calibration::cold_cache). BRDFBAKE_SLOWDOWN=X
/// replaces the measured factor (the cache is then taken as warm).
void probe_slowdown(const GlobalOptions& g, Calibration& c) {
    if (const double given = slowdown_from_environment(); given > 0) {
        c.slowdown = given;
        return;
    }
    Engine engine(g.device, false);
    LutRequest r;
    r.kind = "albedo";
    r.model = "ggx";
    r.width = r.height = 4;
    r.samples = 1u << 16;
    const ProgressSilence quiet;
    compute_lut(engine, r);
    const double build = engine.build_seconds();
    r.width = 64;
    r.height = 64;
    const SlowdownClock clock;
    compute_lut(engine, r);
    c.slowdown = clock.slowdown();
    c.cold_cache = build > builtin_figures::kColdBuildSeconds * serial_slowdown(c.slowdown);
}

/// The scene with the command line's settings applied.
Scene load_scene_with(const SceneOptions& o) {
    Scene scene = load_scene(o.scene);
    SceneSettings& s = scene.settings;
    if (o.samples < 0) throw Error("--samples must be positive");
    if (o.samples > 0) s.samples = std::uint64_t(o.samples);
    if (o.mu_texels < 0 || o.alpha_texels < 0) throw Error("--mu-texels and --alpha-texels must be positive");
    if (o.mu_texels > 0) s.mu_texels = o.mu_texels;
    if (o.alpha_texels > 0) s.alpha_texels = o.alpha_texels;
    if (o.mu_texels > 0 || o.alpha_texels > 0) s.size_from_command_line = true;
    if (!o.precision.empty()) s.precision = o.precision == "double" ? Precision::Double : Precision::Float;
    if (!o.table_format.empty()) s.table_format = o.table_format;
    if (o.half) s.half = true;
    if (!o.size.empty()) parse_scene_size(o.size, s);
    if (!o.tables.empty()) s.tables = o.tables;
    if (!o.sheen_model.empty()) s.sheen_model = o.sheen_model;
    if (!o.mu_map.empty()) s.mu_map = o.mu_map;
    if (!o.alpha_map.empty()) s.alpha_map = o.alpha_map;
    if (o.eta_step > 0) s.eta_step = o.eta_step;
    s.preset = o.preset;
    s.target = o.target;
    check_settings(s);
    return scene;
}

/// A bake whose tables take at least this many idle-core seconds measures the slowdown before
/// it starts (the probe, 0.1 s on idle cores, is then under a sixth of its tables and a tenth of
/// the bake with its start-up, builds and report); a shorter one estimates its first table at
/// the plan's idle figures and the rest at the slowdown its tables measure. At 2 s, the sheen
/// scene (1.4 idle s) and a 1024x1024 albedo table (0.9 idle s) went unmeasured: their log said
/// a tenth of the time they took at load 20.
constexpr double kProbedBakeSeconds = 0.75;

// --- kernel build measurement ------------------------------------------------------------------
// --- kernel build measurement ------------------------------------------------------------------

/// The model id of a model name, found by resolving it with typical parameters.
int model_id(const std::string& name) {
    for (const char* keys : {"", ":alpha=0.5", ":n=10", ":sigma=0.3", ":eta=1.5"}) {
        try {
            return resolve_model(name + keys).id;
        } catch (const Error&) {
        }
    }
    throw Error("internal error: cannot resolve model '" + name + "' for a kernel build");
}

struct BuildStats {
    int programs = 0;
    double seconds = 0.0;
    std::uint64_t binary_bytes = 0;
    std::uint64_t source_bytes = 0;
};

/// Builds the albedo kernel (the kernel every table integrates with) for each model and measures
/// the build time (clBuildProgram) and the size of the device binary.
BuildStats measure_builds(Engine& engine, const std::vector<std::string>& models, Precision precision) {
    BuildStats s;
    const std::string source = kernel_source("albedo.cl");
    for (const auto& name : models) {
        BuildRequest b;
        b.kernel_file = "albedo.cl";
        b.precision = precision;
        b.model = model_id(name);
        b.fresnel = 0;  // BB_FRESNEL_NONE
        const double before = engine.build_seconds();
        cl::Program& p = engine.program(b);
        s.seconds += engine.build_seconds() - before;
        for (std::size_t n : p.getInfo<CL_PROGRAM_BINARY_SIZES>()) s.binary_bytes += n;
        s.source_bytes += source.size();
        ++s.programs;
    }
    return s;
}

json stats_json(const BuildStats& s) {
    return {{"programs", s.programs}, {"build_seconds", s.seconds}, {"binary_bytes", s.binary_bytes},
            {"source_bytes", s.source_bytes}};
}

// --- plan --------------------------------------------------------------------------------------

struct PlanOptions {
    SceneOptions scene;
    std::string format = "table";
    bool measure = false;
};

int run_plan(const PlanOptions& o, const GlobalOptions& g) {
    // The estimates measured against the machine's load now (with a calibration path: not under
    // BRDFBAKE_CALIBRATION=off, which the tests use).
    const Scene scene = load_scene_with(o.scene);
    Calibration calibration = read_calibration(calibration_path());  // estimates from earlier bakes
    if (!calibration.path.empty()) probe_slowdown(g, calibration);
    const Plan plan = make_plan(scene, &calibration);
    std::string out = o.format == "json" ? plan_json(plan) : plan_text(plan);
    if (o.measure) {
        // The scene's models against every model, each model its own program as the engine
        // builds them. Separate engines, so that neither run reuses the other's programs.
        const char* cache = std::getenv("POCL_KERNEL_CACHE");
        const bool cached = !(cache && std::string(cache) == "0");
        Engine scene_engine(g.device, g.verbose);
        {
            // Warm-up: the first build in a process also starts the compiler (about 2 s on PoCL);
            // a trivial program pays that, so that neither measurement below does.
            cl::Program warm(scene_engine.context(), std::string("__kernel void bb_warm_up(__global int* x) { x[0] = 1; }"));
            warm.build(std::vector<cl::Device>{scene_engine.device().device}, "-cl-std=CL1.2");
        }
        const BuildStats used = measure_builds(scene_engine, plan.models, plan.settings.precision);
        Engine all_engine(g.device, g.verbose);
        const BuildStats all = measure_builds(all_engine, model_names(), plan.settings.precision);
        if (o.format == "json") {
            json j = json::parse(out);
            j["kernels"] = {{"device", scene_engine.device().name},
                            {"pocl_kernel_cache", cached},
                            {"scene_models", stats_json(used)},
                            {"all_models", stats_json(all)}};
            out = j.dump(2) + "\n";
        } else {
            char line[512];
            std::snprintf(line, sizeof line,
                          "kernels (%s, %s): scene models %d program%s, build %.3f s, binary %.1f KiB; "
                          "all %d models: build %.3f s, binary %.1f KiB\n",
                          scene_engine.device().name.c_str(),
                          cached ? "PoCL cache on: set POCL_KERNEL_CACHE=0 for cold builds" : "cold builds",
                          used.programs, used.programs == 1 ? "" : "s", used.seconds, used.binary_bytes / 1024.0,
                          all.programs, all.seconds, all.binary_bytes / 1024.0);
            out += line;
        }
    }
    std::cout << out << std::flush;
    return kExitOk;
}

// --- bake --------------------------------------------------------------------------------------

struct BakeCommandOptions {
    SceneOptions scene;
    BakeOptions bake;     // output, force, lock timeout
    bool previews = true;
    bool report = true;   // DIR/index.html, the bake report
    BakeCommandOptions() { bake.output = "out"; }
};

std::string join_path(const std::string& dir, const std::string& file) {
    return dir.empty() || dir.back() == '/' ? dir + file : dir + "/" + file;
}

int run_bake(const BakeCommandOptions& o, const GlobalOptions& g) {
    const auto t0 = Clock::now();
    const Scene scene = load_scene_with(o.scene);
    Calibration calibration = read_calibration(calibration_path());  // read once: estimates, then this bake's record
    Plan plan = make_plan(scene, &calibration);
    double idle_seconds = 0;
    for (const auto& t : plan.tables) idle_seconds += t.idle_compute_seconds;
    if (!calibration.path.empty() && (idle_seconds >= kProbedBakeSeconds || slowdown_from_environment() > 0)) {
        probe_slowdown(g, calibration);  // the same factor as `plan`: the bake's estimates agree with it
        plan = make_plan(scene, &calibration);
    }
    const double plan_seconds = since(t0);
    BakeOptions options = o.bake;
    if (o.previews) options.write_preview = [](const Table& t, const std::string& path) { return write_table_preview(t, path); };
    // The bake report (DIR/index.html) from the index just written, with each lobe's check; when
    // every table was up to date, only if the folder has none.
    std::optional<BakeReportSummary> report;  // printed after the bake's summary
    options.finish = [&](Engine* engine, const std::string& failure) {
        if (!o.report || (!engine && std::ifstream(join_path(options.output, "index.html")))) return;
        std::unique_ptr<Engine> own;
        if (!engine) engine = (own = std::make_unique<Engine>(g.device, g.verbose)).get();
        BakeReportOptions ro;
        ro.draw_missing_previews = false;  // --no-previews holds for the report too
        ro.failure = failure;
        for (const auto& t : plan.tables) ro.planned_tables.push_back(t.file);
        report = write_bake_report(*engine, options.output, ro);
    };
    const BakeResult r = bake_plan(plan, options, [&] { return std::make_unique<Engine>(g.device, g.verbose); });
    if (r.computed > 0) {  // this bake's stage times calibrate later estimates (scene/calibration.h)
        BakeTimings t = r.timings;
        t.report_checks = report ? plan.report_checks : 0;
        add_bake_timings(calibration, t);
        if (const std::string why = write_calibration(calibration); !why.empty())
            std::fprintf(stderr, "brdfbake: warning: calibration not recorded: %s\n", why.c_str());
    }
    if (r.computed == 0) {
        std::fprintf(stderr,
                     "brdfbake: all %zu tables in %s are up to date (same request hash, file present with its "
                     "content hash); nothing to compute\n",
                     r.tables, options.output.c_str());
    } else {
        std::string models;
        for (const auto& m : plan.models) models += (models.empty() ? "" : ", ") + m;
        std::fprintf(stderr,
                     "brdfbake: baked %d table%s (%zu up to date) into %s in %.2f s (kernel builds %.2f s, %s only); "
                     "max error %.2e; index %s\n",
                     r.computed, r.computed == 1 ? "" : "s", r.tables - size_t(r.computed), options.output.c_str(),
                     plan_seconds + r.seconds, r.build_seconds, models.c_str(), r.max_error, r.index_path.c_str());
    }
    if (report)
        std::fprintf(stderr, "brdfbake: report %s: %d lobe checks, %d violations\n",
                     join_path(options.output, "index.html").c_str(), report->lobes_checked, report->lobes_failed);
    return kExitOk;
}

}  // namespace

void add_plan_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<PlanOptions>(
        app, "plan", "list the tables a scene needs (kinds, ranges, sizes, materials, estimates)", global, action,
        run_plan);
    add_scene_options(cmd, o->scene);
    add_format_option(cmd, o->format, {"table", "json"});
    cmd->add_flag("--measure-kernels", o->measure,
                  "build the kernels for the scene's models and for every model on the device; report build time and "
                  "binary size");
}

void add_bake_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<BakeCommandOptions>(
        app, "bake", "compute the tables a scene needs into a folder, with an index.json", global, action, run_bake);
    add_scene_options(cmd, o->scene);
    cmd->add_option("-o,--output", o->bake.output, "output folder")->capture_default_str();
    cmd->add_flag("--force", o->bake.force, "recompute tables that are up to date");
    cmd->add_flag("!--no-previews", o->previews, "write no preview pictures (default: DIR/previews/TABLE.png per table)");
    cmd->add_flag("!--no-report", o->report,
                  "write no bake report (default: DIR/index.html with each table's preview, error, materials and "
                  "the check of each lobe; `brdfbake report DIR` draws it later)");
    cmd->add_option("--lock-timeout", o->bake.lock_timeout,
                    "seconds to wait while another bake writes into the same folder; 0: refuse at once")
        ->capture_default_str()
        ->check(kNonNegative);
}

}  // namespace brdfbake

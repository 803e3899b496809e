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
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "brdfbake/table.h"
#include "brdfbake/version.h"
#include "cli/cli.h"
#include "plot/bake_report.h"
#include "plot/plot.h"
#include "scene/bake_folder.h"
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

Plan load_plan(const SceneOptions& o) {
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
    if (!o.mu_map.empty()) s.mu_map = o.mu_map;
    if (!o.alpha_map.empty()) s.alpha_map = o.alpha_map;
    if (o.eta_step > 0) s.eta_step = o.eta_step;
    s.preset = o.preset;
    s.target = o.target;
    check_settings(s);
    return make_plan(scene);
}

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
    const Plan plan = load_plan(o.scene);
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

struct BakeOptions {
    SceneOptions scene;
    std::string output = "out";
    bool force = false;
    bool previews = true;
    bool report = true;  // DIR/index.html, the bake report
    double lock_timeout = 600.0;  // seconds to wait for another bake into the same folder
};

/// Progress on stderr: a bar redrawn in place when stderr is a terminal, plain lines otherwise.
class Progress {
public:
    explicit Progress(double total_work) : total_(std::max(total_work, 1.0)), tty_(::isatty(2) != 0), t0_(Clock::now()) {}
    bool tty() const { return tty_; }

    void start(const std::string& label, int index, int count, const std::string& detail) {
        label_ = label;
        index_ = index;
        count_ = count;
        if (!tty_) std::fprintf(stderr, "brdfbake: [%d/%d] %s: computing %s\n", index, count, label.c_str(), detail.c_str());
        draw();
    }
    void advance(double work) {
        done_ += work;
        draw();
    }
    void finish_table(const std::string& message) {
        if (tty_) std::fprintf(stderr, "\r\033[K");
        std::fprintf(stderr, "brdfbake: [%d/%d] %s\n", index_, count_, message.c_str());
        draw();
    }
    void end() {
        if (tty_) std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }

private:
    void draw() {
        if (!tty_) return;
        const double f = std::min(1.0, done_ / total_);
        const int width = 30, fill = int(f * width + 0.5);
        const double t = since(t0_);
        std::string bar(size_t(fill), '=');
        bar += std::string(size_t(width - fill), ' ');
        char eta[32] = "";
        if (f > 0.02 && f < 1.0) std::snprintf(eta, sizeof eta, ", ~%.0f s left", t / f * (1.0 - f));
        std::fprintf(stderr, "\r\033[K[%s] %3.0f%%  %s (%d/%d)  %.1f s%s", bar.c_str(), 100 * f, label_.c_str(), index_,
                     count_, t, eta);
        std::fflush(stderr);
    }

    double total_, done_ = 0.0;
    bool tty_;
    Clock::time_point t0_;
    std::string label_;
    int index_ = 0, count_ = 0;
};

/// The tiles of a table along its roughness axis (rows of a 2D table, texels of eavg): each tile
/// is the same request over a sub-range whose texel centres are the full table's.
std::vector<LutRequest> tiles_of(const TableKind& kind, const LutRequest& r, int max_tiles) {
    const bool along_x = kind.one_dimensional;
    const int n = along_x ? r.width : r.height;
    const int tiles = std::max(1, std::min(n, max_tiles));
    std::vector<LutRequest> out;
    for (int k = 0; k < tiles; ++k) {
        const int j0 = n * k / tiles, j1 = n * (k + 1) / tiles;
        LutRequest t = r;
        t.alpha_lo = r.alpha_lo + (r.alpha_hi - r.alpha_lo) * j0 / n;
        t.alpha_hi = k + 1 == tiles ? r.alpha_hi : r.alpha_lo + (r.alpha_hi - r.alpha_lo) * j1 / n;
        (along_x ? t.width : t.height) = j1 - j0;
        out.push_back(t);
    }
    return out;
}

/// Joins tiles computed by tiles_of back into the table of the full request.
Table stitch(const TableKind& kind, const LutRequest& r, std::vector<Table>& parts) {
    Table t = std::move(parts.front());
    const bool along_x = kind.one_dimensional;
    Axis& axis = along_x ? t.x : t.y;
    for (size_t k = 1; k < parts.size(); ++k) {
        const Table& p = parts[k];
        const Axis& a = along_x ? p.x : p.y;
        axis.coordinate.insert(axis.coordinate.end(), a.coordinate.begin(), a.coordinate.end());
        axis.parameter.insert(axis.parameter.end(), a.parameter.begin(), a.parameter.end());
        for (size_t c = 0; c < t.values.size(); ++c)
            t.values[c].insert(t.values[c].end(), p.values[c].begin(), p.values[c].end());
        t.error.insert(t.error.end(), p.error.begin(), p.error.end());
        for (const auto& kv : p.attributes)
            if (!t.attributes.count(kv.first)) t.attributes.insert(kv);  // e.g. the alpha floor note
    }
    axis.lo = r.alpha_lo;
    axis.hi = r.alpha_hi;
    axis.size = int(axis.coordinate.size());
    return t;
}

std::string join_path(const std::string& dir, const std::string& file) {
    return dir.empty() || dir.back() == '/' ? dir + file : dir + "/" + file;
}

bool file_exists(const std::string& path) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

json axis_json(const Axis& a) {
    return {{"name", a.name}, {"mapping", a.mapping}, {"lo", a.lo}, {"hi", a.hi}, {"size", a.size}};
}

json lobe_json(const Lobe& l) {
    json j = {{"role", l.role}, {"model", l.model}, {"fresnel", l.fresnel}, {"alpha_range", {l.alpha.lo, l.alpha.hi}},
              {"kinds", kind_names(l.kinds)}};
    if (l.eta) j["eta_range"] = {l.eta->lo, l.eta->hi};
    if (l.wavelength_nm > 0) j["wavelength_nm"] = l.wavelength_nm;
    return j;
}

json materials_json(const Plan& plan) {
    // The plan's materials: the scene's, with the tables --tables gave them.
    json out = json::array();
    for (const auto& m : plan.materials) {
        json files = json::array();
        for (const auto& t : plan.tables)
            if (std::find(t.materials.begin(), t.materials.end(), m.name) != t.materials.end()) files.push_back(t.file);
        json lobes = json::array();
        for (const auto& l : m.lobes) lobes.push_back(lobe_json(l));
        out.push_back({{"name", m.name}, {"tables", files}, {"lobes", lobes}, {"notes", m.notes}});
    }
    return out;
}

json settings_json(const SceneSettings& s) {
    return {{"samples", s.samples},       {"mu_texels", s.mu_texels}, {"alpha_texels", s.alpha_texels},
            {"eta_step", s.eta_step},     {"mu_map", s.mu_map},       {"alpha_map", s.alpha_map},
            {"precision", precision_name(s.precision)}, {"format", s.table_format}, {"half", s.half},
            {"tables", s.tables}, {"preset", s.preset}, {"target", s.target}};
}

int run_bake(const BakeOptions& o, const GlobalOptions& g) {
    const auto t0 = Clock::now();
    const SceneOptions& so = o.scene;
    // Everything is checked before the device is touched or a file is written.
    const Plan plan = load_plan(so);
    if (o.output.empty()) throw Error("-o: give an output folder");
    for (const auto& t : plan.tables)
        if (!t.unavailable.empty())
            throw Error("cannot bake '" + t.file + "' (for " + [&] {
                std::string s;
                for (const auto& m : t.materials) s += (s.empty() ? "" : ", ") + m;
                return s;
            }() + "): " + t.unavailable);
    for (const auto& w : plan.warnings) std::fprintf(stderr, "brdfbake: warning: %s\n", w.c_str());

    // The folder is locked from here on: the index read below is still the index when this bake
    // writes it, and another bake into the folder waits (docs/scenes.md, "Bake folders").
    BakeFolder folder(o.output, o.lock_timeout);
    const std::string index_path = join_path(o.output, "index.json");
    json old_index;
    if (file_exists(index_path)) {
        std::ifstream in(index_path);
        std::stringstream s;
        s << in.rdbuf();
        try {
            old_index = json::parse(s.str());
        } catch (const json::exception&) {
            std::fprintf(stderr, "brdfbake: warning: %s is not valid JSON; every table is recomputed\n", index_path.c_str());
        }
    }
    auto old_entry = [&](const std::string& file) -> const json* {
        if (!old_index.is_object() || !old_index.contains("tables") || !old_index["tables"].is_array()) return nullptr;
        for (const auto& e : old_index["tables"])
            if (e.is_object() && e.value("file", "") == file) return &e;
        return nullptr;
    };

    // What is up to date: the same request hash in the index, and the file present with the
    // content hash the index records (a file another bake or an edit replaced is recomputed).
    const bool same_hash_algorithm =
        old_index.is_object() && old_index.value("content_hash_algorithm", "") == kContentHashAlgorithm;
    std::vector<bool> fresh(plan.tables.size(), false);
    double work = 0.0;
    int to_compute = 0;
    for (size_t i = 0; i < plan.tables.size(); ++i) {
        const PlannedTable& t = plan.tables[i];
        const json* e = old_entry(t.file);
        const std::string path = join_path(o.output, t.file);
        if (!o.force && e && e->value("request_hash", "") == t.hash && file_exists(path)) {
            fresh[i] = same_hash_algorithm && e->value("content_hash", "") == content_hash_of_file(path);
            if (!fresh[i])
                std::fprintf(stderr, "brdfbake: %s is not the table index.json describes (content hash differs); "
                                     "recomputing it\n", path.c_str());
        }
        if (!fresh[i]) {
            work += double(t.samples_total);
            ++to_compute;
        }
    }

    json index = {{"brdfbake_index", 1},
                  {"tool", std::string("brdfbake ") + BRDFBAKE_VERSION},
                  {"scene", plan.scene},
                  {"source", plan.source},
                  {"settings", settings_json(plan.settings)},
                  {"content_hash_algorithm", kContentHashAlgorithm},
                  {"tables", json::array()},
                  {"materials", materials_json(plan)},
                  {"warnings", plan.warnings}};
    for (size_t i = 0; i < plan.tables.size(); ++i)
        if (fresh[i]) {
            json e = *old_entry(plan.tables[i].file);
            e["materials"] = plan.tables[i].materials;  // which materials it serves may have changed
            e["serves"] = plan.tables[i].serves;
            index["tables"].push_back(e);
        }
    auto write_index = [&] {
        const std::string text = index.dump(2) + "\n";
        std::ifstream in(index_path, std::ios::binary);
        std::stringstream s;
        if (in) s << in.rdbuf();
        if (!in || s.str() != text) {
            write_file_atomically(index_path, text);
            folder.commit();
        }
    };

    // Tables of an earlier bake that the plan no longer has: reported, left in place.
    if (old_index.is_object() && old_index.contains("tables") && old_index["tables"].is_array())
        for (const auto& e : old_index["tables"]) {
            const std::string f = e.is_object() ? e.value("file", "") : "";
            if (!f.empty() && std::none_of(plan.tables.begin(), plan.tables.end(),
                                           [&](const PlannedTable& t) { return t.file == f; }))
                std::fprintf(stderr, "brdfbake: %s is no longer in the plan; left in place, dropped from the index\n",
                             join_path(o.output, f).c_str());
        }

    // The bake report (DIR/index.html) from the index just written, with each lobe's check.
    auto write_report = [&](Engine& engine) {
        if (!o.report) return;
        BakeReportOptions options;
        options.draw_missing_previews = false;  // --no-previews holds for the report too
        const BakeReportSummary s = write_bake_report(engine, o.output, options);
        std::fprintf(stderr, "brdfbake: report %s: %d lobe checks, %d violations\n",
                     join_path(o.output, "index.html").c_str(), s.lobes_checked, s.lobes_failed);
    };

    if (to_compute == 0) {
        write_index();
        std::fprintf(stderr,
                     "brdfbake: all %zu tables in %s are up to date (same request hash, file present with its "
                     "content hash); nothing to compute\n",
                     plan.tables.size(), o.output.c_str());
        if (o.report && !std::ifstream(join_path(o.output, "index.html"))) {
            Engine engine(g.device, g.verbose);
            write_report(engine);
        }
        return kExitOk;
    }

    std::unique_ptr<Engine> engine = std::make_unique<Engine>(g.device, g.verbose);
    Progress progress(work);
    // bake draws its own progress over all its tables: the computations' stages stay silent.
    const ProgressSilence silence;
    int n = 0, computed = 0;
    double max_error = 0.0;
    for (size_t i = 0; i < plan.tables.size(); ++i) {
        const PlannedTable& t = plan.tables[i];
        if (fresh[i]) continue;
        ++n;
        const auto t1 = Clock::now();
        LutRequest r = t.request;
        apply_eta_axis(t, r);
        const TableKind& kind = *t.kind;
        char detail[160];
        std::snprintf(detail, sizeof detail, "%s table %dx%d%s, %llu samples per cell (estimate %.1f s)", r.kind.c_str(),
                      r.width, r.height, kind.eta_axis ? ("x" + std::to_string(t.depth)).c_str() : "",
                      static_cast<unsigned long long>(r.samples), t.est_seconds);
        progress.start(t.file, n, to_compute, detail);
        Table table;
        if (kind.tileable) {
            const std::vector<LutRequest> tiles = tiles_of(kind, r, 16);
            std::vector<Table> parts;
            for (const auto& tile : tiles) {
                parts.push_back(compute_lut(*engine, tile));
                progress.advance(double(t.samples_total) * (kind.one_dimensional ? tile.width : tile.height) /
                                 (kind.one_dimensional ? r.width : r.height));
            }
            table = stitch(kind, r, parts);
        } else {
            table = compute_lut(*engine, r);
            progress.advance(double(t.samples_total));
        }
        check_finite(table);
        const std::string path = join_path(o.output, t.file);
        write_table(table, path, t.half);
        folder.commit();
        // Its preview beside it (previews/FILE.png), unless --no-previews.
        std::string preview;
        if (o.previews) {
            ::mkdir(join_path(o.output, "previews").c_str(), 0755);
            preview = "previews/" + t.file + ".png";
            write_table_preview(table, join_path(o.output, preview));
        }
        const double seconds = since(t1);
        max_error = std::max(max_error, table.max_error());

        json axes = json::array({axis_json(table.x)});
        if (table.height() > 1 || !kind.one_dimensional) axes.push_back(axis_json(table.y));
        if (table.depth() > 1 || kind.eta_axis) axes.push_back(axis_json(table.z));
        json e = {{"file", t.file},
                  {"kind", r.kind},
                  {"quantity", table.quantity},
                  {"model", r.model},
                  {"fresnel", r.fresnel},
                  {"size", std::to_string(table.width()) + "x" + std::to_string(table.height()) +
                               (kind.eta_axis ? "x" + std::to_string(table.depth()) : "")},
                  {"layout", table.depth() > 1 ? "z-slices stacked along y" : "2D"},
                  {"axes", axes},
                  {"channels", table.channels},
                  {"error_channel", "estimated absolute error per texel"},
                  {"max_error", table.max_error()},
                  {"samples_per_cell", r.samples},
                  {"precision", precision_name(r.precision)},
                  {"attributes", table.attributes},
                  {"alpha_range", {t.alpha.lo, t.alpha.hi}},
                  {"materials", t.materials},
                  {"serves", t.serves},
                  {"request_hash", t.hash},
                  {"content_hash", content_hash_of_file(path)},
                  {"request", t.key},
                  {"seconds", std::round(seconds * 1000) / 1000}};
        if (t.eta) e["eta_range"] = {t.eta->lo, t.eta->hi};
        if (r.wavelength_nm > 0) e["wavelength_nm"] = r.wavelength_nm;
        if (!t.layout.empty()) e["layout"] = t.layout;
        if (!preview.empty()) e["preview"] = preview;
        // Keep the index in plan order, and written after every table: an interrupted bake
        // keeps what it finished.
        json tables = json::array();
        for (size_t k = 0; k < plan.tables.size(); ++k) {
            if (k == i) tables.push_back(e);
            else
                for (const auto& x : index["tables"])
                    if (x.value("file", "") == plan.tables[k].file) tables.push_back(x);
        }
        index["tables"] = tables;
        write_index();
        ++computed;
        char msg[256];
        std::snprintf(msg, sizeof msg, "wrote %s in %.2f s, max error %.2e", path.c_str(), seconds, table.max_error());
        progress.finish_table(msg);
    }
    progress.end();
    std::fprintf(stderr,
                 "brdfbake: baked %d table%s (%zu up to date) into %s in %.2f s (kernel builds %.2f s, %s only); "
                 "max error %.2e; index %s\n",
                 computed, computed == 1 ? "" : "s", plan.tables.size() - size_t(computed), o.output.c_str(), since(t0),
                 engine->build_seconds(), [&] {
                     std::string s;
                     for (const auto& m : plan.models) s += (s.empty() ? "" : ", ") + m;
                     return s;
                 }().c_str(),
                 max_error, index_path.c_str());
    write_report(*engine);
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
    const auto [cmd, o] = add_command<BakeOptions>(
        app, "bake", "compute the tables a scene needs into a folder, with an index.json", global, action, run_bake);
    add_scene_options(cmd, o->scene);
    cmd->add_option("-o,--output", o->output, "output folder")->capture_default_str();
    cmd->add_flag("--force", o->force, "recompute tables that are up to date");
    cmd->add_flag("!--no-previews", o->previews, "write no preview pictures (default: DIR/previews/TABLE.png per table)");
    cmd->add_flag("!--no-report", o->report,
                  "write no bake report (default: DIR/index.html with each table's preview, error, materials and "
                  "the check of each lobe; `brdfbake report DIR` draws it later)");
    cmd->add_option("--lock-timeout", o->lock_timeout,
                    "seconds to wait while another bake writes into the same folder; 0: refuse at once")
        ->capture_default_str()
        ->check(kNonNegative);
}

}  // namespace brdfbake

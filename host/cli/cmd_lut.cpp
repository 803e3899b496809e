// `brdfbake lut KIND`: lookup tables of the kinds in brdfbake/table_kinds.h as OpenEXR, CSV or a C header.
#include <algorithm>
#include <chrono>
#include <tuple>
#include <cstdio>
#include <iostream>
#include <memory>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/output.h"
#include "brdfbake/progress.h"
#include "brdfbake/table_kinds.h"
#include "brdfbake/version.h"
#include "cli/cli.h"
#include "engine/distributed.h"
#include "integrate/distributed_compute.h"
#include "io/part_file.h"
#include "models/key_reader.h"
#include "plot/plot.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace {

struct LutOptions {
    CLI::App* command = nullptr;  // to tell the options given from the defaults (a preset fills the rest)
    std::string kind, preset, model, estimator, fresnel;
    double wavelength_nm = 0.0;
    std::string colour_space = "srgb";
    bool rgb_wavelengths = false;
    std::string size;
    std::string mu_map, alpha_map, eta_map, texels;
    std::string alpha_range, eta_range, mu_range, thickness_range;
    double thickness_step = 0.0;  // nm: the thin-film table's depth from its thickness range
    double mu_floor = 0.0;
    std::string axes, flip;
    MethodOptions integration;
    std::string precision;
    bool half = false;
    std::string preview;  // default: the output's name with .png
    bool no_preview = false;
    std::string output;
    std::string shard;  // K/N: compute shard K of N into a part file (brdfbake merge)
};

// "K/N" as (K, N), 0 <= K < N.
std::pair<int, int> parse_shard(const std::string& text) {
    const size_t slash = text.find('/');
    auto number = [&](const std::string& s) {
        if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
            throw Error("--shard: '" + text + "' is not K/N (shard K of N, 0 <= K < N, e.g. 3/8)");
        return std::stoi(s);
    };
    if (slash == std::string::npos) number("");
    const int k = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
    if (n < 1 || k >= n) throw Error("--shard: '" + text + "' is not K/N with 0 <= K < N");
    return {k, n};
}

std::vector<int> parse_size(const std::string& text) {
    std::vector<int> dims;
    size_t start = 0;
    while (start <= text.size()) {
        size_t x = text.find('x', start);
        if (x == std::string::npos) x = text.size();
        const std::string s = text.substr(start, x - start);
        if (s.empty() || s.size() > 5 || s.find_first_not_of("0123456789") != std::string::npos)
            throw Error("--size: '" + text + "' is not N, WIDTHxHEIGHT or WIDTHxHEIGHTxDEPTH (e.g. 32x32)");
        dims.push_back(std::stoi(s));
        start = x + 1;
    }
    return dims;
}

std::vector<std::string> parse_names(const std::string& text, const std::string& option) {
    std::vector<std::string> names;
    if (text.empty()) return names;
    size_t start = 0;
    while (start <= text.size()) {
        size_t comma = text.find(',', start);
        if (comma == std::string::npos) comma = text.size();
        const std::string name = text.substr(start, comma - start);
        if (name.empty()) throw Error(option + ": '" + text + "' is not a comma-separated list of axis names");
        names.push_back(name);
        start = comma + 1;
    }
    return names;
}

/// The options given on the command line, parsed, for apply_preset.
LutSettings given_settings(const LutOptions& o) {
    auto given = [&](const char* option) { return o.command->count(option) > 0; };
    auto text = [&](const char* option, const std::string& value) {
        return given(option) ? std::optional<std::string>(value) : std::nullopt;
    };
    auto number = [&](const char* option, double value) {
        return given(option) ? std::optional<double>(value) : std::nullopt;
    };
    LutSettings s;
    if (!o.kind.empty()) s.kind = o.kind;
    s.preset = text("--preset", o.preset);
    s.model = text("--model", o.model);
    s.estimator = text("--estimator", o.estimator);
    s.fresnel = text("--fresnel", o.fresnel);
    s.wavelength_nm = number("--wavelength", o.wavelength_nm);
    if (o.rgb_wavelengths && given("--colour-space"))
        throw Error("--rgb-wavelengths takes R, G, B at 650, 550 and 450 nm, not a colour space; drop one of them");
    s.colour = o.rgb_wavelengths ? std::optional<std::string>("wavelengths") : text("--colour-space", o.colour_space);
    if (given("--size")) s.size = parse_size(o.size);
    s.mu_map = text("--mu-map", o.mu_map);
    s.alpha_map = text("--alpha-map", o.alpha_map);
    s.eta_map = text("--eta-map", o.eta_map);
    s.texels = text("--texels", o.texels);
    if (given("--alpha-range")) s.alpha_range = parse_number_list(o.alpha_range, "--alpha-range");
    if (given("--eta-range")) s.eta_range = parse_number_list(o.eta_range, "--eta-range");
    if (given("--mu-range")) s.mu_range = parse_number_list(o.mu_range, "--mu-range");
    if (given("--thickness-range")) s.thickness_range = parse_number_list(o.thickness_range, "--thickness-range");
    s.thickness_step = number("--thickness-step", o.thickness_step);
    s.mu_floor = number("--mu-floor", o.mu_floor);
    if (given("--axes")) s.axes = parse_names(o.axes, "--axes");
    if (given("--flip")) s.flip = parse_names(o.flip, "--flip");
    s.samples = number("--samples", double(o.integration.samples));
    s.tolerance = number("--tolerance", o.integration.tolerance);
    s.method = text("--method", o.integration.method);
    s.max_samples = number("--max-samples", double(o.integration.max_samples));
    s.precision = text("--precision", o.precision);
    if (given("--half")) s.half = o.half;
    return s;
}

int run_lut(LutOptions& o, const GlobalOptions& g) {
    const auto t0 = std::chrono::steady_clock::now();
    LutSetup setup = apply_preset(given_settings(o));
    const LutRequest& r = setup.request;
    const bool sharded = !o.shard.empty();
    std::pair<int, int> shard{0, 1};
    if (sharded) {
        shard = parse_shard(o.shard);
        if (dist::active()) throw Error("--shard is for separate processes; an MPI job shares the table among its ranks");
        check_output_path(o.output);  // a part file, whatever its name
        o.no_preview = true;
    } else {
        check_table_path(o.output);
    }
    check_plot_output(o.preview, "--preview");
    std::string preview = o.preview;
    const std::string stem = o.output.substr(0, o.output.find_last_of('.'));
    // A PNG table keeps its name: its preview goes beside it as NAME.preview.png.
    if (preview.empty()) preview = stem + (stem + ".png" == o.output ? ".preview.png" : ".png");
    if (!o.no_preview && preview == o.output)
        throw Error("--preview '" + preview + "' is the table's own file; give another name or --no-preview");
    if (!o.no_preview) check_output_path(preview);
    validate_lut(r);  // every input checked before the device is touched
    // A format that cannot hold the table (three.js: 1, 2 or 4 channels; EEVEE: its arrays) is
    // refused now, not after the compute.
    if (!sharded) check_table_format(lut_table_shape(r), o.output);

    Engine engine(g.device, g.verbose);
    if (sharded) {
        begin_shard(shard.first, shard.second);
        compute_lut(engine, r);  // this shard's cells recorded, the others placeholders
        PartFile part;
        part.command = shard_command(command_line());
        part.version = BRDFBAKE_VERSION;
        part.source = source_digest();
        part.shard = shard.first;
        part.shards = shard.second;
        part.cells = shard_records().cells;
        part.texts = shard_records().texts;
        write_part_file(part, o.output);
        std::fprintf(stderr, "brdfbake: wrote %s: shard %d of %d, %zu cells\n", o.output.c_str(), shard.first,
                     shard.second, part.cells.size());
        return kExitOk;
    }
    Table table;
    {
        // One display, as `bake`'s: the table's passes ("pass 1 of 2: E") share one bar, then its
        // preview is a step of its own.
        // A refinement's later rounds cost what they cost: its time left is its round's.
        ProgressStage stage(r.kind + " table into " + o.output, 1, {}, {}, r.tolerance.tolerance <= 0);
        stage.update(0, {}, 1);
        table = compute_lut(engine, r);
        OutputGroup together;  // the table and its preview land together or not at all
        write_table(table, o.output, setup.half);
        if (!o.no_preview) {
            stage.update(1, "drawing its preview " + preview);
            write_table_preview(table, preview, -1, PreviewLayout::Summary);
        }
        together.commit();
    }
    if (!o.no_preview && table.depth() > kSummarySlices)  // a summary: the full picture on demand
        std::fprintf(stderr, "brdfbake: preview %s shows %d of %d slices; brdfbake show %s --plot FILE.png draws more\n",
                     preview.c_str(), kSummarySlices, table.depth(), o.output.c_str());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "brdfbake: wrote %s: %s table %dx%dx%d (%s), max error %.2e, %.2f s\n", o.output.c_str(),
                 table.kind.c_str(), table.width(), table.height(), table.depth(), table.attributes.at("model").c_str(),
                 table.max_error(), seconds);
    return kExitOk;
}

/// The options at LutRequest's defaults, for the help text (an option not given leaves the
/// request's field to the preset or to LutRequest).
LutOptions default_options() {
    const LutRequest d;
    auto range = [](double lo, double hi) { return format_number(lo) + "," + format_number(hi); };
    LutOptions o;
    o.estimator = d.estimator;
    o.fresnel = d.fresnel;
    o.size = std::to_string(kDefaultLutTexels);
    o.mu_map = d.mu_map;
    o.alpha_map = d.alpha_map;
    o.eta_map = d.eta_map;
    o.texels = texels_name(d.texels);
    o.alpha_range = range(d.alpha_lo, d.alpha_hi);
    o.eta_range = range(d.eta_lo, d.eta_hi);
    o.mu_range = range(d.mu_lo, d.mu_hi);
    o.thickness_range = range(d.thickness_lo, d.thickness_hi);
    o.mu_floor = d.mu_floor;
    o.precision = precision_name(d.precision);
    return o;
}

}  // namespace

void add_lut_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    std::string kinds;
    for (const TableKind* k : table_kinds()) kinds += "\n  " + k->name + ": " + k->description;
    const auto [cmd, o] = add_command<LutOptions>(
        app, "lut", "write a lookup table (OpenEXR, CSV, C header, 16-bit PNG or .npy by the -o extension)", global,
        action, run_lut, default_options());
    std::string presets;
    for (const LutPreset& p : lut_presets())
        presets += "\n  " + p.name + ": " + p.engine + " " + p.ships + " (" + [&] {
            std::string k;
            for (const auto& kind : p.kinds) k += (k.empty() ? "" : ", ") + kind;
            return k;
        }() + "; ." + p.extension + "): " + p.summary;
    o->command = cmd;
    cmd->add_option("kind", o->kind, "table kind (default with --preset: the preset's first):" + kinds);
    cmd->add_option("--preset", o->preset,
                    "an engine's table layout; options given beside it override its settings:" + presets);
    cmd->add_option("--model", o->model, "model spec without alpha, e.g. ggx or ggx:shadowing=separable "
                                                  "(required without --preset)");
    cmd->add_option("--estimator", o->estimator,
                    "gen-schlick kinds: ratio (s = E_w / E, exact) or cycles (Blender Cycles' estimator: E_w of the "
                    "masking-only lobe, shadowing=masking, not divided by E); sheen-ltc: ratio (the walks to the end) or "
                    "cycles (the paper's precomputation behind Cycles' table: 16 scatterings, a walk still inside "
                    "counted by its direction)")
        ->check(CLI::IsMember({"ratio", "cycles"}))
        ->capture_default_str();
    cmd->add_option("--fresnel", o->fresnel, "Fresnel spec (albedo and eavg)")->capture_default_str();
    cmd->add_option("--wavelength", o->wavelength_nm,
                    "wavelength in nm for a Fresnel term that depends on it (metal:X, nk:FILE, thin-film); without it "
                    "the table holds its colour, R, G, B");
    cmd->add_option("--colour-space", o->colour_space,
                    "the colour of a spectral Fresnel term (no --wavelength): srgb (linear sRGB, CIE 1931 2-degree "
                    "observer under D65, 380-780 nm at 1 nm) or acescg (ACES AP1, D60 white by Bradford)")
        ->check(CLI::IsMember({"srgb", "acescg"}))
        ->capture_default_str();
    cmd->add_flag("--rgb-wavelengths", o->rgb_wavelengths,
                  "R, G, B at 650, 550 and 450 nm instead of the spectral colour (the tables before 2026-12)");
    cmd->add_option("--size", o->size, "N (N on every axis), WIDTHxHEIGHT (mu x alpha), WIDTHxHEIGHTxDEPTH (x eta) for the kinds with a "
                    "z axis; without --preset, " +
                        std::to_string(kDefaultLutTexels) + " on every axis")
        ->capture_default_str();
    cmd->add_option("--mu-map", o->mu_map,
                    "mu axis: linear (mu = u), sqrt (u = sqrt(mu)) or sqrt-one-minus (u = sqrt(1 - mu), three.js's LTC)")
        ->check(CLI::IsMember({"linear", "sqrt", "sqrt-one-minus"}))
        ->capture_default_str();
    cmd->add_option("--alpha-map", o->alpha_map, "roughness axis: alpha (v = alpha) or roughness (v = sqrt(alpha))")
        ->check(CLI::IsMember({"alpha", "roughness"}))
        ->capture_default_str();
    cmd->add_option("--alpha-range", o->alpha_range, "LO,HI of the roughness axis coordinate")->capture_default_str();
    cmd->add_option("--eta-range", o->eta_range, "LO,HI of eta (0 < LO < HI <= 100; below 1: from the denser side)")
        ->capture_default_str();
    cmd->add_option("--thickness-range", o->thickness_range,
                    "LO,HI of the film thickness in nm (the thin-film table's z axis; KHR_materials_iridescence's 100,400)")
        ->capture_default_str();
    cmd->add_option("--thickness-step", o->thickness_step,
                    "NM: thin-film slices at most NM apart over --thickness-range, ceil((HI - LO) / NM) + 1 of them "
                    "(the scene setting thickness_step), instead of --size's depth");
    cmd->add_option("--eta-map", o->eta_map,
                    "eta axis coordinate: linear (w = eta), f0 (w = ((eta-1)/(eta+1))^2) or cycles "
                    "(w = sqrt((eta-1)/(eta+1)), Cycles' glass tables)")
        ->capture_default_str();
    cmd->add_option("--texels", o->texels,
                    "where texels sit on every axis: centre ((i + 0.5)/N) or edge (i/(N - 1): the range's ends)")
        ->capture_default_str();
    cmd->add_option("--mu-range", o->mu_range, "LO,HI of the mu axis coordinate (0 <= LO < HI <= 1)")
        ->capture_default_str();
    cmd->add_option("--mu-floor", o->mu_floor, "mu below this is computed at it (0 < F < 1)")
        ->capture_default_str();
    cmd->add_option("--axes", o->axes,
                    "axis order, x first, by name: e.g. roughness,mu (names: mu or sqrt_mu, alpha or roughness, eta, "
                    "f0 or cycles_z)");
    cmd->add_option("--flip", o->flip, "axes stored from their upper end (texel 0 at HI), e.g. roughness");
    add_method_options(cmd, o->integration, "texel");
    add_precision_option(cmd, o->precision);
    cmd->add_flag("--half", o->half, "store half-float EXR channels instead of float32");
    cmd->add_option("-o,--output", o->output, "output file: .exr, .csv, .h, .png (16-bit) or .npy (+ .npy.json)")
        ->required();
    cmd->add_option("--preview", o->preview, "preview picture (.png or .svg); default: the output name with .png (NAME.preview.png for a .png table)");
    cmd->add_flag("--no-preview", o->no_preview, "write no preview picture");
    cmd->add_option("--shard", o->shard,
                    "K/N: compute shard K of N (0 <= K < N) into the part file -o; `brdfbake merge` joins the N "
                    "parts into the table (docs/cluster.md)");
}

}  // namespace brdfbake

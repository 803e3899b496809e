// `brdfbake lut KIND`: lookup tables of the kinds in brdfbake/table_kinds.h as OpenEXR, CSV or a C header.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/output.h"
#include "brdfbake/table_kinds.h"
#include "cli/cli.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

struct LutOptions {
    LutRequest request;
    std::string size = "32x32";
    std::string alpha_range = "0,1";
    std::string eta_range = "1,3";
    MethodOptions integration;
    std::string precision = "float";
    bool half = false;
    std::string preview;  // default: the output's name with .png
    bool no_preview = false;
    std::string output;
};

void parse_size(const std::string& text, LutRequest& r) {
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
    // An unknown kind is reported by validate_lut; its size is read as 2D meanwhile.
    const TableKind* kind = find_table_kind(r.kind);
    const bool three = kind && kind->eta_axis, one = kind && kind->one_dimensional;
    if (dims.size() > (three ? 3u : 2u))
        throw Error("--size: '" + text + "' has too many dimensions for a " + r.kind + " table");
    r.width = dims[0];
    r.height = dims.size() > 1 ? dims[1] : (one ? 1 : dims[0]);
    if (three) r.depth = dims.size() > 2 ? dims[2] : r.height;
    if (one && r.height != 1) throw Error("--size: an " + r.kind + " table is 1D; give N or Nx1");
}

int run_lut(LutOptions& o, const GlobalOptions& g) {
    const auto t0 = std::chrono::steady_clock::now();
    LutRequest& r = o.request;
    parse_size(o.size, r);
    const std::vector<double> range = parse_number_list(o.alpha_range, "--alpha-range");
    if (range.size() != 2) throw Error("--alpha-range needs two numbers: LO,HI");
    r.alpha_lo = range[0];
    r.alpha_hi = range[1];
    const std::vector<double> eta = parse_number_list(o.eta_range, "--eta-range");
    if (eta.size() != 2) throw Error("--eta-range needs two numbers: LO,HI");
    r.eta_lo = eta[0];
    r.eta_hi = eta[1];
    const MethodChoice choice = resolve_method_choice(o.integration);
    r.samples = choice.samples;
    r.method = choice.method;
    r.tolerance = choice.tolerance;
    r.precision = o.precision == "double" ? Precision::Double : Precision::Float;
    check_table_path(o.output);
    check_plot_output(o.preview, "--preview");
    std::string preview = o.preview;
    if (preview.empty()) preview = o.output.substr(0, o.output.find_last_of('.')) + ".png";
    if (!o.no_preview) check_output_path(preview);
    validate_lut(r);  // every input checked before the device is touched

    Engine engine(g.device, g.verbose);
    const Table table = compute_lut(engine, r);
    write_table(table, o.output, o.half);
    if (!o.no_preview) write_table_preview(table, preview);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "brdfbake: wrote %s: %s table %dx%dx%d (%s), max error %.2e, %.2f s\n", o.output.c_str(),
                 table.kind.c_str(), table.width(), table.height(), table.depth(), table.attributes.at("model").c_str(),
                 table.max_error(), seconds);
    return kExitOk;
}

}  // namespace

void add_lut_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    std::string kinds;
    for (const TableKind* k : table_kinds()) kinds += "\n  " + k->name + ": " + k->description;
    const auto [cmd, o] = add_command<LutOptions>(
        app, "lut", "write a lookup table (OpenEXR, CSV or C header by the -o extension)", global, action, run_lut);
    cmd->add_option("kind", o->request.kind, "table kind:" + kinds)->required();
    cmd->add_option("--model", o->request.model, "model spec without alpha, e.g. ggx or ggx:shadowing=separable")
        ->required();
    cmd->add_option("--fresnel", o->request.fresnel, "Fresnel spec (albedo and eavg)")->capture_default_str();
    cmd->add_option("--wavelength", o->request.wavelength_nm, "wavelength in nm for measured metals");
    cmd->add_option("--size", o->size, "WIDTHxHEIGHT (mu x alpha), WIDTHxHEIGHTxDEPTH (x eta) for dielectric, N for eavg")->capture_default_str();
    cmd->add_option("--mu-map", o->request.mu_map, "mu axis: linear (mu = u) or sqrt (u = sqrt(mu))")
        ->check(CLI::IsMember({"linear", "sqrt"}))
        ->capture_default_str();
    cmd->add_option("--alpha-map", o->request.alpha_map, "roughness axis: alpha (v = alpha) or roughness (v = sqrt(alpha))")
        ->check(CLI::IsMember({"alpha", "roughness"}))
        ->capture_default_str();
    cmd->add_option("--alpha-range", o->alpha_range, "LO,HI of the roughness axis coordinate")->capture_default_str();
    cmd->add_option("--eta-range", o->eta_range, "LO,HI of the eta axis (dielectric)")->capture_default_str();
    add_method_options(cmd, o->integration, "texel");
    add_precision_option(cmd, o->precision);
    cmd->add_flag("--half", o->half, "store half-float EXR channels instead of float32");
    cmd->add_option("-o,--output", o->output, "output file: .exr, .csv or .h")->required();
    cmd->add_option("--preview", o->preview, "preview picture (.png or .svg); default: the output name with .png");
    cmd->add_flag("--no-preview", o->no_preview, "write no preview picture");
}

}  // namespace brdfbake

// `brdfbake check` (white furnace, reciprocity and value scans with a verdict) and
// `brdfbake reciprocity` (the reciprocity-error map as EXR and heatmap).
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/check.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/table.h"
#include "cli/cli.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

constexpr double kDeg = 180.0 / M_PI;

struct CheckArgs {
    std::string model;
    std::string fresnel = "none";
    double wavelength_nm = 0.0;
    std::int64_t samples = 1 << 16;
    std::string precision = "float";
    std::string format = "table";
    std::string output;
    CheckOptions options;
};

std::string render(const CheckReport& r, Format format) {
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "check";
        j["model"] = r.model;
        j["fresnel"] = r.fresnel;
        j["passed"] = r.passed();
        j["energy"] = {{"max_albedo", r.max_albedo},
                       {"error", r.max_albedo_error},
                       {"mu", r.max_albedo_mu},
                       {"phi_deg", r.max_albedo_phi * kDeg},
                       {"tolerance", r.options.energy_tolerance},
                       {"directions", r.furnace_directions},
                       {"samples", r.furnace_samples},
                       {"violation", r.energy_violation}};
        j["reciprocity"] = {{"max_relative_error", r.max_rel},
                            {"theta_i_deg", r.max_rel_theta_i * kDeg},
                            {"theta_o_deg", r.max_rel_theta_o * kDeg},
                            {"delta_phi_deg", r.max_rel_dphi * kDeg},
                            {"tolerance", r.reciprocity_tolerance},
                            {"pairs", r.pairs},
                            {"nonfinite", r.scan_nonfinite},
                            {"violation", r.reciprocity_violation}};
        if (r.reciprocity_noise) j["reciprocity"]["standard_errors"] = r.reciprocity_sigmas;
        if (r.scan_nonfinite > 0) j["reciprocity"]["violation"] = nullptr;  // unknown
        j["values"] = {{"nonfinite", r.nonfinite},
                       {"min_value", r.min_value},
                       {"violation", r.value_violation}};
        if (!r.nonfinite_where.empty()) j["values"]["nonfinite_where"] = r.nonfinite_where;
        out << j.dump(2) << "\n";
        return out.str();
    }
    out << check_report_text(r);
    return out.str();
}

int run_check_command(const CheckArgs& a, const GlobalOptions& g) {
    const ModelConfig model = resolve_model_simulated(a.model);  // scattering=multiple: by walk estimates
    const FresnelConfig fresnel = resolve_fresnel(a.fresnel, a.wavelength_nm);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; drop --fresnel");
    const Format format = parse_format(a.format);
    if (a.samples < 16) throw Error("--samples must be at least 16");
    CheckOptions o = a.options;
    o.samples = std::uint64_t(a.samples);
    o.precision = a.precision == "double" ? Precision::Double : Precision::Float;
    Engine engine(g.device, g.verbose);
    const CheckReport report = run_check(engine, model, fresnel, o);
    emit(a.output, render(report, format));
    return report.passed() ? kExitOk : kExitViolation;
}

struct ReciprocityArgs {
    std::string model;
    std::string fresnel = "none";
    double wavelength_nm = 0.0;
    int resolution = 64;
    int phi_resolution = 32;
    std::string precision = "double";
    std::string output;
    std::string plot;
};

int run_reciprocity(const ReciprocityArgs& a, const GlobalOptions& g) {
    const ModelConfig model = resolve_model(a.model);
    const FresnelConfig fresnel = resolve_fresnel(a.fresnel, a.wavelength_nm);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; drop --fresnel");
    if (a.output.empty() && a.plot.empty()) throw Error("give -o FILE.exr and/or --plot FILE.png");
    if (!a.output.empty()) check_table_path(a.output);
    check_plot_output(a.plot, "--plot");
    Engine engine(g.device, g.verbose);
    const Precision p = a.precision == "double" ? Precision::Double : Precision::Float;
    const ReciprocityMap m = scan_reciprocity(engine, model, fresnel, a.resolution, a.phi_resolution, p);
    if (m.nonfinite > 0)
        throw Error("the model produced " + std::to_string(m.nonfinite) + " NaN or Inf values; run `brdfbake check`");

    Table t;
    t.kind = "reciprocity";
    t.quantity = "relative reciprocity error |f(wo,wi) - f(wi,wo)| / max(f(wo,wi), f(wi,wo)), worst over azimuths";
    t.x = make_axis("theta_i", "theta_i in degrees = u", 0.0, 90.0, m.n_theta);
    t.y = make_axis("theta_o", "theta_o in degrees = v", 0.0, 90.0, m.n_theta);
    t.x.parameter = t.x.coordinate;
    t.y.parameter = t.y.coordinate;
    t.channels = {"rel_error"};
    t.values = {m.max_rel};
    // The scan is exact up to round-off in the two evaluations.
    t.error.assign(m.max_rel.size(), (p == Precision::Double ? 2.2e-16 : 1.2e-7) * 8);
    t.attributes["model"] = model.canonical;
    t.attributes["fresnel"] = fresnel.canonical;
    t.attributes["method"] = "point evaluations on a grid: " + std::to_string(m.n_phi) + " azimuth differences x " +
                             std::to_string(m.n_phi_o) + " outgoing azimuths per pair";
    t.attributes["samples"] = std::to_string(m.n_phi * m.n_phi_o);
    t.attributes["precision"] = precision_name(p);
    if (!a.output.empty()) write_table(t, a.output);
    if (!a.plot.empty()) {
        PlotSpec ps;
        ps.title = "reciprocity: " + model.canonical;
        ps.x.label = "\\theta_i (degrees)";
        ps.y.label = "\\theta_o (degrees)";
        ps.legend = LegendPlace::None;
        Heatmap& h = ps.heatmap;
        h.nx = h.ny = m.n_theta;
        h.x_lo = h.y_lo = 0.0;
        h.x_hi = h.y_hi = 90.0;
        // Floor at 1e-16 so that exact zeros show at the bottom of the log scale.
        for (double v : m.max_rel) h.z.push_back(std::max(v, 1e-16));
        h.log_scale = true;
        h.z_lo = 1e-16;
        h.z_hi = std::max(1.0, *std::max_element(m.max_rel.begin(), m.max_rel.end()));
        h.colorbar_label = "relative error";
        write_plot(a.plot, ps, 900, 760);
    }
    double worst = 0;
    for (double v : m.max_rel) worst = std::max(worst, v);
    std::fprintf(stderr, "brdfbake: reciprocity of %s: worst relative error %.3g over %llu pairs\n",
                 model.canonical.c_str(), worst, (unsigned long long)(m.evaluations / 2));
    return kExitOk;
}

void add_model_options(CLI::App* cmd, std::string& model, std::string& fresnel, double& wavelength) {
    cmd->add_option("--model", model, "model spec, e.g. ggx:alpha=0.5")->required();
    cmd->add_option("--fresnel", fresnel, "Fresnel spec (see `brdfbake fresnel --help`)")->capture_default_str();
    cmd->add_option("--wavelength", wavelength, "wavelength in nm for measured metals");
}

}  // namespace

void add_check_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, a] = add_command<CheckArgs>(
        app, "check",
        "white furnace, reciprocity and NaN/Inf/negative scans; exit 0 passes, 1 a violation, 2 bad input", global,
        action, run_check_command);
    add_model_options(cmd, a->model, a->fresnel, a->wavelength_nm);
    cmd->add_option("--directions", a->options.directions, "furnace: outgoing theta values")->capture_default_str();
    cmd->add_option("--phis", a->options.phis, "furnace: outgoing phi values (anisotropic models)")->capture_default_str();
    cmd->add_option("--samples", a->samples, "furnace: samples per direction")->capture_default_str();
    add_precision_option(cmd, a->precision, "furnace kernel arithmetic");
    cmd->add_option("--energy-tolerance", a->options.energy_tolerance,
                    "allowed albedo above 1 beyond the error estimate")
        ->capture_default_str();
    cmd->add_option("--resolution", a->options.resolution, "reciprocity: theta values per axis")->capture_default_str();
    cmd->add_option("--phi-resolution", a->options.phi_resolution, "reciprocity: azimuth differences")
        ->capture_default_str();
    cmd->add_option("--reciprocity-tolerance", a->options.reciprocity_tolerance,
                    "allowed relative reciprocity error (at least 1e-3 on a device without double)")
        ->capture_default_str();
    add_format_option(cmd, a->format, {"table", "json"});
    cmd->add_option("-o,--output", a->output, "write the report to FILE");
}

void add_reciprocity_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, a] = add_command<ReciprocityArgs>(
        app, "reciprocity", "reciprocity-error map over (theta_i, theta_o) as EXR and heatmap", global, action,
        run_reciprocity);
    add_model_options(cmd, a->model, a->fresnel, a->wavelength_nm);
    cmd->add_option("--resolution", a->resolution, "theta values per axis")->capture_default_str();
    cmd->add_option("--phi-resolution", a->phi_resolution, "azimuth differences per pair")->capture_default_str();
    add_precision_option(cmd, a->precision);
    cmd->add_option("-o,--output", a->output, "map as .exr, .csv or .h");
    cmd->add_option("--plot", a->plot, "heatmap as .png or .svg");
}

}  // namespace brdfbake

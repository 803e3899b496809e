// `brdfbake albedo`: directional albedo E(mu) of one or more models, each value with its error
// estimate, as a table, JSON or CSV, and optionally as a plot of E(mu) curves.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/analytic.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "integrate/random_walk.h"
#include "models/key_reader.h"
#include "models/merl_file.h"
#include "plot/plot.h"
#include "tables/spectral_fresnel.h"

namespace brdfbake {
namespace {

constexpr double kDeg = 180.0 / M_PI;

struct AlbedoOptions {
    std::vector<std::string> models;
    std::string fresnel = "none";
    double wavelength_nm = 0.0;
    std::string mu;  // empty: kDefaultMu, or with --plot a dense set (plot_mus)
    std::string phi = "0";
    MethodOptions integration;
    std::string precision = "float";
    std::string format = "table";
    std::string output;
    std::string plot;
    std::string colour_space = "srgb";
    std::uint64_t seed = 0x62726466u;
};

/// One model's request and result.
struct Run {
    ModelConfig model;
    AlbedoRequest request;
    AlbedoResult result;
    WalkResult walk;  // scattering=multiple: the walks' three estimates (result holds the albedo)
    // A spectral Fresnel term without --wavelength: the albedo of each colour channel's curve,
    // each value's error its integration's plus the curve's and the spectrum's (spectral_fresnel.h).
    std::array<AlbedoResult, 3> colour;
};

const char* kWalkMeaning =
    "single: the first scattering order (the height-correlated Smith lobe's albedo); cutoff: the energy still "
    "inside the microsurface at the bounce limit, not in the albedo";
const char* kDielectricWalkMeaning =
    "albedo: R + T, the energy reflected (R) and transmitted (T) by the rough dielectric (transmitted radiance is "
    "T times eta^2); single, single_T: the first scattering order of R and T (the height-correlated lobes, "
    "Heitz 2014 eq. 99 and 100); cutoff: the energy still inside at the bounce limit, in neither";

const char* kLayerWalkMeaning =
    "albedo: R, the energy the sheen layer reflects (Zeltner et al. 2022), its error with the cut-off added; T: "
    "what it transmits to the base below (not reflected); single: R's first order; single_T: T without "
    "scattering (Beer-Lambert; JSON: unscattered_transmitted); cutoff: the energy still inside at the bounce "
    "limit, in neither";

/// A walk with reflected and transmitted columns: the rough dielectric's, or a layer's
/// (BB_TRAIT_LAYER_WALK: the sheen layer over a base that takes what it transmits).
bool walk_with_transmission(const ModelConfig& m) { return m.dielectric_walk || m.traits().layer_walk; }

const char* walk_meaning(const ModelConfig& m) {
    return m.traits().layer_walk ? kLayerWalkMeaning : m.dielectric_walk ? kDielectricWalkMeaning : kWalkMeaning;
}

/// The albedo a walk reports: R + T of the dielectric; R of a layer, with the cut-off energy in its
/// error (the walk's albedo up to the bounce limit); E of the conductor (its cut-off in a column).
AlbedoValue walk_albedo_value(const ModelConfig& m, const WalkAlbedo& w) {
    if (m.dielectric_walk) return w.total;
    AlbedoValue v = w.energy;
    if (m.traits().layer_walk) v.error += w.cutoff.value + w.cutoff.error;
    return v;
}

/// A walk run's extra columns of cell i: single scattering and cut-off energy, and the dielectric's
/// R, T and T's first order (empty for a conductor), each with its error.
void walk_columns(const Run& r, size_t i, Format format, std::ostream& out) {
    const bool csv = format == Format::Csv;
    if (!r.model.simulated) {
        if (csv) out << ",,,,,,,,,,";  // the ten walk columns, empty
        return;
    }
    const WalkAlbedo& w = r.walk.values[i];
    std::vector<const AlbedoValue*> cols = {&w.single, &w.cutoff};
    if (walk_with_transmission(r.model)) cols = {&w.energy, &w.transmitted, &w.single, &w.single_t, &w.cutoff};
    if (csv && walk_with_transmission(r.model)) cols = {&w.single, &w.cutoff, &w.energy, &w.transmitted, &w.single_t};
    char cell[64];
    for (const AlbedoValue* v : cols) {
        std::snprintf(cell, sizeof cell, csv ? ",%.17g,%.3e" : " %12.8f %10.2e", v->value, v->error);
        out << cell;
    }
    if (csv && !walk_with_transmission(r.model)) out << ",,,,,,";
}

/// A walk run's JSON fields of cell i.
void walk_json(const Run& r, size_t i, nlohmann::json& e) {
    if (!r.model.simulated) return;
    const WalkAlbedo& w = r.walk.values[i];
    e["single_scattering"] = w.single.value;
    e["single_scattering_error"] = w.single.error;
    e["cutoff"] = w.cutoff.value;
    e["cutoff_error"] = w.cutoff.error;
    if (!walk_with_transmission(r.model)) return;
    e["reflected"] = w.energy.value;
    e["reflected_error"] = w.energy.error;
    e["transmitted"] = w.transmitted.value;
    e["transmitted_error"] = w.transmitted.error;
    // the dielectric's T after one scattering; a layer's T without scattering (Beer-Lambert)
    const std::string t1 = r.model.traits().layer_walk ? "unscattered_transmitted" : "single_scattering_transmitted";
    e[t1] = w.single_t.value;
    e[t1 + "_error"] = w.single_t.error;
}

const char* kColourErrorMeaning =
    "; in colour, each channel's also adds its tabulated colour curve's interpolation error and its 1 nm vs 2 nm "
    "spectral sums' difference";

const char* kErrorMeaning =
    "3 standard errors of the replicas plus 3 |E| / N for what N samples cannot see (sampling), or the "
    "difference from the half-order rule, the larger of the last two differences where the n/4, n/2 and n "
    "rules do not converge geometrically (quadrature), plus a floating-point bound";

std::string render(Format format, const FresnelConfig& fresnel, const std::vector<Run>& runs, const Engine& engine,
                   double seconds) {
    std::ostringstream out;
    const Run& first = runs.front();
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "albedo";
        if (runs.size() == 1) j["model"] = first.model.canonical;
        j["models"] = nlohmann::json::array();
        for (const Run& r : runs) j["models"].push_back(r.model.canonical);
        j["fresnel"] = fresnel.canonical;
        j["method"] = has_analytic_albedo(first.model) ? "analytic" : method_name(first.result.values.front().method);
        j["estimator"] = first.result.method;
        j["precision"] = precision_name(first.request.precision);
        j["samples"] = first.result.samples_per_cell;
        if (first.result.tolerance > 0.0) {
            j["tolerance"] = first.result.tolerance;
            j["rounds"] = first.result.rounds;
            j["total_samples"] = first.result.total_samples;
        }
        j["error_meaning"] = kErrorMeaning;
        j["device"] = engine.device().name;
        j["seconds"] = seconds;
        j["results"] = nlohmann::json::array();
        for (const Run& r : runs)
            for (size_t i = 0; i < r.request.cells.size(); ++i)
            {
                nlohmann::json e = {{"model", r.model.canonical},
                                    {"mu", r.request.cells[i].mu},
                                    {"phi_deg", r.request.cells[i].phi * kDeg},
                                    {"albedo", r.result.values[i].value},
                                    {"error", r.result.values[i].error}};
                walk_json(r, i, e);
                if (r.result.tolerance > 0.0) {
                    e["method"] = method_name(r.result.values[i].method);
                    e["samples"] = r.result.values[i].samples;
                }
                MerlUnmeasured u;
                if (merl_unmeasured(r.model, {r.request.cells[i].mu}, u)) {
                    e["unmeasured_bins"] = u.bins;
                    e["unmeasured_share"] = u.share.front();
                }
                SpecularTransmission t;
                if (analytic_transmission(r.model, r.request.cells[i].mu, t)) {
                    e["transmission"] = t.energy;
                    e["radiance_factor"] = t.radiance_factor;
                }
                j["results"].push_back(e);
            }
        out << j.dump(2) << "\n";
        return out.str();
    }
    char line[256];
    if (format == Format::Csv) {
        bool walks = false;
        for (const Run& r : runs) walks = walks || r.model.simulated;
        out << (runs.size() > 1 ? "model," : "") << "mu,phi_deg,albedo,error"
            << (walks ? ",single,single_error,cutoff,cutoff_error,R,R_error,T,T_error,single_T,single_T_error" : "")
            << "\n";
        for (const Run& r : runs)
            for (size_t i = 0; i < r.request.cells.size(); ++i) {
                std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.3e", r.request.cells[i].mu,
                              r.request.cells[i].phi * kDeg, r.result.values[i].value, r.result.values[i].error);
                out << (runs.size() > 1 ? "\"" + r.model.canonical + "\"," : "") << line;
                if (walks) walk_columns(r, i, Format::Csv, out);
                out << "\n";
            }
        return out.str();
    }
    for (const Run& r : runs) {
        out << "# albedo of " << r.model.canonical << ", Fresnel " << fresnel.canonical << "\n";
        if (r.result.samples_per_cell == 0)
            out << "# " << r.result.method << ", computed on the host in double\n"
                << "# error: a rounding bound\n";
        else
            out << "# " << r.result.method << ", " << precision_name(r.request.precision) << ", "
                << (r.result.tolerance > 0.0 ? "at most " : "") << r.result.samples_per_cell
                << (r.model.simulated ? " walks" : " samples") << " per direction, " << engine.device().name << "\n"
                << "# error: " << kErrorMeaning << "\n";
        std::vector<double> mus;
        for (const auto& c : r.request.cells) mus.push_back(c.mu);
        out << merl_unmeasured_line(r.model, mus);
        if (r.model.simulated) out << "# " << walk_meaning(r.model) << "\n";
        out << "        mu   phi_deg       albedo      error"
            << (walk_with_transmission(r.model) ? "            R      error            T      error       single      error"
                                          "     single_T      error       cutoff      error"
                : r.model.simulated     ? "       single      error       cutoff      error"
                                        : "")
            << "\n";
        for (size_t i = 0; i < r.request.cells.size(); ++i) {
            std::snprintf(line, sizeof line, "%10.6f %9.3f %12.8f %10.2e", r.request.cells[i].mu,
                          r.request.cells[i].phi * kDeg, r.result.values[i].value, r.result.values[i].error);
            out << line;
            walk_columns(r, i, Format::Table, out);
            out << "\n";
        }
        if (&r != &runs.back()) out << "\n";
    }
    return out.str();
}

/// The colour runs (a spectral Fresnel term without --wavelength) as a table, JSON or CSV: per
/// direction the albedo in each channel and each channel's error.
std::string render_colour(Format format, const std::string& fresnel, const tables::SpectralCurves& curves,
                          const std::vector<Run>& runs, const Engine& engine, double seconds) {
    std::ostringstream out;
    const Run& first = runs.front();
    auto rgb = [](const Run& r, size_t i, bool error) {
        std::array<double, 3> v{};
        for (size_t ch = 0; ch < 3; ++ch) v[ch] = error ? r.colour[ch].values[i].error : r.colour[ch].values[i].value;
        return v;
    };
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "albedo";
        j["models"] = nlohmann::json::array();
        for (const Run& r : runs) j["models"].push_back(r.model.canonical);
        j["fresnel"] = fresnel;
        j["colour_space"] = curves.colour;
        j["estimator"] = first.colour[0].method;
        j["precision"] = precision_name(first.request.precision);
        j["error_meaning"] = std::string(kErrorMeaning) + kColourErrorMeaning;
        j["device"] = engine.device().name;
        j["seconds"] = seconds;
        j["results"] = nlohmann::json::array();
        for (const Run& r : runs)
            for (size_t i = 0; i < r.request.cells.size(); ++i)
                j["results"].push_back({{"model", r.model.canonical},
                                        {"mu", r.request.cells[i].mu},
                                        {"phi_deg", r.request.cells[i].phi * kDeg},
                                        {"rgb", rgb(r, i, false)},
                                        {"rgb_error", rgb(r, i, true)}});
        out << j.dump(2) << "\n";
        return out.str();
    }
    char line[256];
    const bool csv = format == Format::Csv;
    if (csv) out << (runs.size() > 1 ? "model," : "") << "mu,phi_deg,R,G,B,error_R,error_G,error_B\n";
    for (const Run& r : runs) {
        if (!csv)
            out << "# albedo of " << r.model.canonical << ", Fresnel " << fresnel << " in " << curves.colour << "\n# "
                << r.colour[0].method << ", " << precision_name(r.request.precision) << ", " << engine.device().name
                << "\n# error: " << kErrorMeaning << kColourErrorMeaning << "\n"
                << "        mu   phi_deg            R            G            B      error\n";
        for (size_t i = 0; i < r.request.cells.size(); ++i) {
            const auto v = rgb(r, i, false), e = rgb(r, i, true);
            if (csv) {
                std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.3e,%.3e,%.3e\n", r.request.cells[i].mu,
                              r.request.cells[i].phi * kDeg, v[0], v[1], v[2], e[0], e[1], e[2]);
                out << (runs.size() > 1 ? "\"" + r.model.canonical + "\"," : "") << line;
            } else {
                std::snprintf(line, sizeof line, "%10.6f %9.3f %12.8f %12.8f %12.8f %10.2e\n", r.request.cells[i].mu,
                              r.request.cells[i].phi * kDeg, v[0], v[1], v[2], std::max({e[0], e[1], e[2]}));
                out << line;
            }
        }
        if (!csv && &r != &runs.back()) out << "\n";
    }
    return out.str();
}

/// The albedo of each colour channel of `curves` (tables/spectral_fresnel.h), as `lut conductor`
/// makes its channels: the curve's and the spectrum's errors are added to the integration's, and
/// a --tolerance leaves the integration what those two leave of it.
void integrate_colour_run(Engine& engine, Run& r, const tables::SpectralCurves& curves, const ToleranceRequest& tolerance) {
    for (size_t ch = 0; ch < 3; ++ch) {
        const double own = curves.curve_error[ch] + curves.spectral_error[ch];
        ToleranceRequest t = tolerance;
        if (t.tolerance > 0.0) {
            const double share = 1.0 - own / t.tolerance;
            if (share < 0.25)
                throw Error("--tolerance " + format_number(t.tolerance) + " is below what the spectral colour allows in "
                            "channel " + tables::colour_channel_names()[ch] + " (its curve's and spectrum's error " +
                            format_number(own) + "; ask for at least " + format_number(4.0 * own) + ", or give --wavelength NM)");
            t.tolerance *= share;
        }
        AlbedoRequest req = r.request;
        req.fresnel = curves.channel[ch];
        r.colour[ch] = albedo_of_model(engine, r.model, curves.channel[ch], req, t);
        for (AlbedoValue& v : r.colour[ch].values) v.error += own;
    }
}

void plot_colour_runs(const std::string& path, const std::string& fresnel, const std::vector<Run>& runs) {
    PlotSpec p;
    p.title = "directional albedo E(\\mu), Fresnel " + plot_text(short_numbers(fresnel)) + ", linear sRGB";
    p.x = PlotAxis{"\\mu = cos \\theta_o", 0.0, 1.0, 0.0};
    p.y.label = "E(\\mu)";
    p.legend = LegendPlace::Outside;
    const char colours[3] = {'r', 'g', 'b'};
    const char dashes[4] = {'-', ';', '|', ':'};  // one per model
    for (const Run& r : runs)
        for (size_t ch = 0; ch < 3; ++ch) {
            const std::string pen = std::string(1, colours[ch]) + dashes[size_t(&r - runs.data()) % 4] + "2";
            Curve c{plot_text(r.model.canonical) + " " + tables::colour_channel_names()[ch], {}, {}, pen};
            for (size_t i = 0; i < r.request.cells.size(); ++i) {
                c.x.push_back(r.request.cells[i].mu);
                c.y.push_back(r.colour[ch].values[i].value);
            }
            p.curves.push_back(c);
        }
    write_plot(path, p, 1300, 640);
}

constexpr const char* kDefaultMu = "0.05,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1";

/// The directions of a plot without --mu: 64 values of mu = u^2, u evenly spaced, dense at grazing
/// angles where E(mu) changes fastest, from mu = 1/4096 to 1.
std::vector<double> plot_mus() {
    std::vector<double> mus;
    for (int k = 1; k <= 64; ++k) mus.push_back(double(k * k) / (64.0 * 64.0));
    return mus;
}

void plot_runs(const std::string& path, const FresnelConfig& fresnel, const std::vector<Run>& runs) {
    PlotSpec p;
    p.title = "directional albedo E(\\mu)" + (fresnel.kind ? ", Fresnel " + fresnel.canonical : std::string());
    p.x.label = "\\mu = cos \\theta_o";
    p.y.label = "E(\\mu)";
    p.x.lo = 0.0;
    p.x.hi = 1.0;
    p.legend = LegendPlace::Outside;
    for (const Run& r : runs) {
        // One curve per model and azimuth.
        std::map<double, Curve> by_phi;
        for (size_t i = 0; i < r.request.cells.size(); ++i) {
            Curve& c = by_phi[r.request.cells[i].phi];
            c.x.push_back(r.request.cells[i].mu);
            c.y.push_back(r.result.values[i].value);
        }
        for (auto& kv : by_phi) {
            std::string label = plot_text(r.model.canonical);
            if (by_phi.size() > 1) label += ", \\phi = " + format_number(std::round(kv.first * kDeg * 10) / 10);
            kv.second.label = label;
            p.curves.push_back(kv.second);
        }
    }
    write_plot(path, p, 1300, 640);  // room for the legend right of the curves
}

/// What the random walk (scattering=multiple) does not support yet: one line naming it.
void check_walk_options(const ModelConfig& model, const AlbedoOptions& o) {
    const std::string what = "model '" + model.canonical + "': ";
    if (o.integration.method != "auto" && o.integration.method != "mc")
        throw Error(what + "scattering=multiple is integrated by random walks (Philox, as --method mc); --method " +
                    o.integration.method + " is not supported for it");
}

int run_albedo(const AlbedoOptions& o, const GlobalOptions& g) {
    const auto t0 = std::chrono::steady_clock::now();
    // Check every input before touching the device.
    // A term that depends on the wavelength, without --wavelength: its colour (fresnel_needs_wavelength).
    const bool colour = o.wavelength_nm == 0.0 && fresnel_needs_wavelength(o.fresnel);
    if (!colour && o.colour_space != "srgb") throw Error("--colour-space is for a spectral --fresnel (metal:, nk:, thin-film:) without --wavelength");
    const FresnelConfig fresnel = resolve_fresnel(o.fresnel, colour ? 550.0 : o.wavelength_nm);
    const Format format = parse_format(o.format);
    check_plot_output(o.plot, "--plot");
    check_text_output(o.output);
    const std::vector<double> mus = !o.mu.empty() ? parse_number_list(o.mu, "--mu")
                                    : o.plot.empty() ? parse_number_list(kDefaultMu, "--mu")
                                                     : plot_mus();
    for (double mu : mus)
        if (!(mu > 0.0 && mu <= 1.0))
            throw Error("--mu: " + format_number(mu) + " is out of range; mu = cos(theta_o) must lie in (0, 1]");
    const std::vector<double> phis = parse_number_list(o.phi, "--phi");
    const MethodChoice choice = resolve_method_choice(o.integration);
    std::vector<Run> runs;
    for (const std::string& spec : o.models) {
        Run r;
        r.model = resolve_model_simulated(spec);
        if (r.model.simulated) check_walk_options(r.model, o);
        if (colour && r.model.simulated)
            throw Error("model '" + r.model.canonical + "': the random walk takes one wavelength of " + o.fresnel +
                        "; give --wavelength NM");
        if (fresnel.kind != 0 && r.model.dielectric_walk)
            throw Error("model '" + r.model.canonical + "': eta=E walks the rough dielectric with the exact dielectric "
                        "Fresnel term of eta; drop --fresnel");
        if (fresnel.kind != 0 && !r.model.uses_fresnel)
            throw Error("model '" + r.model.name + "' has no Fresnel term; drop --fresnel");
        r.request.model = r.model.id;
        r.request.fresnel = fresnel;
        r.request.samples = choice.samples;
        r.request.method = choice.method;
        r.request.precision = o.precision == "double" ? Precision::Double : Precision::Float;
        r.request.seed = o.seed;
        for (double phi_deg : phis)
            for (const auto& c : cells_for(mus, azimuth_from_degrees(phi_deg), r.model.params))
                r.request.cells.push_back(c);
        runs.push_back(std::move(r));
    }

    Engine engine(g.device, g.verbose);
    if (colour) {
        const tables::SpectralCurves curves = tables::spectral_curves(engine, o.fresnel, o.colour_space,
                                                                      runs.front().request.precision);
        for (Run& r : runs) integrate_colour_run(engine, r, curves, choice.tolerance);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!o.plot.empty()) plot_colour_runs(o.plot, o.fresnel, runs);
        emit(o.output, render_colour(format, o.fresnel, curves, runs, engine, seconds));
        return kExitOk;
    }
    for (Run& r : runs) {
        if (r.model.simulated) {
            r.walk = choice.tolerance.tolerance > 0.0 ? walk_albedo_to_tolerance(engine, r.request, choice.tolerance)
                                                      : walk_albedo(engine, r.request);
            r.result.tolerance = choice.tolerance.tolerance;
            r.result.rounds = r.walk.rounds;
            r.result.total_samples = r.walk.total_walks;
            r.result.method = r.walk.method;
            r.result.samples_per_cell = r.walk.walks_per_cell;
            r.result.kernel_seconds = r.walk.kernel_seconds;
            for (const WalkAlbedo& w : r.walk.values) r.result.values.push_back(walk_albedo_value(r.model, w));
        } else {
            r.result = albedo_of_model(engine, r.model, fresnel, r.request, choice.tolerance);
        }
        if (g.verbose)
            std::cerr << "brdfbake: " << r.model.canonical << ": kernel " << r.result.kernel_seconds * 1e3 << " ms\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.plot.empty()) plot_runs(o.plot, fresnel, runs);
    emit(o.output, render(format, fresnel, runs, engine, seconds));
    return kExitOk;
}

}  // namespace

void add_albedo_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<AlbedoOptions>(
        app, "albedo", "directional albedo E(mu_o) = integral of f cos(theta_i) dwi", global, action, run_albedo);
    cmd->add_option("--model", o->models,
                    "model spec, e.g. ggx:alpha=0.5 or lambert:rho=0.8; repeat it to compare models")
        ->required();
    cmd->add_option("--fresnel", o->fresnel, fresnel_spec_help())->capture_default_str();
    cmd->add_option("--wavelength", o->wavelength_nm,
                    "wavelength in nm for measured metals and films (metal:Al, nk:FILE, thin-film:); without it, "
                    "such a term gives the albedo's colour (R, G, B over 380-780 nm, CIE 1931, D65)");
    add_colour_space_option(cmd, o->colour_space,
                            "the colour of a spectral --fresnel without --wavelength: srgb (linear sRGB) or acescg");
    cmd->add_option("--mu", o->mu,
                    "comma-separated cos(theta_o) values in (0, 1] (default: 0.05,0.1,0.2,...,0.9,1; with --plot, 64 "
                    "values from 1/4096 to 1, dense at grazing angles)");
    cmd->add_option("--phi", o->phi, "comma-separated phi_o in degrees (anisotropic models)")->capture_default_str();
    add_method_options(cmd, o->integration, "direction");
    add_precision_option(cmd, o->precision);
    add_format_option(cmd, o->format, {"table", "json", "csv"});
    cmd->add_option("-o,--output", o->output, "write to FILE instead of standard output");
    cmd->add_option("--plot", o->plot, "draw E(mu) curves, one per model (and phi), into FILE.png or .svg");
    cmd->add_option("--seed", o->seed, "seed of the randomised point sets")->capture_default_str();
}

}  // namespace brdfbake

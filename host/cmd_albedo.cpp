// `brdfbake albedo`: directional albedo E(mu) of a model, each value with its error estimate.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli.h"
#include "key_reader.h"

namespace brdfbake {
namespace {

struct AlbedoOptions {
    std::string model;
    std::string fresnel = "none";
    double wavelength_nm = 0.0;
    std::string mu = "0.05,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1";
    std::string phi = "0";
    std::int64_t samples = 1 << 18;
    std::string method = "auto";
    std::string precision = "float";
    std::string format = "table";
    std::string output;
    std::uint64_t seed = 0x62726466u;
};

std::string render(const AlbedoOptions& o, const ModelConfig& model, const FresnelConfig& fresnel,
                   const AlbedoRequest& req, const AlbedoResult& res, const Engine& engine, double seconds) {
    const Format format = parse_format(o.format);
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "albedo";
        j["model"] = model.canonical;
        j["fresnel"] = fresnel.canonical;
        j["method"] = "importance";
        j["estimator"] = res.method;
        j["precision"] = precision_name(req.precision);
        j["samples"] = res.samples_per_cell;
        j["error_meaning"] = "3 standard errors of the replicas plus a floating-point bound";
        j["device"] = engine.device().name;
        j["seconds"] = seconds;
        j["results"] = nlohmann::json::array();
        for (size_t i = 0; i < req.cells.size(); ++i)
            j["results"].push_back({{"mu", req.cells[i].mu},
                                    {"phi_deg", req.cells[i].phi * 180.0 / M_PI},
                                    {"albedo", res.values[i].value},
                                    {"error", res.values[i].error}});
        out << j.dump(2) << "\n";
    } else if (format == Format::Csv) {
        out << "mu,phi_deg,albedo,error\n";
        char line[160];
        for (size_t i = 0; i < req.cells.size(); ++i) {
            std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.3e\n", req.cells[i].mu,
                          req.cells[i].phi * 180.0 / M_PI, res.values[i].value, res.values[i].error);
            out << line;
        }
    } else {
        out << "# albedo of " << model.canonical << ", Fresnel " << fresnel.canonical << "\n"
            << "# " << res.method << ", " << precision_name(req.precision) << ", " << res.samples_per_cell
            << " samples per direction, " << engine.device().name << "\n"
            << "# error: 3 standard errors + floating-point bound\n";
        out << "        mu   phi_deg       albedo      error\n";
        char line[160];
        for (size_t i = 0; i < req.cells.size(); ++i) {
            std::snprintf(line, sizeof line, "%10.6f %9.3f %12.8f %10.2e\n", req.cells[i].mu,
                          req.cells[i].phi * 180.0 / M_PI, res.values[i].value, res.values[i].error);
            out << line;
        }
    }
    return out.str();
}

int run_albedo(const AlbedoOptions& o, const GlobalOptions& g) {
    const auto t0 = std::chrono::steady_clock::now();
    // Check every input before touching the device.
    const ModelConfig model = resolve_model(o.model);
    const FresnelConfig fresnel = resolve_fresnel(o.fresnel, o.wavelength_nm);
    parse_format(o.format);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; drop --fresnel");
    const std::vector<double> mus = parse_number_list(o.mu, "--mu");
    for (double mu : mus)
        if (!(mu > 0.0 && mu <= 1.0))
            throw Error("--mu: " + format_number(mu) + " is out of range; mu = cos(theta_o) must lie in (0, 1]");
    const std::vector<double> phis = parse_number_list(o.phi, "--phi");
    if (o.samples <= 0) throw Error("--samples must be positive");

    AlbedoRequest req;
    req.model = model.id;
    req.fresnel = fresnel;
    req.samples = std::uint64_t(o.samples);
    req.precision = o.precision == "double" ? Precision::Double : Precision::Float;
    req.seed = o.seed;
    for (double phi_deg : phis)
        for (const auto& c : cells_for(mus, phi_deg * M_PI / 180.0, model.params)) req.cells.push_back(c);

    Engine engine(g.device, g.verbose);
    const AlbedoResult res = compute_albedo(engine, req);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (g.verbose)
        std::cerr << "brdfbake: kernel " << res.kernel_seconds * 1e3 << " ms, total " << seconds * 1e3 << " ms\n";
    emit(o.output, render(o, model, fresnel, req, res, engine, seconds));
    return kExitOk;
}

}  // namespace

void add_albedo_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    auto o = std::make_shared<AlbedoOptions>();
    CLI::App* cmd = app.add_subcommand("albedo", "directional albedo E(mu_o) = integral of f cos(theta_i) dwi");
    cmd->add_option("--model", o->model, "model spec, e.g. ggx:alpha=0.5 or lambert:rho=0.8")->required();
    cmd->add_option("--fresnel", o->fresnel, "Fresnel spec: none, schlick:f0=F0")->capture_default_str();
    cmd->add_option("--wavelength", o->wavelength_nm, "wavelength in nm for measured metals (metal:Al, nk:FILE)");
    cmd->add_option("--mu", o->mu, "comma-separated cos(theta_o) values in (0, 1]")->capture_default_str();
    cmd->add_option("--phi", o->phi, "comma-separated phi_o in degrees (anisotropic models)")->capture_default_str();
    cmd->add_option("--samples", o->samples, "samples per direction")->capture_default_str();
    cmd->add_option("--method", o->method, "integration method")->capture_default_str()
        ->check(CLI::IsMember({"auto", "importance"}));
    cmd->add_option("--precision", o->precision, "kernel arithmetic")->capture_default_str()
        ->check(CLI::IsMember({"float", "double"}));
    cmd->add_option("--format", o->format, "output format")->capture_default_str()
        ->check(CLI::IsMember({"table", "json", "csv"}));
    cmd->add_option("-o,--output", o->output, "write to FILE instead of standard output");
    cmd->add_option("--seed", o->seed, "seed of the randomised point sets")->capture_default_str();
    cmd->callback([o, &global, &action] { action = [o, &global] { return run_albedo(*o, global); }; });
}

}  // namespace brdfbake

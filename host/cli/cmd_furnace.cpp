// `brdfbake furnace`: the white-furnace picture. A row of spheres lit by a uniform white
// environment (radiance 1), one per model; each pixel shows E(n.v), the light the sphere sends
// back, so energy loss reads at a glance as darkening against the white background.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "brdfbake/albedo.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "cli/furnace_sphere.h"
#include "models/key_reader.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

// Linear interpolation of E at mu from values at nodes mu_k = ((k + 0.5)/n)^2 (denser at grazing).
double interpolate(const std::vector<double>& e, double mu) {
    const int n = int(e.size());
    const double u = std::sqrt(std::max(mu, 0.0)) * n - 0.5;
    if (u <= 0) return e.front();
    if (u >= n - 1) return e.back();
    const int k = int(u);
    return e[size_t(k)] + (u - k) * (e[size_t(k) + 1] - e[size_t(k)]);
}

}  // namespace

std::vector<double> furnace_nodes(int n) {
    std::vector<double> mus;
    for (int k = 0; k < n; ++k) mus.push_back(std::pow((k + 0.5) / n, 2));
    return mus;
}

PlotSpec furnace_sphere(const std::string& title, const std::vector<double>& e, int pixels) {
    PlotSpec p;
    p.axes = false;
    p.title = title;
    Curve outline;  // the sphere's silhouette, so that a sphere with E = 1 still shows
    outline.style = "h-1";
    for (int k = 0; k <= 256; ++k) {
        outline.x.push_back(std::cos(k * 2 * M_PI / 256));
        outline.y.push_back(std::sin(k * 2 * M_PI / 256));
    }
    p.curves.push_back(outline);
    Heatmap& h = p.heatmap;
    h.nx = h.ny = pixels;
    h.x_lo = h.y_lo = -1.0;
    h.x_hi = h.y_hi = 1.0;
    h.z_lo = 0.0;
    h.z_hi = 1.0;
    h.scheme = "kw";
    // The environment (E = 1 by definition) in a colour of its own, so that a sphere that
    // conserves energy (white) still stands out; the figure's colour bar gives the scale.
    h.gap_colour = "{x8DB3D9}";
    for (int j = 0; j < pixels; ++j)
        for (int i = 0; i < pixels; ++i) {
            const double x = -1 + (i + 0.5) * 2.0 / pixels, y = -1 + (j + 0.5) * 2.0 / pixels;
            const double r2 = x * x + y * y;
            // Background: a gap (the environment's colour). Sphere: E(n.v) for the view along -z.
            h.z.push_back(r2 >= 1.0 ? NAN : std::min(1.0, interpolate(e, std::sqrt(1.0 - r2))));
        }
    return p;
}

Figure furnace_figure(int pixels) {
    Figure fig;
    fig.panel_width = pixels * 2;
    fig.panel_height = int(std::lround(fig.panel_width * 0.94 / 0.86));  // square spheres (see write_figure)
    fig.colorbar_label = "E(\\mu); environment (blue) = 1";
    fig.colorbar_scheme = "kw";
    return fig;
}

namespace {

struct FurnaceArgs {
    std::vector<std::string> models;
    std::string roughness;  // a list applied to one model spec without alpha
    std::string fresnel = "none";
    double wavelength_nm = 0.0;
    int pixels = 160;         // sphere diameter
    int nodes = 64;           // mu nodes of E(mu), interpolated per pixel
    std::int64_t samples = 1 << 16;
    std::string output;
};

int run_furnace(const FurnaceArgs& a, const GlobalOptions& g) {
    check_plot_output(a.output, "-o");
    if (a.pixels < 16 || a.pixels > 2048) throw Error("--pixels must be 16 to 2048");
    if (a.nodes < 4 || a.nodes > 4096) throw Error("--nodes must be 4 to 4096");
    if (a.samples < 16) throw Error("--samples must be at least 16");
    std::vector<std::string> specs = a.models, labels;
    if (!a.roughness.empty()) {
        if (specs.size() != 1) throw Error("--roughness needs exactly one --model without alpha, e.g. --model ggx");
        const std::string base = specs[0];
        specs.clear();
        for (double r : parse_number_list(a.roughness, "--roughness")) {
            specs.push_back(base + (base.find(':') == std::string::npos ? ":" : ",") + "roughness=" + format_number(r));
            labels.push_back("roughness " + format_number(r));
        }
    } else {
        labels = specs;
    }
    if (specs.empty()) throw Error("give --model SPEC (repeatable) or --model NAME --roughness LIST");
    const FresnelConfig fresnel = resolve_fresnel(a.fresnel, a.wavelength_nm);
    std::vector<ModelConfig> models;
    for (const auto& s : specs) {
        models.push_back(resolve_model(s));
        if (fresnel.kind != 0 && !models.back().uses_fresnel)
            throw Error("model '" + models.back().name + "' has no Fresnel term; drop --fresnel");
    }

    Engine engine(g.device, g.verbose);
    Figure fig = furnace_figure(a.pixels);
    const std::vector<double> mus = furnace_nodes(a.nodes);
    std::optional<ProgressStage> stage;  // ends before the figure is written
    stage.emplace("white furnace of " + std::to_string(models.size()) + (models.size() == 1 ? " model" : " models"),
                  models.size(), models.size() == 1 ? "" : "models");
    for (size_t mi = 0; mi < models.size(); ++mi) {
        const ModelConfig& m = models[mi];
        stage->update(mi, labels[mi], 1);
        AlbedoRequest req;
        req.model = m.id;
        req.fresnel = fresnel;
        req.cells = cells_for(mus, 0.0, m.params);
        req.samples = std::uint64_t(a.samples);
        const AlbedoResult res = compute_albedo(engine, req);
        std::vector<double> e;
        for (const auto& v : res.values) e.push_back(v.value);
        fig.panels.push_back(furnace_sphere(labels[mi], e, a.pixels));
    }
    stage->update(models.size());
    stage.reset();
    write_figure(a.output, fig);
    std::fprintf(stderr, "brdfbake: wrote %s: %zu spheres\n", a.output.c_str(), models.size());
    return kExitOk;
}

}  // namespace

void add_furnace_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, a] = add_command<FurnaceArgs>(
        app, "furnace", "white-furnace picture: spheres under uniform white light, one per model", global, action,
        run_furnace);
    cmd->add_option("--model", a->models, "model spec (repeatable), or a model without alpha with --roughness")->required();
    cmd->add_option("--roughness", a->roughness, "comma-separated roughness values (alpha = roughness^2)");
    cmd->add_option("--fresnel", a->fresnel, "Fresnel spec")->capture_default_str();
    cmd->add_option("--wavelength", a->wavelength_nm, "wavelength in nm for measured metals");
    cmd->add_option("--pixels", a->pixels, "sphere diameter in pixels")->capture_default_str();
    cmd->add_option("--nodes", a->nodes, "mu values at which E is integrated")->capture_default_str();
    cmd->add_option("--samples", a->samples, "samples per mu value")->capture_default_str();
    cmd->add_option("-o,--output", a->output, "picture: .png or .svg")->required();
}

}  // namespace brdfbake

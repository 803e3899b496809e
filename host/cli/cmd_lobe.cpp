// `brdfbake lobe`: the lobe of a BRDF for a given incident direction, in its plane of incidence:
// the radiance reflected towards wo per unit irradiance from wi, f(wi, wo) cos(theta_i), drawn
// as a polar curve over the outgoing angle (Disney's BRDF Explorer draws the same picture).
// Several models and incident angles overlay; delta lobes are drawn as an arrow along the
// mirror direction whose length is their reflectance. The numbers behind the picture go to
// --data as CSV, computed by the same eval kernel every other command uses.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "brdfbake/analytic.h"
#include "brdfbake/error.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "models/key_reader.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

constexpr double kRad = M_PI / 180.0;

struct LobeOptions {
    std::vector<std::string> models;
    std::string theta_i = "30,60";
    double phi_i = 0.0;
    std::string fresnel = "none";
    double wavelength_nm = 0.0;
    int resolution = 361;  // outgoing angles over [-90, 90] degrees
    bool log_scale = false;
    std::string precision = "double";
    std::string output;  // picture
    std::string data;    // CSV of the numbers
};

/// A direction at angle t (degrees, signed) from the normal in the plane of azimuth phi (degrees):
/// positive t lies on the phi side, negative t on the opposite side.
Vec3 in_plane(double t_deg, double phi_deg) {
    const double t = t_deg * kRad, p = phi_deg * kRad;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct LobeCurve {
    std::string model;
    double theta_i = 0.0;
    std::vector<double> theta_o, f, f_cos;  // signed outgoing angle (+: the mirror side)
    double delta_weight = -1.0;             // a delta lobe: its reflectance (else -1)
};

int run_lobe(const LobeOptions& o, const GlobalOptions& g) {
    if (o.models.empty()) throw Error("give --model SPEC (repeatable)");
    if (o.output.empty() && o.data.empty()) throw Error("give -o FILE.png|.svg and/or --data FILE.csv");
    check_plot_output(o.output, "-o");
    if (!o.data.empty()) check_text_output(o.data);
    if (o.resolution < 3 || o.resolution > 100000) throw Error("--resolution must be 3 to 100000");
    if (!std::isfinite(o.phi_i)) throw Error("--phi-i must be a finite angle");
    const std::vector<double> thetas = parse_number_list(o.theta_i, "--theta-i");
    for (double t : thetas)
        if (!(t >= 0.0 && t < 90.0)) throw Error("--theta-i: " + format_number(t) + " must lie in [0, 90) degrees");
    const FresnelConfig fresnel = resolve_fresnel(o.fresnel, o.wavelength_nm);
    std::vector<ModelConfig> models;
    for (const auto& spec : o.models) {
        models.push_back(resolve_model(spec));
        if (fresnel.kind != 0 && !models.back().uses_fresnel)
            throw Error("model '" + models.back().name + "' has no Fresnel term; drop --fresnel");
    }
    const Precision precision = o.precision == "double" ? Precision::Double : Precision::Float;

    // The incident direction lies at azimuth phi_i + 180 degrees, so that its mirror direction is
    // at +theta_i in the plane of azimuth phi_i.
    Engine engine(g.device, g.verbose);
    std::vector<LobeCurve> curves;
    for (const ModelConfig& model : models)
        for (double ti : thetas) {
            LobeCurve c;
            c.model = model.canonical;
            c.theta_i = ti;
            const Vec3 wi = in_plane(-ti, o.phi_i);
            double analytic = 0.0;
            if (analytic_albedo(model, fresnel, std::cos(ti * kRad), analytic)) {
                c.delta_weight = analytic;  // the whole lobe leaves along the mirror direction
            } else {
                std::vector<Vec3> wo, wis;
                for (int k = 0; k < o.resolution; ++k) {
                    const double t = -90.0 + 180.0 * k / (o.resolution - 1);
                    c.theta_o.push_back(t);
                    wo.push_back(in_plane(std::fabs(t) >= 90.0 ? std::copysign(89.999, t) : t, o.phi_i));
                    wis.push_back(wi);
                }
                // f(wo, wi) in brdfbake's convention: light arriving from wi leaves towards wo.
                c.f = evaluate_on_device(engine, model, fresnel, precision, wo, wis);
                for (double f : c.f)
                    if (!std::isfinite(f))
                        throw Error("the model produced NaN or Inf in the plane of incidence; run `brdfbake check`");
                for (double f : c.f) c.f_cos.push_back(f * std::cos(ti * kRad));
            }
            curves.push_back(std::move(c));
        }

    if (!o.data.empty()) {
        std::ostringstream csv;
        csv << "# lobe: f(wi, wo) cos(theta_i) in the plane of incidence at phi = " << format_number(o.phi_i)
            << " deg; theta_o > 0 on the mirror side; a delta lobe is one row at theta_o = theta_i with no f (a "
               "delta function) and its reflectance as f_cos_theta_i\n";
        csv << "# fresnel: " << fresnel.canonical << "\nmodel,theta_i_deg,theta_o_deg,f,f_cos_theta_i\n";
        char line[128];
        for (const LobeCurve& c : curves) {
            if (c.delta_weight >= 0.0) {
                std::snprintf(line, sizeof line, ",%.17g,%.17g,,%.17g\n", c.theta_i, c.theta_i, c.delta_weight);
                csv << '"' << c.model << '"' << line;
                continue;
            }
            for (size_t k = 0; k < c.theta_o.size(); ++k) {
                std::snprintf(line, sizeof line, ",%.17g,%.17g,%.17g,%.17g\n", c.theta_i, c.theta_o[k], c.f[k], c.f_cos[k]);
                csv << '"' << c.model << '"' << line;
            }
        }
        emit(o.data, csv.str());
    }
    if (!o.output.empty()) {
        PlotSpec p;
        p.title = "lobe f(\\omega_i, \\omega_o) cos\\theta_i in the plane of incidence" +
                  std::string(o.log_scale ? " (radius: log_{10}, 6 decades)" : "");
        p.x.label = "";
        p.y.label = "";
        double radius = 0.0;
        for (const LobeCurve& c : curves)
            for (double v : c.f_cos) radius = std::max(radius, v);
        for (const LobeCurve& c : curves) radius = std::max(radius, c.delta_weight);
        if (!(radius > 0.0)) throw Error("every lobe is zero in this plane; nothing to draw");
        const double floor = radius * 1e-6;
        auto r_of = [&](double v) { return o.log_scale ? std::max(0.0, std::log10(std::max(v, floor) / floor)) : v; };
        const double r_max = r_of(radius);
        for (const LobeCurve& c : curves) {
            Curve curve;
            char angle[32];
            std::snprintf(angle, sizeof angle, "%g", c.theta_i);
            curve.label = c.model + ", \\theta_i = " + angle + "\\deg";
            if (c.delta_weight >= 0.0) {  // an arrow from the origin along the mirror direction
                const double r = r_of(c.delta_weight), t = c.theta_i * kRad;
                curve.x = {0.0, r * std::sin(t)};
                curve.y = {0.0, r * std::cos(t)};
                curve.label += " (delta, R = " + format_number(std::round(c.delta_weight * 1e4) / 1e4) + ")";
            } else {
                for (size_t k = 0; k < c.theta_o.size(); ++k) {
                    const double r = r_of(c.f_cos[k]), t = c.theta_o[k] * kRad;
                    curve.x.push_back(r * std::sin(t));
                    curve.y.push_back(r * std::cos(t));
                }
            }
            p.curves.push_back(curve);
        }
        for (double ti : thetas) {  // the incident directions, thin and dotted: where light comes from
            Curve in;
            in.x = {-r_max * std::sin(ti * kRad), 0.0};
            in.y = {r_max * std::cos(ti * kRad), 0.0};
            in.style = "k:1";
            p.curves.push_back(in);
        }
        p.x.lo = -1.05 * r_max;
        p.x.hi = 1.05 * r_max;
        p.y.lo = 0.0;
        p.y.hi = 1.05 * r_max;
        p.legend = LegendPlace::TopLeft;
        write_plot(o.output, p, 1000, 600);
        std::fprintf(stderr, "brdfbake: wrote %s\n", o.output.c_str());
    }
    return kExitOk;
}

}  // namespace

void add_lobe_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<LobeOptions>(
        app, "lobe", "the lobe f(wi, wo) cos(theta_i) in the plane of incidence, as a polar plot and CSV", global,
        action, run_lobe);
    cmd->add_option("--model", o->models, "model spec (repeatable: lobes overlay)")->required();
    cmd->add_option("--theta-i", o->theta_i, "incident angles in degrees, comma-separated")->capture_default_str();
    cmd->add_option("--phi-i", o->phi_i, "azimuth of the plane of incidence in degrees (anisotropic models)")
        ->capture_default_str();
    cmd->add_option("--fresnel", o->fresnel, kFresnelSpecHelp)->capture_default_str();
    cmd->add_option("--wavelength", o->wavelength_nm, "wavelength in nm for measured metals");
    cmd->add_option("--resolution", o->resolution, "outgoing angles over [-90, 90] degrees")->capture_default_str();
    cmd->add_flag("--log", o->log_scale, "radius on a log scale (six decades below the peak)");
    add_precision_option(cmd, o->precision, "evaluation arithmetic");
    cmd->add_option("-o,--output", o->output, "the picture: .png or .svg");
    cmd->add_option("--data", o->data, "the numbers behind it as CSV (- for standard output)");
}

}  // namespace brdfbake

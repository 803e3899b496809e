// `brdfbake lobe`: the lobe of a BRDF for a given incident direction, in its plane of incidence:
// the radiance reflected towards wo per unit irradiance from wi, f(wi, wo) cos(theta_i), drawn
// as a polar curve over the outgoing angle (Disney's BRDF Explorer draws the same picture).
// Several models and incident angles overlay; delta lobes are drawn as an arrow along the
// mirror direction whose length is their reflectance. The numbers behind the picture go to
// --data as CSV, computed by the same eval kernel every other command uses.
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "brdfbake/analytic.h"
#include "brdfbake/error.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "integrate/random_walk.h"
#include "integrate/sheen_volume.h"
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
    std::string view = "plane";  // plane: the polar plot in the plane of incidence; 3d: the lobe in 3D
    std::int64_t walks = 1 << 14;  // a simulated model (scattering=multiple): walks per direction pair
    bool transmission = false;     // a dielectric walk's transmitted f_t too (theta_o 90 to 270 degrees)
};

/// f(wo[k], wis[k]) of a model: the eval kernel, or for a simulated model (scattering=multiple) the
/// walks' next-event estimate (integrate/random_walk.h), its error estimate in *error.
std::vector<double> lobe_values(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                Precision precision, const std::vector<Vec3>& wo, const std::vector<Vec3>& wis,
                                std::int64_t walks, std::vector<double>* error) {
    if (!model.simulated) return evaluate_on_device(engine, model, fresnel, precision, wo, wis);
    if (model.traits().layer_walk)  // a histogram of exits, at least 2^20 walks per incident direction
        return sheen_layer_lobe(engine, model, precision, wo, wis, std::max<std::uint64_t>(walks, 1u << 20), error);
    WalkEvalRequest req;
    req.model = model.id;
    req.fresnel = fresnel;
    req.samples = std::uint64_t(walks);
    req.precision = precision;
    for (size_t k = 0; k < wo.size(); ++k) req.pairs.push_back({wis[k], wo[k], model.params});  // walks from wi
    const WalkEvalResult r = walk_eval(engine, req);
    std::vector<double> f;
    for (const AlbedoValue& v : r.f) {
        f.push_back(v.value);
        if (error) error->push_back(v.error);
    }
    return f;
}

/// A direction at angle t (degrees, signed) from the normal in the plane of azimuth phi (degrees):
/// positive t lies on the phi side, negative t on the opposite side.
Vec3 in_plane(double t_deg, double phi_deg) {
    const double t = t_deg * kRad, p = phi_deg * kRad;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct LobeCurve {
    std::string model;  // its canonical spec (the CSV's column)
    std::string label;  // the spec as the user gave it (the picture's legend: the canonical one, with
                        // every default spelled out, overflowed the panel for a walk)
    double theta_i = 0.0;
    std::vector<double> theta_o, f, f_cos;  // signed outgoing angle (+: the mirror side; > 90: below)
    std::vector<double> f_error;            // a simulated model's error estimate of f (else empty)
    double delta_weight = -1.0;             // a delta lobe: its reflectance (else -1)
};

/// A fixed oblique view of 3D points: the camera looks at the origin from azimuth -60 degrees and
/// elevation 25 degrees, z (the normal) up on the page; orthographic projection.
struct View {
    double x, y;
};
View project(double px, double py, double pz) {
    const double az = -60.0 * kRad, el = 25.0 * kRad;
    return {-px * std::sin(az) + py * std::cos(az),
            -px * std::sin(el) * std::cos(az) - py * std::sin(el) * std::sin(az) + pz * std::cos(el)};
}

/// A polyline of 3D points as a projected curve.
Curve projected(const std::vector<std::array<double, 3>>& points, const std::string& style) {
    Curve c;
    c.style = style;
    for (const auto& p : points) {
        const View v = project(p[0], p[1], p[2]);
        c.x.push_back(v.x);
        c.y.push_back(v.y);
    }
    return c;
}

/// The lobe in 3D, one panel per model and incident angle: the surface r(wo) = f(wi, wo) cos(theta_i)
/// over the upper hemisphere, normalised to its peak (or over six decades with --log), drawn as a
/// wireframe of rings of constant theta_o (blue) and meridians of constant phi_o (grey) in a fixed
/// oblique view; the base circle, the normal, the incident direction (dotted) and a delta lobe as
/// an arrow as long as its reflectance.
void write_lobe_3d(Engine& engine, const LobeOptions& o, const std::vector<ModelConfig>& models,
                   const FresnelConfig& fresnel, Precision precision, const std::vector<double>& thetas) {
    constexpr int n_theta = 46, n_phi = 73;  // 2 degrees in theta_o (to 89.9), 5 degrees in phi_o
    auto direction = [](double t_deg, double p_deg) {
        const double t = std::min(t_deg, 89.9) * kRad, p = p_deg * kRad;
        return std::array<double, 3>{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
    };
    Figure fig;
    for (const ModelConfig& model : models)
        for (double ti : thetas) {
            const Vec3 wi = in_plane(-ti, o.phi_i);
            PlotSpec p;
            p.axes = false;
            p.x.lo = p.y.lo = -1.15;
            p.x.hi = p.y.hi = 1.15;
            // The spec on lines of its own, broken after its commas: a long one (an anisotropic GGX)
            // would run into the next panel.
            p.title = plot_text(wrap_at_commas(model.canonical, 30)) + "\n\\theta_i = " + format_number(ti) + "\\deg";
            std::vector<std::array<double, 3>> base;
            for (int j = 0; j <= 72; ++j) base.push_back(direction(90.0, 5.0 * j));
            p.curves.push_back(projected(base, "h:1"));
            p.curves.push_back(projected({{0, 0, 0}, {0, 0, 1}}, "k-1"));  // the normal
            double analytic = 0.0;
            if (analytic_albedo(model, fresnel, std::cos(ti * kRad), analytic)) {
                const Vec3 m = in_plane(ti, o.phi_i);
                p.curves.push_back(projected({{0, 0, 0}, {analytic * m[0], analytic * m[1], analytic * m[2]}}, "r-4A"));
                p.title += ", delta, R = " + format_number(std::round(analytic * 1e4) / 1e4);
            } else {
                std::vector<Vec3> wo, wis;
                for (int j = 0; j < n_phi; ++j)
                    for (int i = 0; i < n_theta; ++i) {
                        const auto d = direction(2.0 * i, 5.0 * j);
                        wo.push_back({d[0], d[1], d[2]});
                        wis.push_back(wi);
                    }
                const std::vector<double> f = lobe_values(engine, model, fresnel, precision, wo, wis, o.walks, nullptr);
                double peak = 0.0;
                for (double v : f) {
                    if (!std::isfinite(v)) throw Error("the model produced NaN or Inf; run `brdfbake check`");
                    peak = std::max(peak, v * std::cos(ti * kRad));
                }
                if (!(peak > 0.0)) throw Error("the lobe of '" + model.canonical + "' is zero everywhere; nothing to draw");
                const double floor = peak * 1e-6;
                auto point = [&](int i, int j) {
                    const size_t k = size_t(j) * n_theta + size_t(i);
                    const double v = f[k] * std::cos(ti * kRad);
                    const double r = o.log_scale ? std::log10(std::max(v, floor) / floor) / 6.0 : v / peak;
                    return std::array<double, 3>{r * wo[k][0], r * wo[k][1], r * wo[k][2]};
                };
                for (int i = 5; i < n_theta; i += 5) {  // rings every 10 degrees of theta_o
                    std::vector<std::array<double, 3>> ring;
                    for (int j = 0; j < n_phi; ++j) ring.push_back(point(i, j));
                    p.curves.push_back(projected(ring, "b-1"));
                }
                for (int j = 0; j < n_phi - 1; j += 3) {  // meridians every 15 degrees of phi_o
                    std::vector<std::array<double, 3>> meridian;
                    for (int i = 0; i < n_theta; ++i) meridian.push_back(point(i, j));
                    p.curves.push_back(projected(meridian, "h-1"));
                }
                char peak_text[40];
                std::snprintf(peak_text, sizeof peak_text, ", peak %.3g", peak);
                p.title += peak_text;
            }
            p.curves.push_back(projected({{0, 0, 0}, {wi[0], wi[1], wi[2]}}, "k:2"));  // where light comes from
            fig.panels.push_back(p);
        }
    fig.columns = std::min<int>(int(fig.panels.size()), 3);
    fig.panel_width = 700;
    fig.panel_height = 700;
    fig.caption = std::string(o.log_scale ? "radius: log f cos\\theta_i, six decades" : "radius: f cos\\theta_i / peak") +
                  "; blue: constant \\theta_o (10\\deg apart), grey: constant \\phi_o (15\\deg); dotted: incident "
                  "direction; red: a delta lobe, length R";
    write_figure(o.output, fig);
}

/// The plane of incidence as CSV: one row per theta_o (a delta lobe: one row at theta_i), with f's
/// error column when a walk drew any of the curves.
void write_lobe_csv(const std::string& path, const std::vector<LobeCurve>& curves, const FresnelConfig& fresnel,
                    double phi_i) {
    bool below = false;  // --transmission's rows
    for (const LobeCurve& c : curves)
        for (double t : c.theta_o) below = below || t > 90.0;
    std::ostringstream csv;
    csv << "# lobe: f(wi, wo) cos(theta_i) in the plane of incidence at phi = " << format_number(phi_i)
        << " deg; theta_o > 0 on the mirror side" << (below ? ", 90 to 270 below the surface (f_t)" : "") << "; a delta lobe is one row at theta_o = theta_i with no f (a "
           "delta function) and its reflectance as f_cos_theta_i\n";
    bool simulated = false;  // a walk's estimate: one more column, f's error (3 standard errors)
    for (const LobeCurve& c : curves) simulated = simulated || !c.f_error.empty();
    csv << "# fresnel: " << fresnel.canonical << "\nmodel,theta_i_deg,theta_o_deg,f,f_cos_theta_i"
        << (simulated ? ",f_error\n" : "\n");
    char line[160];
    for (const LobeCurve& c : curves) {
        if (c.delta_weight >= 0.0) {
            std::snprintf(line, sizeof line, ",%.17g,%.17g,,%.17g\n", c.theta_i, c.theta_i, c.delta_weight);
            csv << '"' << c.model << '"' << line;
            continue;
        }
        for (size_t k = 0; k < c.theta_o.size(); ++k) {
            std::snprintf(line, sizeof line, ",%.17g,%.17g,%.17g,%.17g", c.theta_i, c.theta_o[k], c.f[k], c.f_cos[k]);
            csv << '"' << c.model << '"' << line;
            if (simulated) csv << (c.f_error.empty() ? std::string(",") : "," + format_number(c.f_error[k]));
            csv << "\n";
        }
    }
    emit(path, csv.str());
}

int run_lobe(const LobeOptions& o, const GlobalOptions& g) {
    if (o.models.empty()) throw Error("give --model SPEC (repeatable)");
    if (o.output.empty() && o.data.empty()) throw Error("give -o FILE.png|.svg and/or --data FILE.csv");
    check_plot_output(o.output, "-o");
    if (!o.data.empty()) check_text_output(o.data);
    if (o.resolution < 3 || o.resolution > 100000) throw Error("--resolution must be 3 to 100000");
    if (!std::isfinite(o.phi_i)) throw Error("--phi-i must be a finite angle");
    if (o.walks < 32 || o.walks > (std::int64_t(1) << 36)) throw Error("--walks must be 32 to 2^36");
    const std::vector<double> thetas = parse_number_list(o.theta_i, "--theta-i");
    for (double t : thetas)
        if (!(t >= 0.0 && t < 90.0)) throw Error("--theta-i: " + format_number(t) + " must lie in [0, 90) degrees");
    const FresnelConfig fresnel = resolve_fresnel(o.fresnel, o.wavelength_nm);
    std::vector<ModelConfig> models;
    for (const auto& spec : o.models) {
        models.push_back(resolve_model_simulated(spec));
        if (o.transmission && !models.back().dielectric_walk)
            throw Error("--transmission: model '" + spec + "' transmits nothing here (it takes a dielectric walk, "
                        "scattering=multiple,eta=N)");
        if (fresnel.kind != 0 && !models.back().uses_fresnel)
            throw Error("model '" + models.back().name + "' has no Fresnel term; drop --fresnel");
    }
    const Precision precision = o.precision == "double" ? Precision::Double : Precision::Float;

    // The incident direction lies at azimuth phi_i + 180 degrees, so that its mirror direction is
    // at +theta_i in the plane of azimuth phi_i.
    if (o.view != "plane" && o.view != "3d") throw Error("--view must be plane or 3d");
    if (o.view == "3d" && o.transmission) throw Error("--transmission draws the plane of incidence (--view plane)");
    if (o.view == "3d" && (o.output.empty() || !o.data.empty()))
        throw Error("--view 3d draws a picture (-o FILE.png or FILE.svg); --data writes the plane of incidence, without it");
    Engine engine(g.device, g.verbose);
    if (o.view == "3d") {
        write_lobe_3d(engine, o, models, fresnel, precision, thetas);
        std::fprintf(stderr, "brdfbake: wrote %s\n", o.output.c_str());
        return kExitOk;
    }
    std::vector<LobeCurve> curves;
    for (size_t m = 0; m < models.size(); ++m)
        for (double ti : thetas) {
            const ModelConfig& model = models[m];
            LobeCurve c;
            c.model = model.canonical;
            c.label = o.models[m];
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
                // the transmitted f_t below the surface: theta_o = 180 - s, s the angle from -z (walk9),
                // labelled where evaluated (90.001 and 269.999 at the horizon: no row twice at 90)
                for (int k = 0; o.transmission && k < o.resolution; ++k) {
                    const double s = 90.0 - 180.0 * k / (o.resolution - 1);
                    c.theta_o.push_back(std::fabs(s) >= 90.0 ? (s > 0.0 ? 90.001 : 269.999) : 180.0 - s);
                    wo.push_back(in_plane(c.theta_o.back(), o.phi_i));
                    wis.push_back(wi);
                }
                // f(wo, wi) in brdfbake's convention: light arriving from wi leaves towards wo.
                c.f = lobe_values(engine, model, fresnel, precision, wo, wis, o.walks, &c.f_error);
                for (double f : c.f)
                    if (!std::isfinite(f))
                        throw Error("the model produced NaN or Inf in the plane of incidence; run `brdfbake check`");
                for (double f : c.f) c.f_cos.push_back(f * std::cos(ti * kRad));
            }
            curves.push_back(std::move(c));
        }

    if (!o.data.empty()) write_lobe_csv(o.data, curves, fresnel, o.phi_i);
    if (!o.output.empty()) {
        PlotSpec p;
        p.title = "lobe f(\\omega_i, \\omega_o) cos\\theta_i in the plane of incidence" +
                  std::string(o.log_scale ? " (radius: log_{10}, 6 decades)" : "");
        // Axes in the units of the radius: a point at angle theta_o from the normal lies at
        // r (sin theta_o, cos theta_o), r = f cos theta_i in sr^-1 (log_10 of it over six decades with --log).
        const std::string unit = o.log_scale ? "log_{10}(f cos\\theta_i / floor), decades" : "f cos\\theta_i  (sr^{-1})";
        p.x.label = unit + " \\times{} sin\\theta_o;  grey rays: \\theta_o every 30\\degree";
        p.y.label = unit + " \\times{} cos\\theta_o";
        double radius = 0.0;
        for (const LobeCurve& c : curves)
            for (double v : c.f_cos) radius = std::max(radius, v);
        for (const LobeCurve& c : curves) radius = std::max(radius, c.delta_weight);
        if (!(radius > 0.0)) throw Error("every lobe is zero in this plane; nothing to draw");
        const double floor = radius * 1e-6;
        auto r_of = [&](double v) { return o.log_scale ? std::max(0.0, std::log10(std::max(v, floor) / floor)) : v; };
        const double r_max = r_of(radius);
        double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;  // the lobes' extent: the ranges fit the data
        for (const LobeCurve& c : curves) {
            Curve curve;
            char angle[32];
            std::snprintf(angle, sizeof angle, "%g", c.theta_i);
            curve.label = c.label + ", \\theta_i = " + angle + "\\deg";
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
            for (size_t k = 0; k < curve.x.size(); ++k) {
                x_lo = std::min(x_lo, curve.x[k]);
                x_hi = std::max(x_hi, curve.x[k]);
                y_lo = std::min(y_lo, curve.y[k]);
                y_hi = std::max(y_hi, curve.y[k]);
            }
            p.curves.push_back(curve);
        }
        // The box: the lobes plus room for the legend above them (its rows take about 6% of the
        // height each); at least 30% of the lobes' width on the side they leave empty (the
        // incident direction's side, usually).
        const double left = 1.05 * std::max({-x_lo, 0.3 * x_hi, 1e-3 * r_max});
        const double right = 1.05 * std::max({x_hi, 0.3 * -x_lo, 1e-3 * r_max});
        const double legend_rows = double(curves.size());
        const double top = std::max({y_hi, 1e-3 * r_max, 0.3 * -y_lo}) * (1.1 + 0.08 * legend_rows + 0.08);
        auto ray = [&](double t_deg, const std::string& style) {  // from the origin to the box's edge
            const double t = t_deg * kRad, s = std::sin(t), c = std::cos(t);
            double len = top / std::max(c, 1e-9);
            if (std::fabs(s) > 1e-9) len = std::min(len, (s < 0 ? left : right) / std::fabs(s));
            Curve in;
            in.x = {0.0, len * s};
            in.y = {0.0, len * c};
            in.style = style;
            return in;
        };
        for (int t = -60; t <= 60; t += 30) p.curves.push_back(ray(t, "h:1"));  // the angle's guide rays
        for (double ti : thetas) p.curves.push_back(ray(-ti, "k:1"));  // where light comes from
        p.x.lo = -left;
        p.x.hi = right;
        p.y.lo = 1.05 * y_lo;  // below 0 only with --transmission
        p.y.hi = top;
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
    cmd->add_option("--fresnel", o->fresnel, fresnel_spec_help())->capture_default_str();
    cmd->add_option("--wavelength", o->wavelength_nm, "wavelength in nm for measured metals");
    cmd->add_option("--resolution", o->resolution, "outgoing angles over [-90, 90] degrees")->capture_default_str();
    cmd->add_flag("--log", o->log_scale, "radius on a log scale (six decades below the peak)");
    cmd->add_option("--view", o->view, "plane: polar plot in the plane of incidence; 3d: the lobe over the hemisphere")
        ->capture_default_str();
    add_precision_option(cmd, o->precision, "evaluation arithmetic");
    cmd->add_option("--walks", o->walks, "simulated models: walks per direction pair (scattering=multiple); per incident direction, "
                    "at least 2^20, for sheen-volume's histogram of exits")
        ->capture_default_str();
    cmd->add_flag("--transmission", o->transmission,
                  "a dielectric walk (scattering=multiple,eta=N): the transmitted f_t below the surface too");
    cmd->add_option("-o,--output", o->output, "the picture: .png or .svg");
    cmd->add_option("--data", o->data, "the numbers behind it as CSV (- for standard output)");
}

}  // namespace brdfbake

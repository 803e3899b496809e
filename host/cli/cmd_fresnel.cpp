// `brdfbake fresnel`: Fresnel reflectance F, Rs and Rp over incidence angles (computed in the
// fresnel_curve kernel), the hemispherical average 2 int F mu dmu, the deviation of the
// approximate forms from the exact one, and plots; `--compare` draws the classic figure.
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_curve.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "cli/fresnel_pictures.h"
#include "fit/f82_tint.h"
#include "models/key_reader.h"
#include "models/spectrum.h"
#include "plot/plot.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace {

struct FresnelOptions {
    std::vector<std::string> fresnels;  // --fresnel, several only for --rgb
    std::string fresnel;                // the first
    std::string swatch;
    std::string thickness_range;
    std::optional<double> thickness_step;  // nm between the iridescence map's rows (none: 121 rows)
    std::string theta = "0,10,20,30,40,50,60,70,75,80,85,89,89.9,90";
    double wavelength_nm = 0.0;
    std::string precision = "float";
    std::string format = "table";
    std::string output;
    std::string plot;
    bool compare = false;
    bool rgb = false;
    std::string colour_space = "srgb";
    std::string fit;
};

constexpr double kDeg = M_PI / 180.0;

/// cos(theta) for theta in degrees, as sin(90 deg - theta): exactly 0 at 90 deg and accurate to
/// the last bit near grazing, where cos(theta * pi/180) would carry the rounding of the angle.
double cos_deg(double theta_deg) { return std::sin((90.0 - theta_deg) * kDeg); }

bb_params to_params(const ParamBlock& p) {
    bb_params b;
    for (int i = 0; i < BB_MAX_PARAMS; ++i) b.v[i] = p[size_t(i)];
    return b;
}

/// F, Rs, Rp of a Fresnel term on the host, in double, from the shared header.
struct HostFresnel {
    int kind;
    bb_params p;
    explicit HostFresnel(const FresnelConfig& f) : kind(f.kind), p(to_params(f.params)) {}
    HostFresnel(int k, double eta, double ext) : kind(k), p{} {
        p.v[BB_FRESNEL_ETA] = eta;
        p.v[BB_FRESNEL_K] = ext;
    }
    double f(double mu) const { return bb_fresnel_eval(kind, p, mu); }
    double rs(double mu) const { return bb_fresnel_eval_rs(kind, p, mu); }
    double rp(double mu) const { return bb_fresnel_eval_rp(kind, p, mu); }
};

HostFresnel schlick(double f0) {
    HostFresnel h(BB_FRESNEL_SCHLICK, 0.0, 0.0);
    h.p.v[BB_SCHLICK_F0] = f0;
    return h;
}

// ------------------------------------------------------------ hemispherical average

/// The result of an adaptive quadrature and its error estimate.
struct Quadrature {
    double value = 0.0;
    double error = 0.0;
};

/// 2 int_0^1 F(mu) mu dmu. Where total internal reflection can occur (a relative index below 1
/// without absorption), F = 1 for mu < mu_c = sqrt(1 - eta^2) contributes mu_c^2 exactly, and
/// above mu_c, F - 1 ~ sqrt(mu - mu_c): the substitution mu = mu_c + (1 - mu_c) t^2 makes the
/// integrand smooth in t, so the quadrature converges as for an analytic function.
Quadrature hemispherical_average(const HostFresnel& h) {
    const double eta = h.p.v[BB_FRESNEL_ETA], k = h.p.v[BB_FRESNEL_K];
    const bool tir = (h.kind == BB_FRESNEL_DIELECTRIC && eta < 1.0) ||
                     (h.kind == BB_FRESNEL_CONDUCTOR && k == 0.0 && eta < 1.0);
    const double mu_c = tir ? std::sqrt((1.0 - eta) * (1.0 + eta)) : 0.0;
    // Boost.Math's adaptive Gauss-Kronrod 7-15 (QUADPACK's qk15 pair): an interval is bisected
    // while its |K15 - G7| exceeds both 1e-13 of its own integral and its share (halved at each
    // bisection) of 1e-13 of the whole; the error is the sum of the intervals' estimates. A
    // tighter tolerance is below the rounding of F near the critical angle: at 1e-14,
    // dielectric:eta=0.6667 bisects to the last level (123,015 evaluations instead of 135).
    Quadrature q;
    const double relative_tolerance = 1e-13;
    const unsigned max_bisections = 15;
    q.value = boost::math::quadrature::gauss_kronrod<double, 15>::integrate(
        [&](double t) {
            const double mu = mu_c + (1.0 - mu_c) * t * t;
            return 2.0 * h.f(mu) * mu * 2.0 * (1.0 - mu_c) * t;
        },
        0.0, 1.0, max_bisections, relative_tolerance, &q.error);
    q.value += mu_c * mu_c;
    // Rounding: each of the ~15 evaluations per interval is good to a few ulps of the result.
    q.error += 16.0 * 2.220446049250313e-16 * std::fabs(q.value);
    return q;
}

// ------------------------------------------------------------ deviation of approximations

struct Deviation {
    double max_abs = 0.0;
    double theta_deg = 0.0;
};

/// max over theta in [0, 90] of |a(theta) - b(theta)|: a 0.01 degree scan, then a golden-section
/// refinement around the largest grid value (the differences are smooth in theta).
template <class A, class B>
Deviation max_deviation(const A& a, const B& b) {
    auto d = [&](double t) { return std::fabs(a(cos_deg(t)) - b(cos_deg(t))); };
    const int n = 9000;
    int best = 0;
    double best_v = -1.0;
    for (int i = 0; i <= n; ++i) {
        const double v = d(90.0 * i / n);
        if (v > best_v) best_v = v, best = i;
    }
    double lo = 90.0 * std::max(best - 1, 0) / n, hi = 90.0 * std::min(best + 1, n) / n;
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 60; ++it) {
        const double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
        if (d(x1) > d(x2)) hi = x2; else lo = x1;
    }
    Deviation out{best_v, 90.0 * best / n};
    const double mid = 0.5 * (lo + hi);
    if (d(mid) > out.max_abs) out = {d(mid), mid};
    return out;
}

/// The exact form that an approximate or measured term approximates, if any.
bool exact_reference(const FresnelConfig& f, HostFresnel& exact) {
    const double eta = f.params[BB_FRESNEL_ETA], k = f.params[BB_FRESNEL_K];
    if (f.kind == BB_FRESNEL_CONDUCTOR || f.kind == BB_FRESNEL_CONDUCTOR_APPROX) {
        exact = HostFresnel(BB_FRESNEL_CONDUCTOR, eta, k);
        return true;
    }
    if (f.kind == BB_FRESNEL_DIELECTRIC) {
        exact = HostFresnel(BB_FRESNEL_DIELECTRIC, eta, 0.0);
        return true;
    }
    return false;
}

struct Comparison {
    bool present = false;
    bool conductor = false;
    double f0 = 0.0;
    Deviation approx, schlick;
    Quadrature exact_avg, approx_avg, schlick_avg;
};

Comparison compare_forms(const FresnelConfig& f) {
    Comparison c;
    HostFresnel exact(BB_FRESNEL_NONE, 0.0, 0.0);
    if (!exact_reference(f, exact)) return c;
    c.present = true;
    c.conductor = exact.kind == BB_FRESNEL_CONDUCTOR;
    const HostFresnel approx(BB_FRESNEL_CONDUCTOR_APPROX, exact.p.v[BB_FRESNEL_ETA], exact.p.v[BB_FRESNEL_K]);
    c.f0 = exact.f(1.0);
    const HostFresnel sch = schlick(c.f0);
    auto fe = [&](double mu) { return exact.f(mu); };
    c.approx = max_deviation([&](double mu) { return approx.f(mu); }, fe);
    c.schlick = max_deviation([&](double mu) { return sch.f(mu); }, fe);
    c.exact_avg = hemispherical_average(exact);
    c.approx_avg = hemispherical_average(approx);
    c.schlick_avg = hemispherical_average(sch);
    return c;
}


// ------------------------------------------------------------ plots

std::vector<double> plot_thetas() {
    std::vector<double> t;
    for (int i = 0; i <= 900; ++i) t.push_back(0.1 * i);
    return t;
}

Curve host_curve(const std::string& label, const std::string& style, const std::vector<double>& thetas,
                 const std::function<double(double)>& fn) {
    Curve c;
    c.label = label;
    c.style = style;
    c.x = thetas;
    for (double t : thetas) c.y.push_back(fn(cos_deg(t)));
    return c;
}

/// F, R_s and R_p of one term as three curves labelled PREFIX + "F", "R_s", "R_p".
void add_components(PlotSpec& p, const std::string& prefix, const HostFresnel& h, const std::vector<double>& thetas,
                    const char* f_style, const char* rs_style, const char* rp_style) {
    p.curves.push_back(host_curve(prefix + "F", f_style, thetas, [&](double mu) { return h.f(mu); }));
    p.curves.push_back(host_curve(prefix + "R_s", rs_style, thetas, [&](double mu) { return h.rs(mu); }));
    p.curves.push_back(host_curve(prefix + "R_p", rp_style, thetas, [&](double mu) { return h.rp(mu); }));
}

PlotAxis theta_axis() { return PlotAxis{"angle of incidence \\theta  (degrees)", 0.0, 90.0, 15.0}; }
PlotAxis reflectance_axis() { return PlotAxis{"reflectance", 0.0, 1.0, 0.2}; }

/// The panel for one Fresnel term: F, Rs, Rp and, where an exact form exists, the approximate
/// conductor formula and Schlick with F0 = F(0).
PlotSpec single_panel(const FresnelConfig& f) {
    const auto th = plot_thetas();
    PlotSpec p;
    p.title = plot_text(short_numbers(f.canonical));  // the title reads 1.33, the CSV keeps every digit
    p.x = theta_axis();
    p.y = reflectance_axis();
    const HostFresnel h(f);
    if (f.kind != BB_FRESNEL_NONE && f.kind != BB_FRESNEL_SCHLICK)
        add_components(p, "", h, th, "b-4", "r;2", "g;2");
    else
        p.curves.push_back(host_curve("F", "b-4", th, [&](double mu) { return h.f(mu); }));
    HostFresnel exact(BB_FRESNEL_NONE, 0.0, 0.0);
    if (exact_reference(f, exact)) {
        if (f.kind != BB_FRESNEL_CONDUCTOR)
            p.curves.push_back(host_curve("exact", "k-2", th, [&](double mu) { return exact.f(mu); }));
        if (f.kind != BB_FRESNEL_CONDUCTOR_APPROX && exact.kind == BB_FRESNEL_CONDUCTOR) {
            const HostFresnel approx(BB_FRESNEL_CONDUCTOR_APPROX, exact.p.v[BB_FRESNEL_ETA], exact.p.v[BB_FRESNEL_K]);
            p.curves.push_back(host_curve("approximate conductor", "m|2", th, [&](double mu) { return approx.f(mu); }));
        }
        const HostFresnel sch = schlick(exact.f(1.0));
        p.curves.push_back(host_curve("Schlick, F_0 = F(0)", "q:3", th, [&](double mu) { return sch.f(mu); }));
    }
    p.legend = f.kind == BB_FRESNEL_DIELECTRIC && f.params[BB_FRESNEL_ETA] > 1.0 ? LegendPlace::TopLeft
                                                                               : LegendPlace::BottomLeft;
    return p;
}

/// "metal:Al at 550 nm: \eta = 1.0152 + 6.6273 i" for a measured metal, else the canonical spec.
std::string metal_title(const FresnelConfig& f) {
    char text[160];
    const std::string what = f.canonical.substr(0, f.canonical.find(" = "));
    std::snprintf(text, sizeof text, "%s:  n = %.4f + %.4f i", what.c_str(), f.params[BB_FRESNEL_ETA],
                  f.params[BB_FRESNEL_K]);
    return text;
}

/// The classic figure: a metal (exact, approximate, Schlick, with Rs and Rp) beside a dielectric
/// of eta = 1.5 seen from outside and from inside (Brewster and critical angles marked).
Figure comparison_figure(const FresnelConfig& metal) {
    const auto th = plot_thetas();
    Figure fig;
    fig.columns = 2;
    fig.panel_width = 900;
    fig.panel_height = 680;

    PlotSpec a;
    a.title = short_numbers(metal_title(metal));
    a.x = theta_axis();
    a.y = reflectance_axis();
    a.y.lo = std::numeric_limits<double>::quiet_NaN();  // metals: zoom on the upper range
    a.y.tick = 0.05;
    HostFresnel exact(BB_FRESNEL_NONE, 0.0, 0.0);
    exact_reference(metal, exact);
    const double eta = exact.p.v[BB_FRESNEL_ETA], k = exact.p.v[BB_FRESNEL_K];
    const HostFresnel approx(BB_FRESNEL_CONDUCTOR_APPROX, eta, k);
    const HostFresnel sch = schlick(exact.f(1.0));
    add_components(a, "exact ", exact, th, "b-4", "r;2", "g;2");
    a.curves.push_back(host_curve("approximate conductor F", "m|2", th, [&](double mu) { return approx.f(mu); }));
    a.curves.push_back(host_curve("Schlick F, F_0 = F(0)", "q:3", th, [&](double mu) { return sch.f(mu); }));
    a.legend = LegendPlace::BottomLeft;
    fig.panels.push_back(a);

    PlotSpec b;
    b.title = "glass \\eta  = 1.5: outside, and inside (\\eta  = 1/1.5)";
    b.x = theta_axis();
    b.y = reflectance_axis();
    const HostFresnel out(BB_FRESNEL_DIELECTRIC, 1.5, 0.0), in(BB_FRESNEL_DIELECTRIC, 1.0 / 1.5, 0.0);
    const HostFresnel sch_out = schlick(out.f(1.0));
    add_components(b, "outside ", out, th, "b-4", "r;2", "g;2");
    add_components(b, "inside ", in, th, "k-4", "r:2", "g:2");
    b.curves.push_back(host_curve("Schlick F_0 = 0.04", "q|2", th, [&](double mu) { return sch_out.f(mu); }));
    char text[64];
    std::snprintf(text, sizeof text, "Brewster %.1f\\degree", std::atan(1.5) / kDeg);
    b.lines.push_back({'x', std::atan(1.5) / kDeg, text});
    std::snprintf(text, sizeof text, "critical %.1f\\degree", std::asin(1.0 / 1.5) / kDeg);
    b.lines.push_back({'x', std::asin(1.0 / 1.5) / kDeg, text});
    b.legend = LegendPlace::TopLeft;
    fig.panels.push_back(b);
    return fig;
}

// ------------------------------------------------------------ output

const char kAverageMethod[] =
    "adaptive Gauss-Kronrod 7-15 in double on the host (error: sum of |K15 - G7| plus rounding); "
    "where total internal reflection occurs, F = 1 below the critical angle integrated exactly and "
    "mu = mu_c + (1 - mu_c) t^2 above it";

/// One line per angle: theta, cos(theta), F, Rs and Rp in the printf format `row`.
void write_rows(std::ostream& out, const char* row, const std::vector<double>& thetas,
                const std::vector<double>& cosines, const FresnelCurves& dev) {
    char line[200];
    for (size_t i = 0; i < thetas.size(); ++i) {
        std::snprintf(line, sizeof line, row, thetas[i], cosines[i], dev.f[i], dev.rs[i], dev.rp[i]);
        out << line;
    }
}

std::string render(const FresnelOptions& o, const FresnelConfig& f, Precision precision, const std::vector<double>& thetas,
                   const std::vector<double>& cosines, const FresnelCurves& dev, double host_diff, const Quadrature& avg,
                   const Comparison& cmp, const Engine& engine, double seconds) {
    const Format format = parse_format(o.format);
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "fresnel";
        j["fresnel"] = f.canonical;
        j["kind"] = fresnel_kind_name(f.kind);
        if (f.kind == BB_FRESNEL_DIELECTRIC || f.kind == BB_FRESNEL_CONDUCTOR || f.kind == BB_FRESNEL_CONDUCTOR_APPROX)
            j["eta"] = f.params[BB_FRESNEL_ETA];
        if (f.kind == BB_FRESNEL_CONDUCTOR || f.kind == BB_FRESNEL_CONDUCTOR_APPROX) j["k"] = f.params[BB_FRESNEL_K];
        if (f.kind == BB_FRESNEL_SCHLICK) j["f0"] = f.params[BB_SCHLICK_F0];
        if (o.wavelength_nm > 0.0) j["wavelength_nm"] = o.wavelength_nm;
        j["precision"] = precision_name(precision);
        j["device"] = engine.device().name;
        j["seconds"] = seconds;
        j["results"] = nlohmann::json::array();
        for (size_t i = 0; i < thetas.size(); ++i)
            j["results"].push_back({{"theta_deg", thetas[i]},
                                    {"cos_theta", cosines[i]},
                                    {"F", dev.f[i]},
                                    {"Rs", dev.rs[i]},
                                    {"Rp", dev.rp[i]}});
        j["device_vs_host_max_abs_diff"] = host_diff;
        j["hemispherical_average"] = {{"value", avg.value}, {"error", avg.error}, {"method", kAverageMethod}};
        if (cmp.present) {
            nlohmann::json d;
            d["reference"] = cmp.conductor ? "conductor (exact)" : "dielectric (exact)";
            d["scan"] = "0.01 degree grid over [0, 90], refined by golden-section search";
            d["conductor_approx"] = {{"max_abs", cmp.approx.max_abs},
                                     {"theta_deg", cmp.approx.theta_deg},
                                     {"hemispherical_average", cmp.approx_avg.value}};
            d["schlick"] = {{"f0", cmp.f0},
                            {"max_abs", cmp.schlick.max_abs},
                            {"theta_deg", cmp.schlick.theta_deg},
                            {"hemispherical_average", cmp.schlick_avg.value}};
            d["exact_hemispherical_average"] = cmp.exact_avg.value;
            j["deviations"] = d;
        }
        out << j.dump(2) << "\n";
    } else if (format == Format::Csv) {
        out << "theta_deg,cos_theta,F,Rs,Rp\n";
        write_rows(out, "%.17g,%.17g,%.17g,%.17g,%.17g\n", thetas, cosines, dev);
    } else {
        out << "# Fresnel " << f.canonical << "\n"
            << "# kernel fresnel_curve, " << precision_name(precision) << ", " << engine.device().name
            << "; max |device - host double| = " << std::setprecision(2) << host_diff << "\n";
        out << " theta_deg      cos_theta            F           Rs           Rp\n";
        write_rows(out, "%10.4f %14.8g %12.8f %12.8f %12.8f\n", thetas, cosines, dev);
        char line[200];
        std::snprintf(line, sizeof line, "# hemispherical average 2 int F mu dmu = %.12f +- %.1e\n", avg.value, avg.error);
        out << line << "#   (" << kAverageMethod << ")\n";
        if (cmp.present) {
            out << "# deviation from the exact " << (cmp.conductor ? "conductor" : "dielectric")
                << " over theta in [0, 90] deg:\n";
            std::snprintf(line, sizeof line,
                          "#   conductor-approx          max |dF| = %.3e at theta = %.3f deg; average %.8f\n",
                          cmp.approx.max_abs, cmp.approx.theta_deg, cmp.approx_avg.value);
            out << line;
            std::snprintf(line, sizeof line,
                          "#   schlick (f0 = %.6f)  max |dF| = %.3e at theta = %.3f deg; average %.8f\n", cmp.f0,
                          cmp.schlick.max_abs, cmp.schlick.theta_deg, cmp.schlick_avg.value);
            out << line;
        }
    }
    return out.str();
}

/// The angles of --theta, each in [0, 90] degrees, and their cosines.
struct AngleGrid {
    std::vector<double> thetas, cosines;
};
AngleGrid angle_grid(const std::string& text) {
    AngleGrid a;
    a.thetas = parse_number_list(text, "--theta");
    for (double t : a.thetas) {
        if (!(t >= 0.0 && t <= 90.0))
            throw Error("--theta: " + format_number(t) + " is out of range; angles of incidence lie in [0, 90] degrees");
        a.cosines.push_back(cos_deg(t));
    }
    return a;
}

Precision precision_of(const FresnelOptions& o) { return o.precision == "double" ? Precision::Double : Precision::Float; }

/// One spec's colours as `fresnel --rgb --format json` prints them.
nlohmann::json rgb_json(const FresnelOptions& o, Precision precision, const std::vector<double>& thetas,
                        const std::vector<double>& cosines, const FresnelColour& c, const Engine& engine) {
    nlohmann::json j;
    j["command"] = "fresnel";
    j["fresnel"] = o.fresnel;
    j["colour_space"] = colour_space_text(o.colour_space);
    j["precision"] = precision_name(precision);
    j["device"] = engine.device().name;
    j["results"] = nlohmann::json::array();
    for (size_t i = 0; i < thetas.size(); ++i)
        j["results"].push_back({{"theta_deg", thetas[i]}, {"cos_theta", cosines[i]}, {"rgb", c.rgb[i]},
                                {"rgb_error", c.error[i]}});
    return j;
}

/// A CSV field as RFC 4180 writes it: quoted (its quotes doubled) when it holds a comma or a quote.
std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string q = "\"";
    for (char ch : text) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
}

/// `fresnel --rgb --format csv`: a row per angle; with several specs (`labelled`) a first column
/// `fresnel` names each row's spec, the rows of each spec one after the other.
std::string rgb_csv(const std::vector<std::pair<std::string, FresnelColour>>& colours, const std::vector<double>& thetas,
                    const std::vector<double>& cosines, bool labelled) {
    std::ostringstream out;
    char line[240];
    out << (labelled ? "fresnel," : "") << "theta_deg,cos_theta,R,G,B,error_R,error_G,error_B\n";
    for (const auto& [spec, c] : colours)
        for (size_t i = 0; i < thetas.size(); ++i) {
            std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.3g,%.3g,%.3g\n", thetas[i], cosines[i],
                          c.rgb[i][0], c.rgb[i][1], c.rgb[i][2], c.error[i][0], c.error[i][1], c.error[i][2]);
            out << (labelled ? csv_field(spec) + "," : "") << line;
        }
    return out.str();
}

/// `fresnel --rgb`: the reflectance's colour in linear sRGB per angle (fresnel_rgb_on_device), a
/// table per spec; JSON: one spec's object, or an array of them (one per spec, in order); CSV:
/// rgb_csv.
std::string render_rgb(const FresnelOptions& o, Precision precision, const std::vector<double>& thetas,
                       const std::vector<double>& cosines,
                       const std::vector<std::pair<std::string, FresnelColour>>& colours, const Engine& engine) {
    const std::string space = colour_space_text(o.colour_space);
    std::ostringstream out;
    char line[240];
    const Format format = parse_format(o.format);
    if (format == Format::Csv) return rgb_csv(colours, thetas, cosines, colours.size() > 1);
    if (format == Format::Json) {
        nlohmann::json all = nlohmann::json::array();
        for (const auto& [spec, c] : colours) {
            FresnelOptions one = o;
            one.fresnel = spec;
            all.push_back(rgb_json(one, precision, thetas, cosines, c, engine));
        }
        out << (colours.size() == 1 ? all[0] : all).dump(2) << "\n";
        return out.str();
    }
    for (const auto& [spec, c] : colours) {
        out << "# Fresnel " << spec << " in " << space << "\n# kernel fresnel_curve, "
            << precision_name(precision) << ", " << engine.device().name << ", " << c.wavelengths
            << " wavelengths; error: |1 nm sum - 2 nm sum|\n";
        out << " theta_deg      cos_theta            R            G            B      error\n";
        for (size_t i = 0; i < thetas.size(); ++i) {
            const double e = std::max({c.error[i][0], c.error[i][1], c.error[i][2]});
            std::snprintf(line, sizeof line, "%10.4f %14.8g %12.8f %12.8f %12.8f %10.1e\n", thetas[i], cosines[i],
                          c.rgb[i][0], c.rgb[i][1], c.rgb[i][2], e);
            out << line;
        }
    }
    return out.str();
}

/// The plot's angles of `fresnel --rgb --plot`: theta in [0, 90] at 1 degree.
AngleGrid plot_grid() {
    AngleGrid a;
    for (int t = 0; t <= 90; ++t) {
        a.thetas.push_back(t);
        a.cosines.push_back(cos_deg(t));
    }
    return a;
}

/// The R, G and B curves of `fresnel --rgb --plot`: `rgb` holds the colours at plot_grid()'s angles.
PlotSpec rgb_panel(const FresnelOptions& o, const std::vector<std::array<double, 3>>& rgb) {
    const AngleGrid a = plot_grid();
    PlotSpec p;
    p.title = plot_text(short_numbers(o.fresnel)) + (o.colour_space == "acescg" ? ": ACEScg" : ": linear sRGB") +
              " (CIE 1931, D65)";
    p.x = theta_axis();
    p.y = PlotAxis{o.colour_space == "acescg" ? "reflectance, ACEScg" : "reflectance, linear sRGB", 0.0, std::numeric_limits<double>::quiet_NaN(), 0.2};
    const char* names[3] = {"R", "G", "B"};
    const char* pens[3] = {"r-4", "g-4", "b-4"};
    for (int ch = 0; ch < 3; ++ch) {
        Curve curve{names[ch], a.thetas, {}, pens[ch]};
        for (const auto& c : rgb) curve.y.push_back(c[ch]);
        p.curves.push_back(curve);
    }
    p.legend = LegendPlace::BottomLeft;
    return p;
}

/// The iridescence map's most rows (thicknesses), one kernel launch each.
constexpr int kMaxMapRows = 1001;

/// The checks of `--rgb --swatch` and `--thickness-range`; returns the thickness range (empty
/// without one).
std::vector<double> check_swatch(const FresnelOptions& o) {
    if (o.thickness_step && o.thickness_range.empty())
        throw Error("--thickness-step spaces the iridescence map's rows: add --thickness-range LO,HI");
    if (o.swatch.empty()) {
        if (!o.thickness_range.empty()) throw Error("--thickness-range is the iridescence map's y axis: add --swatch FILE.png");
        return {};
    }
    if (!is_plot_path(o.swatch)) throw Error("--swatch '" + o.swatch + "': expected a file name ending in .png or .svg");
    if (o.colour_space != "srgb") throw Error("--swatch shows colours encoded as sRGB; drop --colour-space");
    check_plot_output(o.swatch, "--swatch");
    if (o.thickness_range.empty()) return {};
    if (o.fresnels.size() != 1) throw Error("--thickness-range maps one thin film: give one --fresnel");
    const std::vector<double> range = parse_number_list(o.thickness_range, "--thickness-range");
    if (range.size() != 2 || !(range[0] >= 0.0 && range[1] > range[0] && range[1] <= 100000.0))
        throw Error("--thickness-range LO,HI: 0 <= LO < HI <= 100000 (nm)");
    if (o.fresnel.rfind("thin-film:", 0) != 0 ||
        resolve_fresnel(tables::thin_film_at(o.fresnel, range[0]), 550.0).kind != BB_FRESNEL_THIN_FILM)
        throw Error("--thickness-range maps a thin film's colour over its thickness; '" + o.fresnel + "' is not a thin-film: term");
    if (!o.thickness_step) return range;
    const auto nm = [](double v) { return short_numbers(std::to_string(v), 6); };
    const double step = *o.thickness_step;
    if (!(step > 0.0 && step <= range[1] - range[0]))
        throw Error("--thickness-step " + nm(step) + ": must lie in (0, HI - LO] = (0, " + nm(range[1] - range[0]) + "] nm");
    if (tables::thickness_slices(range[0], range[1], step) > kMaxMapRows)
        throw Error("--thickness-step " + nm(step) + " gives more than " + std::to_string(kMaxMapRows) + " rows over " +
                    nm(range[0]) + "-" + nm(range[1]) + " nm (one kernel launch each); give a larger step");
    return range;
}

/// `fresnel --rgb --swatch FILE --thickness-range LO,HI`: a thin film's iridescence map, and a
/// line (or JSON) saying what it holds.
int run_iridescence_map(const FresnelOptions& o, const GlobalOptions& g, const std::vector<double>& thickness) {
    if (!o.plot.empty()) throw Error("--thickness-range draws the map into --swatch's file; drop --plot");
    const Format format = parse_format(o.format);
    if (format == Format::Csv) throw Error("--thickness-range prints a line or JSON; drop --format csv");
    check_text_output(o.output);
    Engine engine(g.device, g.verbose);
    const int rows = o.thickness_step ? tables::thickness_slices(thickness[0], thickness[1], *o.thickness_step) : 121;
    const double error = write_iridescence_map(engine, o.swatch, o.fresnel, thickness[0], thickness[1], precision_of(o), rows);
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j = {{"command", "fresnel"},     {"fresnel", o.fresnel},  {"swatch", o.swatch},
                            {"angles_deg", {0, 90, 91}}, {"thickness_nm", {thickness[0], thickness[1], rows}},
                            {"max_rgb_error", error},    {"colour_space", colour_space_text("srgb")}};
        out << j.dump(2) << "\n";
    } else {
        out << "# iridescence map of " << o.fresnel << " written to " << o.swatch << ": theta 0-90 deg at 1 deg x "
            << rows << " thicknesses " << short_numbers(std::to_string(thickness[0]), 6) << "-" << short_numbers(std::to_string(thickness[1]), 6)
            << " nm, in " << colour_space_text("srgb") << ", encoded as sRGB; largest |1 nm - 2 nm sum| "
            << format_number(error) << "\n";
    }
    emit(o.output, out.str());
    return kExitOk;
}

int run_fresnel_rgb(const FresnelOptions& o, const GlobalOptions& g) {
    if (o.wavelength_nm != 0.0)
        throw Error("--rgb sums the visible spectrum (380 to 780 nm); drop --wavelength, which picks one");
    if (o.compare) throw Error("--compare draws one wavelength's comparison; drop --rgb or --compare");
    if (o.fresnel.empty()) throw Error("--rgb needs --fresnel SPEC");
    parse_format(o.format);
    if (!o.plot.empty() && !is_plot_path(o.plot))
        throw Error("--plot '" + o.plot + "': expected a file name ending in .png or .svg");
    check_plot_output(o.plot, "--plot");
    const std::vector<double> thickness = check_swatch(o);
    if (!thickness.empty()) return run_iridescence_map(o, g, thickness);
    for (const std::string& spec : o.fresnels) resolve_fresnel(spec, 550.0);  // a bad spec is refused before any work
    check_text_output(o.output);
    const AngleGrid a = angle_grid(o.theta);
    const Precision precision = precision_of(o);
    Engine engine(g.device, g.verbose);
    // One spectral pass for the printed angles and, with --plot, the plot's grid after them.
    std::vector<double> cosines = a.cosines;
    if (!o.plot.empty())
        for (double c : plot_grid().cosines) cosines.push_back(c);
    std::vector<std::pair<std::string, FresnelColour>> colours;
    for (const std::string& spec : o.fresnels) {
        FresnelColour c = fresnel_rgb_on_device(engine, spec, precision, cosines, o.colour_space);
        if (!o.plot.empty() && colours.empty())
            write_plot(o.plot, rgb_panel(o, {c.rgb.begin() + std::ptrdiff_t(a.cosines.size()), c.rgb.end()}));
        c.rgb.resize(a.cosines.size());
        c.error.resize(a.cosines.size());
        colours.emplace_back(spec, c);
    }
    if (!o.swatch.empty())
        write_swatches(o.swatch, colours, a.thetas);
    emit(o.output, render_rgb(o, precision, a.thetas, a.cosines, colours, engine));
    return kExitOk;
}

/// `fresnel --fit f82-tint`: the F82-tint f0 and tint of each linear-sRGB channel.
std::string render_f82_fit(const FresnelOptions& o, const fit::F82TintFit& r) {
    const Format format = parse_format(o.format);
    const char* names[3] = {"R", "G", "B"};
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "fresnel";
        j["fit"] = "f82-tint";
        j["fresnel"] = o.fresnel;
        j["colour_space"] = colour_space_text("srgb");
        j["f0"] = r.f0;
        j["tint"] = r.tint;
        j["max_error"] = r.max_error;
        j["max_error_theta_deg"] = r.max_error_theta_deg;
        j["colour_error"] = r.colour_error;
        out << j.dump(2) << "\n";
        return out.str();
    }
    if (format == Format::Csv) throw Error("--fit prints a table or JSON; --format csv is for curves");
    out << "# F82-tint of " << o.fresnel << " in linear sRGB (CIE 1931 observer, D65): f0 = F(0 deg), tint = "
        << "F(82.2 deg) / Schlick's; max |F82-tint - F| over theta on a 0.25 deg grid\n";
    out << "# channel           f0         tint    max |dF|   at theta  colour error\n";
    char line[200];
    for (int c = 0; c < 3; ++c) {
        std::snprintf(line, sizeof line, "  %-7s %12.6f %12.6f %11.2e %8.2f deg %10.1e\n", names[c], r.f0[c], r.tint[c],
                      r.max_error[c], r.max_error_theta_deg[c], r.colour_error[c]);
        out << line;
    }
    return out.str();
}

int run_fresnel_fit(const FresnelOptions& o, const GlobalOptions& g) {
    if (o.fit != "f82-tint") throw Error("--fit '" + o.fit + "': the fit known is f82-tint");
    if (o.wavelength_nm != 0.0 || o.rgb || o.compare || !o.plot.empty())
        throw Error("--fit f82-tint fits the spectral colour of --fresnel alone; drop --wavelength, --rgb, --plot and --compare");
    if (o.colour_space != "srgb") throw Error("--fit f82-tint gives linear-sRGB parameters; drop --colour-space");
    if (o.fresnel.empty()) throw Error("--fit needs --fresnel SPEC, e.g. --fresnel metal:Au");
    resolve_fresnel(o.fresnel, 550.0);  // a bad spec is refused before any work
    parse_format(o.format);
    check_text_output(o.output);
    const Precision precision = precision_of(o);
    Engine engine(g.device, g.verbose);
    emit(o.output, render_f82_fit(o, fit::fit_f82_tint(engine, o.fresnel, precision)));
    return kExitOk;
}

int run_fresnel(FresnelOptions o, const GlobalOptions& g) {
    o.fresnel = o.fresnels.empty() ? "" : o.fresnels.front();
    if (o.fresnels.size() > 1 && !o.rgb) throw Error("several --fresnel are for --rgb (colours); give one");
    if (!o.rgb && (!o.swatch.empty() || !o.thickness_range.empty() || o.thickness_step))
        throw Error(std::string(!o.swatch.empty() ? "--swatch" : !o.thickness_range.empty() ? "--thickness-range" : "--thickness-step") +
                    " draws colours: add --rgb");
    if (!o.fit.empty()) return run_fresnel_fit(o, g);
    if (o.rgb) return run_fresnel_rgb(o, g);
    if (o.colour_space != "srgb") throw Error("--colour-space picks --rgb's colour space; add --rgb");
    const auto t0 = std::chrono::steady_clock::now();
    // Check every input before touching the device.
    if (o.compare) {
        if (o.plot.empty()) throw Error("--compare draws a figure; give --plot FILE.png or --plot FILE.svg");
        if (o.fresnel.empty()) o.fresnel = "metal:Al";
        if (o.wavelength_nm == 0.0 && fresnel_needs_wavelength(o.fresnel))
            o.wavelength_nm = 550.0;
    }
    if (o.fresnel.empty()) throw Error("--fresnel SPEC is required (or --compare for the comparison figure)");
    const FresnelConfig f = resolve_fresnel(o.fresnel, o.wavelength_nm);
    if (o.compare && f.kind != BB_FRESNEL_CONDUCTOR && f.kind != BB_FRESNEL_CONDUCTOR_APPROX)
        throw Error("--compare needs a conductor (conductor:, conductor-approx:, metal: or nk: with k data); got '" +
                    f.canonical + "'");
    parse_format(o.format);
    if (!o.plot.empty() && !is_plot_path(o.plot))
        throw Error("--plot '" + o.plot + "': expected a file name ending in .png or .svg");
    check_plot_output(o.plot, "--plot");
    check_text_output(o.output);
    const AngleGrid grid = angle_grid(o.theta);
    const std::vector<double>& thetas = grid.thetas;
    const std::vector<double>& cosines = grid.cosines;
    const Precision precision = precision_of(o);

    Engine engine(g.device, g.verbose);
    const FresnelCurves dev = fresnel_on_device(engine, f, precision, cosines);
    const HostFresnel host(f);
    double host_diff = 0.0;
    for (size_t i = 0; i < cosines.size(); ++i) {
        host_diff = std::max(host_diff, std::fabs(dev.f[i] - host.f(cosines[i])));
        host_diff = std::max(host_diff, std::fabs(dev.rs[i] - host.rs(cosines[i])));
        host_diff = std::max(host_diff, std::fabs(dev.rp[i] - host.rp(cosines[i])));
    }
    const Quadrature avg = f.kind == BB_FRESNEL_NONE ? Quadrature{1.0, 0.0} : hemispherical_average(host);
    const Comparison cmp = compare_forms(f);

    if (!o.plot.empty()) {
        if (o.compare)
            write_figure(o.plot, comparison_figure(f));
        else
            write_plot(o.plot, single_panel(f));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    emit(o.output, render(o, f, precision, thetas, cosines, dev, host_diff, avg, cmp, engine, seconds));
    return kExitOk;
}

}  // namespace

void add_fresnel_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<FresnelOptions>(
        app, "fresnel", "Fresnel reflectance F, Rs, Rp over the angle of incidence", global, action, run_fresnel);
    cmd->add_option("--fresnel", o->fresnels, fresnel_spec_help() + " (with --rgb, repeat for each term's colours: a swatch row each)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_option("--theta", o->theta, "comma-separated angles of incidence in degrees, in [0, 90]")
        ->capture_default_str();
    cmd->add_option("--wavelength", o->wavelength_nm, "wavelength in nm for the terms that depend on it (metal:, nk:, thin-film:)");
    add_precision_option(cmd, o->precision);
    add_format_option(cmd, o->format, {"table", "json", "csv"});
    cmd->add_option("-o,--output", o->output, "write to FILE instead of standard output");
    cmd->add_option("--plot", o->plot, "draw the curves into FILE.png or FILE.svg");
    cmd->add_flag("--rgb", o->rgb,
                  "the reflectance's colour in linear sRGB: F over 380-780 nm (each wavelength's n, k or film) "
                  "weighed by the CIE 1931 observer under D65");
    cmd->add_option("--swatch", o->swatch,
                    "with --rgb: draw the colour at each --theta angle as an sRGB-encoded swatch into FILE.png or "
                    "FILE.svg, a row per --fresnel (the PNG holds the 8-bit levels exactly)");
    cmd->add_option("--thickness-range", o->thickness_range,
                    "LO,HI in nm, with --rgb --swatch and a thin-film: term: draw its colour over the angle (x, 0-90 "
                    "degrees) and the film's thickness (y, LO to HI) instead");
    cmd->add_option("--thickness-step", o->thickness_step,
                    "NM, with --thickness-range: the map's rows at most NM apart, ceil((HI - LO) / NM) + 1 of them "
                    "(default: 121 rows)");
    add_colour_space_option(cmd, o->colour_space,
                            "--rgb's colour space: srgb (linear sRGB) or acescg (ACES AP1, the ACES white by Bradford)");
    cmd->add_option("--fit", o->fit,
                    "f82-tint: the F82-tint f0 and tint per linear-sRGB channel of --fresnel's spectral colour "
                    "(OpenPBR's metal), with the largest deviation over angle");
    cmd->add_flag("--compare", o->compare,
                  "draw the comparison figure: exact vs approximate vs Schlick for a metal (default metal:Al at "
                  "550 nm) beside eta = 1.5 seen from outside and inside; needs --plot");
}

}  // namespace brdfbake

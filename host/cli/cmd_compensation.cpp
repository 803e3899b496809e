// `brdfbake compensation`: how far the energy-compensation schemes of real-time renderers are from
// the multiple-scattering Smith microsurface they approximate (issue 35 item 3). Each scheme is
// built from brdfbake's own integrals of the single-scattering height-correlated lobe (E(mu) with
// F = 1, E_F(mu) with Schlick's F, and their cosine-weighted average Eavg, tables/mu_average.h) and
// compared, per alpha and mu, with the random walk of Heitz, Hanika, d'Eon and Dachsbacher 2016
// (brdf/random_walk.h) under the same Schlick term at every bounce: the difference in albedo, with
// the walk's error estimate plus the integrals', and the L1 distance between each scheme's lobe and
// the walk's (f by next-event estimation, walk_eval), integral of |f_scheme - f_walk| cos over wi.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/analytic.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "cli/compensation.h"
#include "cli/furnace_sphere.h"
#include "integrate/random_walk.h"
#include "models/key_reader.h"
#include "plot/plot.h"
#include "tables/mu_average.h"

namespace brdfbake {

std::vector<double> e_grid_nodes() {
    std::vector<double> grid;
    for (int k = 0; k < kEGrid; ++k) grid.push_back((k + 0.5) / kEGrid);
    return grid;
}

double e_at(const std::vector<AlbedoValue>& grid, double mu) {
    const double x = std::clamp(mu * kEGrid - 0.5, 0.0, double(kEGrid - 1));
    const int k = std::min(int(x), kEGrid - 2);
    return grid[k].value + (x - k) * (grid[k + 1].value - grid[k].value);
}

LobeDirections lobe_directions(Engine& engine, const ModelConfig& single, double alpha, double mu, int n,
                               std::uint64_t seed) {
    LobeDirections d;
    d.wo = {std::sqrt(1.0 - mu * mu), 0.0, mu};
    std::mt19937_64 rng(std::uint64_t(alpha * 1e6) * 1000003u + std::uint64_t(mu * 1e6) + seed * 0x9E3779B97F4A7C15u);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < n / 2; ++k) {  // cosine-weighted
        const double z = std::sqrt(u(rng)), p = 2 * M_PI * u(rng), s = std::sqrt(1 - z * z);
        d.wi.push_back({s * std::cos(p), s * std::sin(p), z});
    }
    std::vector<std::array<double, 2>> us;
    for (int k = n / 2; k < n; ++k) us.push_back({u(rng), u(rng)});
    const FresnelConfig none = resolve_fresnel("none");
    for (const DeviceSample& s : sample_on_device(engine, single, none, Precision::Double,
                                                  std::vector<Vec3>(us.size(), d.wo), us))
        if (s.wi[2] > 0.0 && std::isfinite(s.weight)) d.wi.push_back(s.wi);  // one below the horizon adds 0
    d.f_single =
        evaluate_on_device(engine, single, none, Precision::Double, std::vector<Vec3>(d.wi.size(), d.wo), d.wi);
    const bool beckmann = single.name == "beckmann";
    const auto lambda = [&](const Vec3& w) {
        const bb_vec3 v = bb_v3(w[0], w[1], w[2]);
        return beckmann ? bb_beckmann_lambda(v, alpha, alpha) : bb_ggx_lambda(v, alpha, alpha);
    };
    const double lo = lambda(d.wo);
    for (size_t k = 0; k < d.wi.size(); ++k) {
        const double z = d.wi[k][2];
        d.density.push_back(0.5 * z / M_PI + 0.5 * d.f_single[k] * z * (1.0 + lo + lambda(d.wi[k])) / (1.0 + lo));
    }
    return d;
}

std::string number_cell(bool csv, double v, int width, int digits) {
    char cell[64];
    if (csv)
        std::snprintf(cell, sizeof cell, ",%.17g", v);
    else
        std::snprintf(cell, sizeof cell, " %*.*f", width, digits, v);
    return cell;
}

std::string lobe_cells(bool csv, const std::vector<std::string>& names, const std::vector<double>& l1, double error,
                       double noise) {
    std::string out;
    for (size_t k = 0; k < names.size(); ++k) out += number_cell(csv, l1[k], int(names[k].size()) + 3, 5);
    char cell[64];
    std::snprintf(cell, sizeof cell, csv ? ",%.3e,%.3e" : " %10.2e %10.2e", error, noise);
    return out + cell;
}

PlotSpec mu_panel(const std::string& title, const std::string& y_label, const std::vector<MuPoint>& points,
                  bool zero_line) {
    PlotSpec p;
    p.title = title;
    p.x.label = "\\mu = cos \\theta_o";
    p.y.label = y_label;
    p.x.lo = 0.0;
    p.x.hi = 1.0;
    p.legend = LegendPlace::Outside;  // the curves reach every corner at some alpha: a legend inside covers one
    for (const MuPoint& q : points) {
        if (p.curves.empty() || p.curves.back().label != "\\alpha = " + format_number(q.alpha))
            p.curves.push_back(Curve{"\\alpha = " + format_number(q.alpha), {}, {}, ""});
        p.curves.back().x.push_back(q.mu);
        p.curves.back().y.push_back(q.y);
    }
    if (zero_line) p.lines.push_back(RefLine{'y', 0.0, ""});
    return p;
}

namespace {

/// What a scheme is built from, at one alpha and mu.
struct SchemeInputs {
    double e;     // E(mu): the single-scattering albedo with F = 1
    double e_f;   // E_F(mu): the same with Schlick's F(f0) at the microfacet
    double e_avg; // Eavg = 2 int E(mu) mu dmu
    double f0;    // Schlick's normal reflectance
    double f_avg; // Favg = 2 int F(mu) mu dmu = f0 + (1 - f0)/21 for Schlick [KC17]
};

/// What a scheme's lobe adds at one wi: the single-scattering lobe f_ss(wo, wi) (with Schlick's F)
/// and E(mu_i), beside the inputs at wo.
struct LobePoint {
    double f_ss;  // the height-correlated lobe with Schlick's F at (wo, wi)
    double e_i;   // E(mu_i), F = 1
};

/// A compensation scheme: its name, its source, the compensated albedo it predicts and its lobe
/// f(wo, wi) (whose integral of f cos over wi is that albedo).
struct Scheme {
    const char* name;
    const char* source;
    double (*albedo)(const SchemeInputs&);
    double (*lobe)(const SchemeInputs&, const LobePoint&);
};

/// The registry of schemes (one row each).
const std::vector<Scheme>& schemes() {
    static const std::vector<Scheme> s = {
        // [KC17] Kulla and Conty 2017, "Revisiting Physically Based Shading at Imageworks": the lobe
        // f_ms = (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - Eavg)), whose albedo is 1 - E(mu_o), times
        // Favg^2 Eavg / (1 - Favg (1 - Eavg)).
        {"kulla-conty", "Kulla and Conty 2017 (E, Eavg)",
         [](const SchemeInputs& x) {
             return x.e_f + (1.0 - x.e) * x.f_avg * x.f_avg * x.e_avg / (1.0 - x.f_avg * (1.0 - x.e_avg));
         },
         [](const SchemeInputs& x, const LobePoint& p) {
             return p.f_ss + (1.0 - x.e) * (1.0 - p.e_i) / (M_PI * (1.0 - x.e_avg)) * x.f_avg * x.f_avg * x.e_avg /
                                 (1.0 - x.f_avg * (1.0 - x.e_avg));
         }},
        // [FA19] Fdez-Aguera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-based
        // Lighting": Ess = A + B, FssEss = F0 A + B (the split sum), Ems = 1 - Ess,
        // Fms = FssEss Favg / (1 - Ems Favg); albedo FssEss + Fms Ems, the added part a uniform
        // (cosine-weighted) lobe Fms Ems / pi, as its irradiance term is.
        {"fdez-aguera", "Fdez-Aguera 2019 (split-sum multiple scattering)",
         [](const SchemeInputs& x) {
             const double ems = 1.0 - x.e;
             return x.e_f + ems * x.e_f * x.f_avg / (1.0 - ems * x.f_avg);
         },
         [](const SchemeInputs& x, const LobePoint& p) {
             const double ems = 1.0 - x.e;
             return p.f_ss + ems * x.e_f * x.f_avg / (1.0 - ems * x.f_avg) / M_PI;
         }},
        // [T19] Turquin 2019, "Practical multiple scattering compensation for microfacet models":
        // the single-scattering lobe scaled by 1 + F0 (1/E(mu_o) - 1).
        {"turquin", "Turquin 2019 (1 + F0 (1/E - 1))",
         [](const SchemeInputs& x) { return x.e_f * (1.0 + x.f0 * (1.0 / x.e - 1.0)); },
         [](const SchemeInputs& x, const LobePoint& p) { return p.f_ss * (1.0 + x.f0 * (1.0 / x.e - 1.0)); }},
    };
    return s;
}

/// One (alpha, mu) row: the walk, the single-scattering terms and each scheme's albedo.
struct Row {
    double alpha, mu;
    AlbedoValue walk;
    SchemeInputs in;
    double input_error;  // the integrals' error, carried into every scheme's
    std::vector<double> scheme;
    std::vector<double> lobe_l1;  // per scheme: integral of |f_scheme - f_walk| cos over wi
    double l1_error = 0.0;        // 3 standard errors of that integral (the largest over the schemes)
    double l1_noise = 0.0;        // what the walk's noise alone adds to it (expected |noise|)
};

std::vector<AlbedoValue> single_albedo(Engine& engine, const ModelConfig& m, const FresnelConfig& f,
                                       const std::vector<double>& mus, double tolerance) {
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = f;
    req.precision = Precision::Double;
    req.cells = cells_for(mus, 0.0, m.params);
    ToleranceRequest tol;
    tol.tolerance = tolerance;
    return albedo_of_model(engine, m, f, req, tol).values;
}

/// The models and terms of one alpha that the lobe distance reads.
struct LobeInputs {
    const ModelConfig &single, &walk;
    const FresnelConfig &none, &schlick;
    std::vector<AlbedoValue> e_grid;
};

/// Each scheme's lobe against the walk's at (alpha, mu) (Row::lobe_l1): integral of
/// |f_scheme - f_walk| cos over wi by o.lobe_directions directions, half cosine-weighted and half
/// the single-scattering lobe's visible-normal sample (sample_on_device), weighted by the mixture's
/// density (the visible normals' p(wi) = f wi.z G1(wo) / G2(wo, wi) with F = 1, Lambda from
/// brdf/microfacet.h); f_walk by next-event estimation on o.lobe_walks walks per direction.
void lobe_distance(Engine& engine, const CompensationOptions& o, const LobeInputs& in, Row& r) {
    const int n = o.lobe_directions;
    const LobeDirections dirs = lobe_directions(engine, in.single, r.alpha, r.mu, n);
    const std::vector<Vec3>& wis = dirs.wi;
    const std::vector<Vec3> wos(wis.size(), dirs.wo);
    const std::vector<double> f_ss = evaluate_on_device(engine, in.single, in.schlick, Precision::Double, wos, wis);
    WalkEvalRequest req;
    req.model = in.walk.id;
    req.fresnel = in.schlick;
    req.samples = std::uint64_t(o.lobe_walks);
    for (const Vec3& wi : wis) req.pairs.push_back({dirs.wo, wi, in.walk.params});
    const WalkEvalResult walk = walk_eval(engine, req);
    std::vector<double> sum(schemes().size(), 0.0), sum2(schemes().size(), 0.0);
    double noise = 0.0;
    for (size_t k = 0; k < wis.size(); ++k) {
        const double z = wis[k][2], p = dirs.density[k];
        const LobePoint at{f_ss[k], e_at(in.e_grid, z)};
        for (size_t s = 0; s < schemes().size(); ++s) {
            const double d = std::fabs(schemes()[s].lobe(r.in, at) - walk.f[k].value) * z / p;
            sum[s] += d;
            sum2[s] += d * d;
        }
        noise += walk.f[k].error / 3.0 * std::sqrt(2.0 / M_PI) * z / p;
    }
    for (size_t s = 0; s < schemes().size(); ++s) {
        const double mean = sum[s] / n;
        r.lobe_l1.push_back(mean);
        r.l1_error = std::max(r.l1_error, 3.0 * std::sqrt(std::max(0.0, sum2[s] / n - mean * mean) / (n - 1)));
    }
    r.l1_noise = noise / n;
}

std::vector<Row> compute(Engine& engine, const CompensationOptions& o, const std::vector<double>& alphas,
                         const std::vector<double>& mus) {
    const FresnelConfig none = resolve_fresnel("none");
    const FresnelConfig schlick = resolve_fresnel("schlick:f0=" + format_number(o.f0));
    std::vector<Row> rows;
    for (double a : alphas) {
        const std::string spec = o.model + ":alpha=" + format_number(a);
        const ModelConfig single = resolve_model(spec);
        const std::vector<AlbedoValue> e = single_albedo(engine, single, none, mus, 1e-5);
        const std::vector<AlbedoValue> e_f = single_albedo(engine, single, schlick, mus, 1e-5);
        const tables::MuAverage avg = tables::average_over_mu(1, 1e-4, [&](const std::vector<double>& nodes) {
            tables::MuSamples s;
            s.values = single_albedo(engine, single, none, nodes, 2.5e-5);
            return s;
        });
        const ModelConfig walk_model = resolve_model_simulated(spec + ",scattering=multiple");
        AlbedoRequest req;
        req.model = walk_model.id;
        req.fresnel = schlick;
        req.samples = std::uint64_t(o.walks);
        req.cells = cells_for(mus, 0.0, walk_model.params);
        const WalkResult walk = walk_albedo(engine, req);
        const std::vector<double> grid = e_grid_nodes();
        const LobeInputs lobe{single, walk_model, none, schlick,
                              o.lobe_directions > 0 ? single_albedo(engine, single, none, grid, 1e-4)
                                                    : std::vector<AlbedoValue>{}};
        for (size_t k = 0; k < mus.size(); ++k) {
            Row r{a, mus[k], walk.values[k].energy, {e[k].value, e_f[k].value, avg.value[0], o.f0, o.f0 + (1 - o.f0) / 21},
                  e[k].error + e_f[k].error + avg.error[0], {}, {}, 0.0, 0.0};
            for (const Scheme& s : schemes()) r.scheme.push_back(s.albedo(r.in));
            if (o.lobe_directions > 0) lobe_distance(engine, o, lobe, r);
            rows.push_back(r);
        }
    }
    return rows;
}

std::string render(const CompensationOptions& o, const std::vector<size_t>& picked, const std::vector<Row>& rows,
                   Format format) {
    std::ostringstream out;
    const auto& all = schemes();
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "compensation";
        j["model"] = o.model;
        j["fresnel"] = "schlick:f0=" + format_number(o.f0);
        j["walks"] = o.walks;
        j["results"] = nlohmann::json::array();
        for (const Row& r : rows) {
            nlohmann::json e = {{"alpha", r.alpha},         {"mu", r.mu},        {"walk", r.walk.value},
                                {"walk_error", r.walk.error}, {"single", r.in.e_f}, {"e", r.in.e},
                                {"e_avg", r.in.e_avg}};
            for (size_t s : picked) {
                e[all[s].name] = r.scheme[s];
                e[std::string(all[s].name) + "_difference"] = r.scheme[s] - r.walk.value;
                e[std::string(all[s].name) + "_error"] = r.walk.error + r.input_error;
                if (!r.lobe_l1.empty()) e[std::string(all[s].name) + "_lobe_l1"] = r.lobe_l1[s];
            }
            if (!r.lobe_l1.empty()) {
                e["lobe_l1_error"] = r.l1_error;
                e["lobe_l1_noise"] = r.l1_noise;
            }
            j["results"].push_back(e);
        }
        out << j.dump(2) << "\n";
        return out.str();
    }
    const bool csv = format == Format::Csv;
    if (!csv) {
        out << "# compensation schemes against the random walk (Heitz et al. 2016), " << o.model
            << ", Schlick f0 = " << o.f0 << " at every bounce, " << o.walks << " walks per direction\n"
            << "# walk: the multiple-scattering albedo; single: E_F, the height-correlated lobe's; per scheme its "
               "albedo minus the walk's (error: the walk's plus the integrals')\n";
        for (size_t s : picked) out << "# " << all[s].name << ": " << all[s].source << "\n";
        if (o.lobe_directions > 0)
            out << "# l1 (per scheme): integral of |f_scheme - f_walk| cos over wi, " << o.lobe_directions
                << " directions x " << o.lobe_walks << " walks (next-event estimation); l1_err: 3 standard errors; "
                   "noise: what the walk's noise alone adds\n";
    }
    const bool lobe = o.lobe_directions > 0;
    out << (csv ? "alpha,mu,walk,walk_error,single" : "   alpha      mu       walk      error     single");
    for (size_t s : picked) out << (csv ? "," : " ") << all[s].name << (csv ? "_difference" : "");
    out << (csv ? ",error" : "      error");
    if (lobe) {
        for (size_t s : picked) out << (csv ? "," : " ") << all[s].name << "_l1";
        out << (csv ? ",l1_error,l1_noise" : "     l1_err      noise");
    }
    out << "\n";
    char cell[96];
    for (const Row& r : rows) {
        std::snprintf(cell, sizeof cell, csv ? "%.17g,%.17g,%.17g,%.3e,%.17g" : "%8.4f %7.4f %10.6f %10.2e %10.6f",
                      r.alpha, r.mu, r.walk.value, r.walk.error, r.in.e_f);
        out << cell;
        std::vector<std::string> names;
        std::vector<double> l1;
        for (size_t s : picked) {
            out << number_cell(csv, r.scheme[s] - r.walk.value, int(std::strlen(all[s].name)), 6);
            names.push_back(all[s].name);
            if (lobe) l1.push_back(r.lobe_l1[s]);
        }
        std::snprintf(cell, sizeof cell, csv ? ",%.3e" : " %10.2e", r.walk.error + r.input_error);
        out << cell;
        if (lobe) out << lobe_cells(csv, names, l1, r.l1_error, r.l1_noise);
        out << "\n";
    }
    return out.str();
}

/// One panel per scheme: its albedo minus the walk's against mu, one curve per alpha.
void plot_rows(const std::string& path, const CompensationOptions& o, const std::vector<size_t>& picked,
               const std::vector<Row>& rows) {
    Figure fig;
    fig.panel_width = 640;
    fig.panel_height = 480;
    for (size_t s : picked) {
        std::vector<MuPoint> points;
        for (const Row& r : rows) points.push_back({r.alpha, r.mu, r.scheme[s] - r.walk.value});
        fig.panels.push_back(mu_panel(std::string(schemes()[s].name) + " - walk", "albedo difference", points, true));
    }
    if (o.lobe_directions > 0)  // a second row: each scheme's lobe L1 distance from the walk's
        for (size_t s : picked) {
            std::vector<MuPoint> points;
            for (const Row& r : rows) points.push_back({r.alpha, r.mu, r.lobe_l1[s]});
            fig.panels.push_back(mu_panel(std::string(schemes()[s].name) + ": lobe L1 distance from the walk's",
                                          "\\int |f - f_{walk}| cos \\theta_i d\\omega_i", points, false));
        }
    fig.columns = int(picked.size());
    fig.caption = "random walk (Heitz et al. 2016) against each scheme, " + o.model + ", Schlick f_0 = " +
                  format_number(o.f0) + " at every bounce";
    write_figure(path, fig);
}

/// `--furnace FILE`: per alpha a row of spheres under the white environment (radiance 1), each
/// pixel E(n.v) with Schlick's f0 at every bounce: single scattering (E_F), each picked scheme's
/// compensated albedo and the walk's (multiple scattering), side by side. E at o.furnace_nodes mu
/// nodes (furnace_nodes), the walk with o.walks walks each; returns the walk's largest error.
double draw_furnace(Engine& engine, const CompensationOptions& o, const std::vector<size_t>& picked,
                    const std::vector<double>& alphas) {
    CompensationOptions albedo_only = o;
    albedo_only.lobe_directions = 0;
    const std::vector<double> mus = furnace_nodes(o.furnace_nodes);
    const std::vector<Row> rows = compute(engine, albedo_only, alphas, mus);
    Figure fig = furnace_figure(o.furnace_pixels);
    fig.columns = int(picked.size()) + 2;
    double worst = 0.0;
    for (size_t a = 0; a < alphas.size(); ++a) {
        std::vector<std::vector<double>> e(picked.size() + 2);
        for (size_t k = 0; k < mus.size(); ++k) {
            const Row& r = rows[a * mus.size() + k];
            e.front().push_back(r.in.e_f);
            for (size_t s = 0; s < picked.size(); ++s) e[s + 1].push_back(r.scheme[picked[s]]);
            e.back().push_back(r.walk.value);
            worst = std::max(worst, r.walk.error);
        }
        const std::string alpha = "\\alpha = " + format_number(alphas[a]) + ": ";
        fig.panels.push_back(furnace_sphere(alpha + "single", e.front(), o.furnace_pixels));
        for (size_t s = 0; s < picked.size(); ++s)
            fig.panels.push_back(furnace_sphere(alpha + schemes()[picked[s]].name, e[s + 1], o.furnace_pixels));
        fig.panels.push_back(furnace_sphere(alpha + "walk", e.back(), o.furnace_pixels));
    }
    fig.caption = "white furnace of " + o.model + ", Schlick f_0 = " + format_number(o.f0) +
                  " at every bounce: single scattering, each compensation scheme, the random walk (multiple "
                  "scattering, Heitz et al. 2016)";
    write_figure(o.furnace, fig);
    return worst;
}

/// The conductor's schemes `o.scheme` picks, and its --model and --f0 checked (one line each).
std::vector<size_t> check_conductor(const CompensationOptions& o) {
    std::vector<size_t> picked;
    std::string names;
    for (size_t s = 0; s < schemes().size(); ++s) {
        names += std::string(names.empty() ? "" : ", ") + schemes()[s].name;
        if (o.scheme == "all" || o.scheme == schemes()[s].name) picked.push_back(s);
    }
    if (picked.empty()) throw Error("--scheme: unknown scheme '" + o.scheme + "'; known: all, " + names);
    if (o.model.find(':') != std::string::npos)
        throw Error("--model '" + o.model + "': give the distribution's name, ggx or beckmann (isotropic, height-correlated)" +
                    (o.model.find("eta=") != std::string::npos
                         ? "; the rough dielectric is compared by --eta E (ggx)"
                         : ""));
    // The random walk's resolver names what it does not take (a model without scattering=multiple).
    if (resolve_model_simulated(o.model + ":alpha=0.5,scattering=multiple").dielectric_walk)
        throw Error("--model: give the distribution's name (ggx or beckmann); the rough dielectric is --eta E");
    if (!(o.f0 >= 0.0 && o.f0 <= 1.0)) throw Error("--f0: " + format_number(o.f0) + " must lie in [0, 1]");
    return picked;
}

int run_compensation(const CompensationOptions& o, const GlobalOptions& g) {
    const Format format = parse_format(o.format);
    check_text_output(o.output);
    check_plot_output(o.plot, "--plot");
    check_plot_output(o.furnace, "--furnace");
    if (!o.furnace.empty() && o.furnace == o.plot) throw Error("--furnace and --plot name the same file");
    if (o.furnace_nodes < 4 || o.furnace_nodes > 256) throw Error("--furnace-nodes must be 4 to 256");
    if (o.furnace_pixels < 16 || o.furnace_pixels > 1024) throw Error("--furnace-pixels must be 16 to 1024");
    if (o.lobe_directions < 0 || o.lobe_directions == 1 || o.lobe_directions > 1 << 20)
        throw Error("--lobe-directions must be 0 or 2 to 2^20");
    if (o.lobe_walks < 32) throw Error("--lobe-walks must be at least 32");
    std::vector<size_t> picked;
    if (o.eta_given)
        check_dielectric_compensation(o, o.f0_given);
    else
        picked = check_conductor(o);
    if (o.walks < 16) throw Error("--walks must be at least 16");
    const std::vector<double> alphas = parse_number_list(o.alpha, "--alpha");
    const std::vector<double> mus = parse_number_list(o.mu, "--mu");
    for (double mu : mus)
        if (!(mu > 0.0 && mu <= 1.0)) throw Error("--mu: " + format_number(mu) + " must lie in (0, 1]");
    for (double a : alphas) resolve_model(o.model + ":alpha=" + format_number(a));  // its range, before the device
    Engine engine(g.device, g.verbose);
    if (o.eta_given) {
        run_dielectric_compensation(engine, o, alphas, mus, format);
        return kExitOk;
    }
    const std::vector<Row> rows = compute(engine, o, alphas, mus);
    if (!o.plot.empty()) plot_rows(o.plot, o, picked, rows);
    if (!o.furnace.empty()) {
        const double worst = draw_furnace(engine, o, picked, alphas);
        std::fprintf(stderr, "brdfbake: wrote %s: %zu rows of %zu spheres (the walk's error at most %.1e)\n",
                     o.furnace.c_str(), alphas.size(), picked.size() + 2, worst);
    }
    emit(o.output, render(o, picked, rows, format));
    return kExitOk;
}

}  // namespace

void add_compensation_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<CompensationOptions>(
        app, "compensation",
        "multiple-scattering compensation schemes (Kulla-Conty, Fdez-Aguera, Turquin) against the random walk",
        global, action, run_compensation);
    cmd->add_option("--scheme", o->scheme, "kulla-conty, fdez-aguera, turquin or all (--eta: kulla-conty, turquin)")->capture_default_str();
    cmd->add_option("--model", o->model, "the distribution: ggx or beckmann (height-correlated)")->capture_default_str();
    cmd->add_option("--alpha", o->alpha, "comma-separated alpha values")->capture_default_str();
    cmd->add_option("--mu", o->mu, "comma-separated cos(theta_o) values in (0, 1]")->capture_default_str();
    cmd->add_option_function<double>(
           "--f0", [o = o](double v) { o->f0 = v, o->f0_given = true; }, "Schlick's normal reflectance at every bounce")
        ->default_str("0.5");
    cmd->add_option_function<double>(
        "--eta", [o = o](double v) { o->eta = v, o->eta_given = true; },
        "the rough dielectric (ggx) of this index relative to the outside, > 1: each glass scheme (kulla-conty, "
        "turquin) against the dielectric walk's R and T from outside (eta) and inside (1/eta)");
    cmd->add_option("--walks", o->walks, "random walks per direction")->capture_default_str();
    cmd->add_option("--lobe-directions", o->lobe_directions,
                    "directions wi of each lobe's L1 distance from the walk's (0: albedo only)")
        ->capture_default_str();
    cmd->add_option("--lobe-walks", o->lobe_walks, "walks per direction wi of the lobe distance")->capture_default_str();
    add_format_option(cmd, o->format, {"table", "json", "csv"});
    cmd->add_option("-o,--output", o->output, "write to FILE instead of standard output");
    cmd->add_option("--plot", o->plot, "draw each scheme's difference from the walk against mu into FILE.png or .svg");
    cmd->add_option("--furnace", o->furnace,
                    "draw the furnace picture into FILE.png or .svg: per alpha, spheres of single scattering, each "
                    "scheme and the walk under a white environment");
    cmd->add_option("--furnace-nodes", o->furnace_nodes, "mu values of the furnace spheres' E (the walk: --walks each)")
        ->capture_default_str();
    cmd->add_option("--furnace-pixels", o->furnace_pixels, "furnace sphere diameter in pixels")->capture_default_str();
}

}  // namespace brdfbake

// `brdfbake compensation`: how far the energy-compensation schemes of real-time renderers are from
// the multiple-scattering Smith microsurface they approximate (issue 35 item 3). Each scheme is
// built from brdfbake's own integrals of the single-scattering height-correlated lobe (E(mu) with
// F = 1, E_F(mu) with Schlick's F, and their cosine-weighted average Eavg, tables/mu_average.h) and
// compared, per alpha and mu, with the random walk of Heitz, Hanika, d'Eon and Dachsbacher 2016
// (brdf/random_walk.h) under the same Schlick term at every bounce: the difference in albedo, with
// the walk's error estimate plus the integrals'.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/analytic.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "cli/cli.h"
#include "integrate/random_walk.h"
#include "models/key_reader.h"
#include "plot/plot.h"
#include "tables/mu_average.h"

namespace brdfbake {
namespace {

/// What a scheme is built from, at one alpha and mu.
struct SchemeInputs {
    double e;     // E(mu): the single-scattering albedo with F = 1
    double e_f;   // E_F(mu): the same with Schlick's F(f0) at the microfacet
    double e_avg; // Eavg = 2 int E(mu) mu dmu
    double f0;    // Schlick's normal reflectance
    double f_avg; // Favg = 2 int F(mu) mu dmu = f0 + (1 - f0)/21 for Schlick [KC17]
};

/// A compensation scheme: its name, its source, and the compensated albedo it predicts.
struct Scheme {
    const char* name;
    const char* source;
    double (*albedo)(const SchemeInputs&);
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
         }},
        // [FA19] Fdez-Aguera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-based
        // Lighting": Ess = A + B, FssEss = F0 A + B (the split sum), Ems = 1 - Ess,
        // Fms = FssEss Favg / (1 - Ems Favg); albedo FssEss + Fms Ems.
        {"fdez-aguera", "Fdez-Aguera 2019 (split-sum multiple scattering)",
         [](const SchemeInputs& x) {
             const double ems = 1.0 - x.e;
             return x.e_f + ems * x.e_f * x.f_avg / (1.0 - ems * x.f_avg);
         }},
        // [T19] Turquin 2019, "Practical multiple scattering compensation for microfacet models":
        // the single-scattering lobe scaled by 1 + F0 (1/E(mu_o) - 1).
        {"turquin", "Turquin 2019 (1 + F0 (1/E - 1))",
         [](const SchemeInputs& x) { return x.e_f * (1.0 + x.f0 * (1.0 / x.e - 1.0)); }},
    };
    return s;
}

struct CompensationOptions {
    std::string scheme = "all";
    std::string model = "ggx";
    std::string alpha = "0.1,0.25,0.5,0.75,1";
    std::string mu = "0.1,0.3,0.5,0.7,1";
    double f0 = 0.5;
    std::int64_t walks = std::int64_t(1) << 18;
    std::string format = "table";
    std::string output;
    std::string plot;
};

/// One (alpha, mu) row: the walk, the single-scattering terms and each scheme's albedo.
struct Row {
    double alpha, mu;
    AlbedoValue walk;
    SchemeInputs in;
    double input_error;  // the integrals' error, carried into every scheme's
    std::vector<double> scheme;
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
        for (size_t k = 0; k < mus.size(); ++k) {
            Row r{a, mus[k], walk.values[k].energy, {e[k].value, e_f[k].value, avg.value[0], o.f0, o.f0 + (1 - o.f0) / 21},
                  e[k].error + e_f[k].error + avg.error[0], {}};
            for (const Scheme& s : schemes()) r.scheme.push_back(s.albedo(r.in));
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
    }
    out << (csv ? "alpha,mu,walk,walk_error,single" : "   alpha      mu       walk      error     single");
    for (size_t s : picked) out << (csv ? "," : " ") << all[s].name << (csv ? "_difference" : "");
    out << (csv ? ",error\n" : "      error\n");
    char cell[96];
    for (const Row& r : rows) {
        std::snprintf(cell, sizeof cell, csv ? "%.17g,%.17g,%.17g,%.3e,%.17g" : "%8.4f %7.4f %10.6f %10.2e %10.6f",
                      r.alpha, r.mu, r.walk.value, r.walk.error, r.in.e_f);
        out << cell;
        for (size_t s : picked) {
            if (csv)
                std::snprintf(cell, sizeof cell, ",%.17g", r.scheme[s] - r.walk.value);
            else
                std::snprintf(cell, sizeof cell, " %*.6f", int(std::strlen(all[s].name)), r.scheme[s] - r.walk.value);
            out << cell;
        }
        std::snprintf(cell, sizeof cell, csv ? ",%.3e\n" : " %10.2e\n", r.walk.error + r.input_error);
        out << cell;
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
        PlotSpec p;
        p.title = std::string(schemes()[s].name) + " - walk";
        p.x.label = "\\mu = cos \\theta_o";
        p.y.label = "albedo difference";
        p.x.lo = 0.0;
        p.x.hi = 1.0;
        std::vector<Curve> by_alpha;
        for (const Row& r : rows) {
            if (by_alpha.empty() || by_alpha.back().label != "\\alpha = " + format_number(r.alpha))
                by_alpha.push_back(Curve{"\\alpha = " + format_number(r.alpha), {}, {}, ""});
            by_alpha.back().x.push_back(r.mu);
            by_alpha.back().y.push_back(r.scheme[s] - r.walk.value);
        }
        p.curves = by_alpha;
        p.lines.push_back(RefLine{'y', 0.0, ""});
        fig.panels.push_back(p);
    }
    fig.caption = "random walk (Heitz et al. 2016) against each scheme, " + o.model + ", Schlick f_0 = " +
                  format_number(o.f0) + " at every bounce";
    write_figure(path, fig);
}

int run_compensation(const CompensationOptions& o, const GlobalOptions& g) {
    const Format format = parse_format(o.format);
    check_text_output(o.output);
    check_plot_output(o.plot, "--plot");
    std::vector<size_t> picked;
    std::string names;
    for (size_t s = 0; s < schemes().size(); ++s) {
        names += std::string(names.empty() ? "" : ", ") + schemes()[s].name;
        if (o.scheme == "all" || o.scheme == schemes()[s].name) picked.push_back(s);
    }
    if (picked.empty()) throw Error("--scheme: unknown scheme '" + o.scheme + "'; known: all, " + names);
    if (o.model != "ggx" && o.model != "beckmann")
        throw Error("--model: '" + o.model + "' is not a distribution of the random walk; use ggx or beckmann");
    if (!(o.f0 >= 0.0 && o.f0 <= 1.0)) throw Error("--f0: " + format_number(o.f0) + " must lie in [0, 1]");
    if (o.walks < 16) throw Error("--walks must be at least 16");
    const std::vector<double> alphas = parse_number_list(o.alpha, "--alpha");
    const std::vector<double> mus = parse_number_list(o.mu, "--mu");
    for (double mu : mus)
        if (!(mu > 0.0 && mu <= 1.0)) throw Error("--mu: " + format_number(mu) + " must lie in (0, 1]");
    for (double a : alphas) resolve_model(o.model + ":alpha=" + format_number(a));  // its range, before the device
    Engine engine(g.device, g.verbose);
    const std::vector<Row> rows = compute(engine, o, alphas, mus);
    if (!o.plot.empty()) plot_rows(o.plot, o, picked, rows);
    emit(o.output, render(o, picked, rows, format));
    return kExitOk;
}

}  // namespace

void add_compensation_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<CompensationOptions>(
        app, "compensation",
        "multiple-scattering compensation schemes (Kulla-Conty, Fdez-Aguera, Turquin) against the random walk",
        global, action, run_compensation);
    cmd->add_option("--scheme", o->scheme, "kulla-conty, fdez-aguera, turquin or all")->capture_default_str();
    cmd->add_option("--model", o->model, "the distribution: ggx or beckmann (height-correlated)")->capture_default_str();
    cmd->add_option("--alpha", o->alpha, "comma-separated alpha values")->capture_default_str();
    cmd->add_option("--mu", o->mu, "comma-separated cos(theta_o) values in (0, 1]")->capture_default_str();
    cmd->add_option("--f0", o->f0, "Schlick's normal reflectance at every bounce")->capture_default_str();
    cmd->add_option("--walks", o->walks, "random walks per direction")->capture_default_str();
    add_format_option(cmd, o->format, {"table", "json", "csv"});
    cmd->add_option("-o,--output", o->output, "write to FILE instead of standard output");
    cmd->add_option("--plot", o->plot, "draw each scheme's difference from the walk against mu into FILE.png or .svg");
}

}  // namespace brdfbake

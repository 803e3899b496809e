// `brdfbake compensation --eta E`: the energy-compensation schemes of rough glass against the
// multiple-scattering rough dielectric of Heitz, Hanika, d'Eon and Dachsbacher 2016 (the walk of
// brdf/random_walk.h with eta=), from outside (relative index eta) and from inside (1/eta), per
// alpha and mu. Each scheme is built from brdfbake's own integrals of the single-scattering
// height-correlated GGX interface (compute_dielectric: R(mu) and T(mu), Heitz 2014 eq. 99 and
// 100; E = R + T and Eavg = 2 int E mu dmu from both sides, tables/mu_average.h, as the
// dielectric-eavg table integrates them) and the average Fresnel reflectance Favg = 2 int F mu dmu
// of the exact unpolarised interface from both sides. Compared: R, T and R + T with the walk's
// errors, and the reflection and transmission lobes' L1 distances from the walk's (walk_eval; f_t
// with wi below since walk9).
#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/random_walk.h"
#include "brdfbake/error.h"
#include "cli/cli.h"
#include "cli/compensation.h"
#include "cli/furnace_sphere.h"
#include "integrate/random_walk.h"
#include "models/key_reader.h"
#include "tables/mu_average.h"

namespace brdfbake {
namespace {

/// What a dielectric scheme is built from, at one alpha, side and mu.
struct GlassInputs {
    double r, t;   // single scattering: R(mu) and T(mu) of the height-correlated interface on this side
    double e_avg;  // Eavg of this side: 2 int (R + T) mu dmu
    double tau;    // [KC17]'s share of the lost energy this side transmits (glass_split)
    double e_avg_far;  // Eavg of the other side (where the transmitted lobe leaves)
};

/// A dielectric compensation scheme: its name and source, the compensated R and T it predicts at mu
/// and its reflection lobe at (wo, wi) from the single-scattering reflection f_ss and E(mu_i).
struct GlassScheme {
    const char* name;
    const char* source;
    std::array<double, 2> (*albedo)(const GlassInputs&);
    double (*reflection)(const GlassInputs&, double f_ss, double e_i);
    /// its transmission lobe at (wo, wi below) from the single-scattering f_t and E(|mu_i|) of wi's side
    double (*transmission)(const GlassInputs&, double ft_ss, double e_far_i);
};

double e_of(const GlassInputs& x) { return x.r + x.t; }

/// The registry of dielectric schemes (one row each). Fdez-Aguera 2019 (the split sum) is not one:
/// it compensates a reflection and defines no transmission.
const std::vector<GlassScheme>& glass_schemes() {
    static const std::vector<GlassScheme> s = {
        // [KC17] Kulla and Conty 2017, "Revisiting Physically Based Shading at Imageworks", section
        // "Dielectrics": E and Eavg of the whole BSDF (R + T) from both sides; the lost energy
        // 1 - E(mu_o) is put back by the lobe (1 - E(mu_o))(1 - E'(mu_i)) / (pi (1 - Eavg')), E' and
        // Eavg' those of the side wi lies on, split between reflection (1 - tau) and transmission
        // (tau). R + T = E + (1 - E) = 1 at every mu: exact for a non-absorbing interface.
        {"kulla-conty", "Kulla and Conty 2017 (E, Eavg from both sides, the split by Favg)",
         [](const GlassInputs& x) {
             const double lost = 1.0 - e_of(x);
             return std::array<double, 2>{x.r + lost * (1.0 - x.tau), x.t + lost * x.tau};
         },
         [](const GlassInputs& x, double f_ss, double e_i) {
             return f_ss + (1.0 - e_of(x)) * (1.0 - e_i) / (M_PI * (1.0 - x.e_avg)) * (1.0 - x.tau);
         },
         [](const GlassInputs& x, double ft_ss, double e_i) {
             return ft_ss + (1.0 - e_of(x)) * (1.0 - e_i) / (M_PI * (1.0 - x.e_avg_far)) * x.tau;
         }},
        // [T19] Turquin 2019, "Practical multiple scattering compensation for microfacet models",
        // the dielectric: the whole single-scattering BSDF (reflection and transmission) scaled by
        // 1 / E(mu_o), E = R + T: R + T = 1 at every mu, exact for a non-absorbing interface.
        {"turquin", "Turquin 2019 (the BSDF times 1/E, E = R + T)",
         [](const GlassInputs& x) {
             return std::array<double, 2>{x.r / e_of(x), x.t / e_of(x)};
         },
         [](const GlassInputs& x, double f_ss, double) { return f_ss / e_of(x); },
         [](const GlassInputs& x, double ft_ss, double) { return ft_ss / e_of(x); }},
    };
    return s;
}

/// Favg = 2 int_0^1 F(mu) mu dmu of the exact unpolarised interface of relative index eta
/// (fresnel.h), Gauss-Kronrod on each side of the critical angle (total reflection below it, eta < 1).
double fresnel_average(double eta) {
    const auto g = [eta](double mu) { return 2.0 * mu * double(bb_fresnel_dielectric(mu, eta)); };
    using gk = boost::math::quadrature::gauss_kronrod<double, 61>;
    const double mu_c = eta < 1.0 ? std::sqrt(1.0 - eta * eta) : 0.0;
    return (mu_c > 0.0 ? gk::integrate(g, 0.0, mu_c, 15, 1e-13) : 0.0) + gk::integrate(g, mu_c, 1.0, 15, 1e-13);
}

/// [KC17] "Dielectrics": the lost energy is reflected and transmitted in the shares 1 - tau and tau;
/// from outside tau = (1 - Favg) x, from inside tau' = (1 - Favg') (1 - x), and x balances the
/// energy the two lobes carry through the interface the way it crosses a smooth one (the
/// cosine-weighted transmittance from inside is that from outside over eta^2):
/// (1 - Eavg) (1 - Favg) x / eta^2 = (1 - Eavg') (1 - Favg') (1 - x),
/// x = t / (1 + t), t = eta^2 (1 - Eavg') (1 - Favg') / ((1 - Eavg) (1 - Favg)). Returns {tau, tau'}.
std::array<double, 2> glass_split(double eta, const std::array<double, 2>& e_avg, const std::array<double, 2>& f_avg) {
    const double lost_out = std::max(1.0 - e_avg[0], 1e-300), lost_in = std::max(1.0 - e_avg[1], 1e-300);
    const double t = eta * eta * lost_in * (1.0 - f_avg[1]) / (lost_out * (1.0 - f_avg[0]));
    const double x = t / (1.0 + t);
    return {(1.0 - f_avg[0]) * x, (1.0 - f_avg[1]) * (1.0 - x)};
}

/// One (alpha, side, mu) row.
struct GlassRow {
    double alpha, mu;
    int side;    // 0: lit from outside (eta), 1: from inside (1/eta)
    double eta;  // this side's relative index
    WalkAlbedo walk;
    GlassInputs in;
    double f_avg;
    double input_error;                         // the integrals' error (R's, T's and Eavg's)
    std::vector<std::array<double, 2>> scheme;  // per scheme: R, T
    std::vector<double> lobe_l1;                // per scheme: integral of |f_R,scheme - f_R,walk| cos over wi
    double l1_error = 0.0, l1_noise = 0.0;
    std::vector<double> lobe_l1_t{};  // per scheme: integral of |f_T,scheme - f_T,walk| |cos| over wi below (walk9)
    double l1_t_error = 0.0, l1_t_noise = 0.0;
};

const char* side_name(int side) { return side == 0 ? "outside" : "inside"; }

/// The walk's parameters seen from `side`: 1/eta from inside, 1/eta - 1 = -(eta - 1)/eta.
ParamBlock side_params(const ModelConfig& walk, int side) {
    ParamBlock p = walk.params;
    if (side == 1) {
        p[BB_SMITH_WALK_ETA] = 1.0 / walk.params[BB_SMITH_WALK_ETA];
        p[BB_SMITH_WALK_ETA_M1] = -walk.params[BB_SMITH_WALK_ETA_M1] / walk.params[BB_SMITH_WALK_ETA];
    }
    return p;
}

/// R(mu) and T(mu) of the single-scattering interface at alpha for each (side, mu), side-major, to
/// `tolerance` (quadrature first, then importance sampling where the rule cannot certify it).
DielectricResult single_glass(Engine& engine, double alpha, double eta, const std::vector<double>& mus,
                              double tolerance) {
    DielectricRequest req;
    req.precision = Precision::Double;
    for (int side = 0; side < 2; ++side)
        for (double mu : mus) req.cells.push_back({mu, alpha, side == 0 ? eta : 1.0 / eta});
    ToleranceRequest tol;
    tol.tolerance = tolerance;
    return compute_dielectric_to_tolerance(engine, req, tol);
}

/// Each scheme's L1 distance of its reflection (or `transmission`) lobe from the walk's (w) over n
/// draws, those that gave a direction of |cos| z[k] with density p[k] (0: one that counts 0), E(|mu_i|) of wi's side
/// from e_grid: the mean of |f_scheme - f_walk| z / p into l1, the largest of its 3 standard errors
/// into error, what the walk's noise alone adds into noise.
void lobe_l1(const WalkEvalResult& w, int n, const std::vector<double>& z, const std::vector<double>& p,
             const GlassInputs& in, const std::vector<AlbedoValue>& e_grid, bool transmission, std::vector<double>& l1,
             double& error, double& noise) {
    const auto& all = glass_schemes();
    std::vector<double> sum(all.size(), 0.0), sum2(all.size(), 0.0);
    double walk_noise = 0.0;
    for (size_t k = 0; k < z.size(); ++k) {
        if (!(p[k] > 0.0)) continue;  // a refraction draw past the critical angle: 0
        // The walk's first order is the single-scattering lobe in closed form (random_walk.h).
        for (size_t s = 0; s < all.size(); ++s) {
            const double f = transmission ? all[s].transmission(in, w.single[k].value, e_at(e_grid, z[k]))
                                          : all[s].reflection(in, w.single[k].value, e_at(e_grid, z[k]));
            const double d = std::fabs(f - w.f[k].value) * z[k] / p[k];
            sum[s] += d;
            sum2[s] += d * d;
        }
        walk_noise += w.f[k].error / 3.0 * std::sqrt(2.0 / M_PI) * z[k] / p[k];
    }
    for (size_t s = 0; s < all.size(); ++s) {
        const double mean = sum[s] / n;
        l1.push_back(mean);
        error = std::max(error, 3.0 * std::sqrt(std::max(0.0, sum2[s] / n - mean * mean) / (n - 1)));
    }
    noise = walk_noise / n;
}

/// The reflection lobe's L1 distance from the walk's of each scheme at row r (directions as the
/// conductor's: lobe_directions), E(mu_i) of r's side from `e_grid`.
void glass_lobe_distance(Engine& engine, const CompensationOptions& o, const ModelConfig& single,
                         const ModelConfig& walk, const std::vector<AlbedoValue>& e_grid, GlassRow& r) {
    const int n = o.lobe_directions;
    const LobeDirections dirs = lobe_directions(engine, single, r.alpha, r.mu, n, std::uint64_t(r.side));
    WalkEvalRequest req;
    req.model = walk.id;
    req.fresnel = resolve_fresnel("none");  // the walk's own exact dielectric F
    req.samples = std::uint64_t(o.lobe_walks);
    req.precision = Precision::Double;
    for (const Vec3& wi : dirs.wi) req.pairs.push_back({dirs.wo, wi, side_params(walk, r.side)});
    const WalkEvalResult w = walk_eval(engine, req);
    std::vector<double> z;
    for (const Vec3& wi : dirs.wi) z.push_back(wi[2]);
    lobe_l1(w, n, z, dirs.density, r.in, e_grid, false, r.lobe_l1, r.l1_error, r.l1_noise);
}

/// The transmission lobe's L1 distance from the walk's f_t (walk_eval with wi below) of each scheme
/// at row r: n directions below (a fixed seed per row) from a one-sample mixture [Veach 1997 ch. 9]:
/// half cosine-distributed (|mu_i| / pi), half a visible normal of wo refracted (density the
/// refraction phase function, bb_walk_refract_phase: single scattering's lobe; a draw past the
/// critical angle counts 0); E(|mu_i|) of the other side from `e_far`.
void glass_transmission_distance(Engine& engine, const CompensationOptions& o, const ModelConfig& walk,
                                 const std::vector<AlbedoValue>& e_far, GlassRow& r) {
    const int n = o.lobe_directions;
    std::mt19937_64 rng(0x74726e73u + std::uint64_t(r.side) + 2 * std::uint64_t(std::llround(r.mu * 1e6)));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    WalkEvalRequest req;
    req.model = walk.id;
    req.fresnel = resolve_fresnel("none");
    req.samples = std::uint64_t(o.lobe_walks);
    req.precision = Precision::Double;
    const Vec3 wo{std::sqrt(1.0 - r.mu * r.mu), 0.0, r.mu};
    const ParamBlock params = side_params(walk, r.side);
    const int dist = o.model == "beckmann" ? BB_SMITH_BECKMANN : BB_SMITH_GGX;
    const bb_vec3 v = bb_v3(wo[0], wo[1], wo[2]);
    std::vector<double> density;  // the mixture's density of each direction (0: a failed draw)
    for (int k = 0; k < n; ++k) {
        const double u0 = u(rng), u1 = u(rng), u2 = u(rng);
        bb_vec3 d;
        if (u0 < 0.5) {
            const double z = std::sqrt(u1), p = 2.0 * M_PI * u2, sz = std::sqrt(1.0 - z * z);
            d = bb_v3(sz * std::cos(p), sz * std::sin(p), -z);
        } else {
            const bb_vec3 m = bb_walk_sample_vndf(dist, v, r.alpha, r.alpha, u1, u2);
            d = bb_refract(v, m, bb_clamp_cos(bb_dot(v, m)), params[BB_SMITH_WALK_ETA]);
        }
        double vh = 0.0;
        const bool ok = bb_dot(d, d) > 0.5 && d.z < 0.0;
        const double pr = ok ? bb_walk_refract_phase(dist, v, d, params[BB_SMITH_WALK_ETA], r.alpha, r.alpha, &vh) : 0.0;
        density.push_back(ok ? 0.5 * -d.z / M_PI + 0.5 * pr : 0.0);
        if (!ok) d = bb_v3(0.0, 0.0, -1.0);  // walked, not counted
        req.pairs.push_back({wo, {d.x, d.y, d.z}, params});
    }
    const WalkEvalResult w = walk_eval(engine, req);
    std::vector<double> z;
    for (const WalkEvalPair& q : req.pairs) z.push_back(-q.wi[2]);
    lobe_l1(w, n, z, density, r.in, e_far, true, r.lobe_l1_t, r.l1_t_error, r.l1_t_noise);
}

/// Eavg of both sides at alpha (2 integrals: outside, inside), R + T's error the sum of theirs.
tables::MuAverage glass_average(Engine& engine, double alpha, double eta) {
    return tables::average_over_mu(2, 1e-4, [&](const std::vector<double>& nodes) {
        const DielectricResult d = single_glass(engine, alpha, eta, nodes, 2.5e-5);
        tables::MuSamples s;
        for (size_t c = 0; c < d.reflected.size(); ++c)
            s.values.push_back(
                {d.reflected[c].value + d.transmitted[c].value, d.reflected[c].error + d.transmitted[c].error});
        return s;
    });
}

std::vector<GlassRow> compute_glass(Engine& engine, const CompensationOptions& o, const std::vector<double>& alphas,
                                    const std::vector<double>& mus) {
    const std::array<double, 2> f_avg{fresnel_average(o.eta), fresnel_average(1.0 / o.eta)};
    std::vector<GlassRow> rows;
    for (double a : alphas) {
        const std::string spec = o.model + ":alpha=" + format_number(a);
        const ModelConfig single = resolve_model(spec);
        const ModelConfig walk_model =
            resolve_model_simulated(spec + ",scattering=multiple,eta=" + format_number(o.eta));
        const DielectricResult ss = single_glass(engine, a, o.eta, mus, 1e-5);
        const tables::MuAverage avg = glass_average(engine, a, o.eta);
        const std::array<double, 2> tau = glass_split(o.eta, {avg.value[0], avg.value[1]}, f_avg);
        AlbedoRequest req;
        req.model = walk_model.id;
        req.fresnel = resolve_fresnel("none");
        req.samples = std::uint64_t(o.walks);
        for (int side = 0; side < 2; ++side)
            for (AlbedoCell c : cells_for(mus, 0.0, walk_model.params)) {
                c.params = side_params(walk_model, side);
                req.cells.push_back(c);
            }
        const WalkResult walk = walk_albedo(engine, req);
        DielectricResult grid;
        if (o.lobe_directions > 0) grid = single_glass(engine, a, o.eta, e_grid_nodes(), 1e-4);
        std::array<std::vector<AlbedoValue>, 2> e_grids;
        for (int side = 0; side < 2; ++side)
            for (int k = 0; k < kEGrid && o.lobe_directions > 0; ++k)
                e_grids[size_t(side)].push_back(
                    {grid.reflected[side * kEGrid + k].value + grid.transmitted[side * kEGrid + k].value, 0.0});
        for (int side = 0; side < 2; ++side) {
            const std::vector<AlbedoValue>& e_grid = e_grids[size_t(side)];
            for (size_t k = 0; k < mus.size(); ++k) {
                const size_t c = side * mus.size() + k;
                GlassRow r{a,
                           mus[k],
                           side,
                           side == 0 ? o.eta : 1.0 / o.eta,
                           walk.values[c],
                           {ss.reflected[c].value, ss.transmitted[c].value, avg.value[side], tau[side],
                            avg.value[1 - side]},
                           f_avg[side],
                           ss.reflected[c].error + ss.transmitted[c].error + avg.error[side],
                           {},
                           {}};
                for (const GlassScheme& s : glass_schemes()) r.scheme.push_back(s.albedo(r.in));
                if (o.lobe_directions > 0) glass_lobe_distance(engine, o, single, walk_model, e_grid, r);
                if (o.lobe_directions > 0)
                    glass_transmission_distance(engine, o, walk_model, e_grids[size_t(1 - side)], r);
                rows.push_back(r);
            }
        }
    }
    return rows;
}

nlohmann::json glass_json(const CompensationOptions& o, const std::vector<size_t>& picked,
                          const std::vector<GlassRow>& rows) {
    const auto& all = glass_schemes();
    nlohmann::json j;
    j["command"] = "compensation";
    j["model"] = o.model;
    j["eta"] = o.eta;
    j["walks"] = o.walks;
    j["results"] = nlohmann::json::array();
    for (const GlassRow& r : rows) {
        nlohmann::json e = {{"alpha", r.alpha},
                            {"side", side_name(r.side)},
                            {"eta", r.eta},
                            {"mu", r.mu},
                            {"walk_R", r.walk.energy.value},
                            {"walk_R_error", r.walk.energy.error},
                            {"walk_T", r.walk.transmitted.value},
                            {"walk_T_error", r.walk.transmitted.error},
                            {"walk_sum", r.walk.total.value},
                            {"walk_sum_error", r.walk.total.error},
                            {"walk_cutoff", r.walk.cutoff.value},
                            {"single_R", r.in.r},
                            {"single_T", r.in.t},
                            {"e_avg", r.in.e_avg},
                            {"f_avg", r.f_avg},
                            {"input_error", r.input_error},
                            {"kulla_conty_transmitted_share", r.in.tau}};
        for (size_t s : picked) {
            const std::string n = all[s].name;
            e[n + "_R"] = r.scheme[s][0];
            e[n + "_T"] = r.scheme[s][1];
            e[n + "_R_difference"] = r.scheme[s][0] - r.walk.energy.value;
            e[n + "_T_difference"] = r.scheme[s][1] - r.walk.transmitted.value;
            e[n + "_sum_difference"] = r.scheme[s][0] + r.scheme[s][1] - r.walk.total.value;
            if (!r.lobe_l1.empty()) e[n + "_reflection_l1"] = r.lobe_l1[s];
            if (!r.lobe_l1_t.empty()) e[n + "_transmission_l1"] = r.lobe_l1_t[s];
        }
        if (!r.lobe_l1.empty()) {
            e["lobe_l1_error"] = r.l1_error;
            e["lobe_l1_noise"] = r.l1_noise;
            e["transmission_l1_error"] = r.l1_t_error;
            e["transmission_l1_noise"] = r.l1_t_noise;
        }
        j["results"].push_back(e);
    }
    return j;
}

std::string glass_header(const CompensationOptions& o, const std::vector<size_t>& picked) {
    std::ostringstream out;
    out << "# rough dielectric compensation against the random walk (Heitz et al. 2016), " << o.model
        << ", eta = " << format_number(o.eta) << " (outside; inside 1/eta), " << o.walks << " walks per direction\n"
        << "# walk: R and T of the multiple-scattering interface (err: 3 standard errors of each; of R + T: "
           "sum_err); single: the height-correlated interface's; per scheme its R, T and R + T minus the walk's "
           "(in_err: the integrals' error)\n";
    for (size_t s : picked) out << "# " << glass_schemes()[s].name << ": " << glass_schemes()[s].source << "\n";
    if (o.lobe_directions > 0)
        out << "# l1 (per scheme): integral of |f_R,scheme - f_R,walk| cos over wi of the reflection lobe, "
            << o.lobe_directions << " directions x " << o.lobe_walks
            << " walks; l1_err: 3 standard errors; noise: what the walk's noise alone adds\n"
            << "# t_l1 (per scheme): the same of the transmission lobe, |f_T,scheme - f_T,walk| |cos| over wi below "
               "(half cosine-distributed directions, half refracted by single scattering); t_l1_err, t_noise as "
               "above\n";
    return out.str();
}

std::string render_glass(const CompensationOptions& o, const std::vector<size_t>& picked,
                         const std::vector<GlassRow>& rows, Format format) {
    if (format == Format::Json) return glass_json(o, picked, rows).dump(2) + "\n";
    const auto& all = glass_schemes();
    const bool csv = format == Format::Csv, lobe = o.lobe_directions > 0;
    std::ostringstream out;
    if (!csv) out << glass_header(o, picked);
    out << (csv ? "alpha,side,mu,walk_R,walk_T,walk_R_error,walk_T_error,walk_sum_error,single_R,single_T"
                : "  alpha    side     mu     walk_R     walk_T      R_err      T_err    sum_err   single_R   "
                  "single_T");
    for (size_t s : picked)
        for (const char* q : {"_R", "_T", "_sum"})
            out << (csv ? "," : " ") << all[s].name << q << (csv ? "_difference" : "");
    out << (csv ? ",input_error" : "     in_err");
    if (lobe) {
        for (size_t s : picked) out << (csv ? "," : " ") << all[s].name << "_l1";
        out << (csv ? ",l1_error,l1_noise" : "     l1_err      noise");
        for (size_t s : picked) out << (csv ? "," : " ") << all[s].name << "_t_l1";
        out << (csv ? ",t_l1_error,t_l1_noise" : "   t_l1_err    t_noise");
    }
    out << "\n";
    char cell[160];
    for (const GlassRow& r : rows) {
        std::snprintf(cell, sizeof cell,
                      csv ? "%.17g,%s,%.17g,%.17g,%.17g,%.3e,%.3e,%.3e,%.17g,%.17g"
                          : "%7.4f %7s %6.4f %10.6f %10.6f %10.2e %10.2e %10.2e %10.6f %10.6f",
                      r.alpha, side_name(r.side), r.mu, r.walk.energy.value, r.walk.transmitted.value,
                      r.walk.energy.error, r.walk.transmitted.error, r.walk.total.error, r.in.r, r.in.t);
        out << cell;
        std::vector<std::string> names, names_t;
        std::vector<double> l1, l1_t;
        for (size_t s : picked) {
            const double d[3] = {r.scheme[s][0] - r.walk.energy.value, r.scheme[s][1] - r.walk.transmitted.value,
                                 r.scheme[s][0] + r.scheme[s][1] - r.walk.total.value};
            const int n = int(std::strlen(all[s].name));
            for (int q = 0; q < 3; ++q) out << number_cell(csv, d[q], n + (q == 2 ? 4 : 2), 6);
            names.push_back(all[s].name);
            names_t.push_back(std::string(all[s].name) + "_t");
            if (lobe) l1.push_back(r.lobe_l1[s]);
            if (lobe) l1_t.push_back(r.lobe_l1_t[s]);
        }
        std::snprintf(cell, sizeof cell, csv ? ",%.3e" : " %10.2e", r.input_error);
        out << cell;
        if (lobe) out << lobe_cells(csv, names, l1, r.l1_error, r.l1_noise);
        if (lobe) out << lobe_cells(csv, names_t, l1_t, r.l1_t_error, r.l1_t_noise);
        out << "\n";
    }
    return out.str();
}

/// `--plot`: per scheme and side, its R minus the walk's against mu (its T's is the negative, both
/// sums being 1), one curve per alpha; with lobes, rows of the reflection's and the transmission's
/// lobe L1 distances.
void plot_glass(const std::string& path, const CompensationOptions& o, const std::vector<size_t>& picked,
                const std::vector<GlassRow>& rows) {
    Figure fig;
    fig.panel_width = 640;
    fig.panel_height = 480;
    // Rows: R's difference; with lobes, the reflection's and the transmission's L1 distances.
    for (int row = 0; row < (o.lobe_directions > 0 ? 3 : 1); ++row)
        for (size_t s : picked)
            for (int side = 0; side < 2; ++side) {
                std::vector<MuPoint> points;
                for (const GlassRow& r : rows)
                    if (r.side == side)
                        points.push_back({r.alpha, r.mu,
                                          row == 0   ? r.scheme[s][0] - r.walk.energy.value
                                          : row == 1 ? r.lobe_l1[s]
                                                     : r.lobe_l1_t[s]});
                const std::string title = std::string(glass_schemes()[s].name) + ", from " + side_name(side);
                fig.panels.push_back(
                    row == 0   ? mu_panel(title + ": R - R_{walk}", "reflectance difference", points, true)
                    : row == 1 ? mu_panel(title + ": reflection lobe's L1 distance from the walk's",
                                          "\\int |f_R - f_{R,walk}| cos \\theta_i d\\omega_i", points, false)
                               : mu_panel(title + ": transmission lobe's L1 distance from the walk's",
                                          "\\int |f_T - f_{T,walk}| |cos \\theta_i| d\\omega_i", points, false));
            }
    fig.columns = int(2 * picked.size());
    fig.caption = "rough dielectric " + o.model + ", \\eta = " + format_number(o.eta) +
                  ": random walk (Heitz et al. 2016) against each scheme, from outside (\\eta) and inside (1/\\eta)";
    write_figure(path, fig);
}

/// `--furnace FILE`: per alpha and side a row of spheres under a white environment, each pixel
/// R + T at n.v: single scattering, each scheme and the walk; returns the walk's largest error.
double furnace_glass(Engine& engine, const CompensationOptions& o, const std::vector<size_t>& picked,
                     const std::vector<double>& alphas) {
    CompensationOptions albedo_only = o;
    albedo_only.lobe_directions = 0;
    const std::vector<double> mus = furnace_nodes(o.furnace_nodes);
    const std::vector<GlassRow> rows = compute_glass(engine, albedo_only, alphas, mus);
    Figure fig = furnace_figure(o.furnace_pixels);
    fig.columns = int(picked.size()) + 2;
    double worst = 0.0;
    for (size_t first = 0; first < rows.size(); first += mus.size()) {  // one (alpha, side) a row
        std::vector<std::vector<double>> e(picked.size() + 2);
        for (size_t k = first; k < first + mus.size(); ++k) {
            e.front().push_back(rows[k].in.r + rows[k].in.t);
            for (size_t s = 0; s < picked.size(); ++s)
                e[s + 1].push_back(rows[k].scheme[picked[s]][0] + rows[k].scheme[picked[s]][1]);
            e.back().push_back(rows[k].walk.total.value);
            worst = std::max(worst, rows[k].walk.total.error);
        }
        const std::string row =
            "\\alpha = " + format_number(rows[first].alpha) + ", " + side_name(rows[first].side) + ": ";
        fig.panels.push_back(furnace_sphere(row + "single", e.front(), o.furnace_pixels));
        for (size_t s = 0; s < picked.size(); ++s)
            fig.panels.push_back(furnace_sphere(row + glass_schemes()[picked[s]].name, e[s + 1], o.furnace_pixels));
        fig.panels.push_back(furnace_sphere(row + "walk", e.back(), o.furnace_pixels));
    }
    fig.caption = "white furnace of the rough dielectric " + o.model + ", \\eta = " + format_number(o.eta) +
                  ": R + T from outside and inside, single scattering, each scheme, the random walk";
    write_figure(o.furnace, fig);
    return worst;
}

std::vector<size_t> picked_glass_schemes(const std::string& scheme) {
    std::vector<size_t> picked;
    std::string names;
    for (size_t s = 0; s < glass_schemes().size(); ++s) {
        names += std::string(names.empty() ? "" : ", ") + glass_schemes()[s].name;
        if (scheme == "all" || scheme == glass_schemes()[s].name) picked.push_back(s);
    }
    if (picked.empty())
        throw Error(
            "--scheme '" + scheme + "' with --eta: the rough dielectric's schemes are all, " + names +
            (scheme == "fdez-aguera" ? " (the split sum compensates a reflection and defines no transmission)" : ""));
    return picked;
}

}  // namespace

void check_dielectric_compensation(const CompensationOptions& o, bool f0_given) {
    if (!(o.eta > 1.0 && o.eta <= 4.0))
        throw Error("--eta: " + format_number(o.eta) +
                    " must lie in (1, 4]: the glass's index relative to the outside (the inside is seen as 1/eta)");
    if (o.model != "ggx")
        throw Error("--model '" + o.model +
                    "' with --eta: the rough dielectric is compared for ggx only "
                    "(brdfbake's single-scattering dielectric integrals are GGX's)");
    if (f0_given) throw Error("--f0 with --eta: the rough dielectric's Fresnel term is the interface's own (eta)");
    picked_glass_schemes(o.scheme);
}

void run_dielectric_compensation(Engine& engine, const CompensationOptions& o, const std::vector<double>& alphas,
                                 const std::vector<double>& mus, Format format) {
    const std::vector<size_t> picked = picked_glass_schemes(o.scheme);
    const std::vector<GlassRow> rows = compute_glass(engine, o, alphas, mus);
    if (!o.plot.empty()) plot_glass(o.plot, o, picked, rows);
    if (!o.furnace.empty()) {
        const double worst = furnace_glass(engine, o, picked, alphas);
        std::fprintf(stderr, "brdfbake: wrote %s: %zu rows of %zu spheres (the walk's error at most %.1e)\n",
                     o.furnace.c_str(), 2 * alphas.size(), picked.size() + 2, worst);
    }
    emit(o.output, render_glass(o, picked, rows, format));
}

}  // namespace brdfbake

// The directional albedo E(mu_o, alpha) and the average albedo Eavg(alpha), both with F = 1 or
// the request's Fresnel term.
#include <algorithm>
#include <cmath>
#include <functional>

#include "brdfbake/brdf/random_walk.h"
#include "brdfbake/error.h"
#include "integrate/random_walk.h"
#include "models/key_reader.h"
#include "models/merl_file.h"
#include "tables/lut_common.h"
#include "tables/mu_average.h"
#include "tables/sweep.h"

namespace brdfbake {
namespace tables {
namespace {

std::vector<std::string> albedo_program(const LutRequest& r) { return {"albedo|" + r.model + "|none"}; }

/// Whether the model is a measured table (BB_TRAIT_MEASURED): no roughness axis, its tables are
/// E(mu_o) alone, 1D, and Eavg one number.
bool without_roughness(const ModelConfig& m) { return m.traits().measured; }

/// E(mu_o) of a model without a roughness axis: a 1D table along mu (height 1).
Table albedo_table_1d(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    Table t;
    t.kind = r.kind;
    t.quantity = "directional albedo E(mu_o) = integral of f(wo, wi) cos(theta_i) dwi";
    t.x = mu_axis(r, r.width);
    t.y = make_axis("-", "-", 0.0, 1.0, 1);
    t.y.parameter = {0.5};
    std::vector<AlbedoCell> cells;
    for (double mu : t.x.parameter) cells.push_back({mu, 0.0, m.params});
    const AlbedoResult res = integrate(engine, r, m, f, cells);
    t.channels = {"E"};
    t.values.assign(1, {});
    for (const auto& v : res.values) {
        t.values[0].push_back(v.value);
        t.error.push_back(v.error);
    }
    describe(t, r, m, f.canonical, res.method, res.samples_per_cell, false);
    return t;
}

/// A table of `one` per colour for a merl spec with channel=rgb (channels E_r, E_g, E_b, the error
/// the largest of the three, the model attribute with channel=rgb); `one` of m otherwise.
Table per_colour(const LutRequest& r, const ModelConfig& m, const std::function<Table(const ModelConfig&)>& one) {
    if (!merl_rgb_spec(r.model)) return one(m);
    Table t;
    for (const char* c : {"r", "g", "b"}) {
        const Table ct = one(resolve_model(merl_channel_spec(r.model, c)));
        if (t.values.empty()) {
            t = ct;
            t.channels.clear();
            t.values.clear();
        }
        t.channels.push_back(ct.channels.front() + "_" + c);
        t.values.push_back(ct.values.front());
        for (size_t i = 0; i < t.error.size(); ++i) t.error[i] = std::max(t.error[i], ct.error[i]);
    }
    t.attributes["model"] = merl_channel_spec(t.attributes["model"], "rgb");
    return t;
}

/// The rough dielectric's walk (ggx or beckmann with scattering=multiple and eta=E, [HHdD16] sec. 5):
/// R and T lit from above (relative index eta) and from below (1/eta) on the mu x alpha grid; each
/// texel's error the largest over the four channels of the replicas' error plus the weight the
/// bounce limit cut off on that side (value and error): the energy that is in neither R nor T. (Its
/// Fresnel term is the interface's own: validation refuses --fresnel for the model.)
Table dielectric_walk_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.quantity = "rough dielectric interface by random walk: reflectance R(mu_o, alpha) and transmittance T lit "
                 "from above (relative index eta), R_below and T_below lit from below (1/eta); R + T = 1 less the "
                 "bounce limit's cut-off";
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = f;
    req.samples = r.samples;
    req.precision = r.precision;
    const double eta = m.params[BB_SMITH_WALK_ETA];
    for (int below = 0; below < 2; ++below)
        for (AlbedoCell c : g.cells) {
            if (below) {  // the same interface seen from the other side: 1/eta, 1/eta - 1 = -(eta - 1)/eta
                c.params[BB_SMITH_WALK_ETA] = 1.0 / eta;
                c.params[BB_SMITH_WALK_ETA_M1] = -m.params[BB_SMITH_WALK_ETA_M1] / eta;
            }
            req.cells.push_back(c);
        }
    const WalkResult w = walk_albedo_at(engine, req, r.tolerance, 1.0);
    const size_t n = g.cells.size();
    t.channels = {"R", "T", "R_below", "T_below"};
    t.values.assign(4, {});
    for (size_t c = 0; c < n; ++c) {
        double err = 0.0;
        for (int below = 0; below < 2; ++below) {
            const WalkAlbedo& v = w.values[below * n + c];
            t.values[2 * below].push_back(v.energy.value);
            t.values[2 * below + 1].push_back(v.transmitted.value);
            const double cut = v.cutoff.value + v.cutoff.error;
            err = std::max({err, v.energy.error + cut, v.transmitted.error + cut});
        }
        t.error.push_back(err);
    }
    describe(t, r, m, f.canonical, w.method, w.walks_per_cell, g.clamped);
    return std::move(g.table);
}

/// The colours of a request: 3 for a merl spec with channel=rgb (per_colour integrates and
/// writes each), else 1; the planner's sample count (planner.cpp, finish_table).
int colours(const LutRequest& r) { return merl_rgb_spec(r.model) ? 3 : 1; }

/// `name`, or NAME_r, NAME_g, NAME_b for a merl spec with channel=rgb (per_colour's names).
std::vector<std::string> colour_names(const LutRequest& r, const std::string& name) {
    if (!merl_rgb_spec(r.model)) return {name};
    return {name + "_r", name + "_g", name + "_b"};
}

/// The albedo table's channels: the dielectric walk's R, T, R_below, T_below, else E per colour.
std::vector<std::string> albedo_channels(const LutRequest& r) {
    try {
        if (sweep_model(r.model, true).dielectric_walk) return {"R", "T", "R_below", "T_below"};
    } catch (const Error&) {  // a merl spec (no roughness) or a bad spec, which validate_lut names
    }
    return colour_names(r, "E");
}

Table compute_albedo_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    if (without_roughness(m))
        return per_colour(r, m, [&](const ModelConfig& c) { return albedo_table_1d(engine, r, c, f); });
    if (m.dielectric_walk) return dielectric_walk_table(engine, r, m, f);
    return directional_albedo_table(engine, r, m, f,
                                    "directional albedo E(mu_o, alpha) = integral of f(wo, wi) cos(theta_i) dwi");
}

// Eavg = 2 int_0^1 E(mu) mu dmu by composite Gauss-Legendre in mu (average_over_mu): with a
// tolerance the rule gets half of it and the sampling the other half; a texel that still misses
// it is an error (exit status 1) naming it, as for the directional albedo.
Table eavg_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    bool clamped = false;
    Table t = roughness_table(r, "average albedo Eavg(alpha) = 2 integral_0^1 E(mu) mu dmu", clamped);
    std::vector<int> slots;
    if (without_roughness(m)) {  // one texel: Eavg of the model as it is
        t.quantity = "average albedo Eavg = 2 integral_0^1 E(mu) mu dmu";
        t.x = make_axis("-", "-", 0.0, 1.0, 1);
        t.x.parameter = {0.5};
    } else {
        slots = roughness_slots(m);
    }
    const size_t n_alpha = t.x.parameter.size();
    const double tolerance = r.tolerance.tolerance;
    const MuAverage avg = average_over_mu(n_alpha, tolerance, [&](const std::vector<double>& mus) {
        std::vector<AlbedoCell> cells;
        for (double alpha : t.x.parameter)
            for (double mu : mus) cells.push_back({mu, 0.0, with_alpha(m, m.params, slots, alpha)});
        const AlbedoResult res = integrate(engine, r, m, f, cells, tolerance > 0.0 ? 0.5 : 1.0);
        return MuSamples{res.values, res.method, res.samples_per_cell};
    });
    t.channels = {"Eavg"};
    t.values = {avg.value};
    t.error = avg.error;
    if (tolerance > 0.0) require_tolerance_met(t, tolerance, avg.panels);
    describe(t, r, m, f.canonical, avg.method, avg.samples, clamped);
    t.attributes["mu_quadrature"] = avg.rule;
    return t;
}

Table compute_eavg_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    return per_colour(r, m, [&](const ModelConfig& c) { return eavg_table(engine, r, c, f); });
}

}  // namespace

TableKind albedo_kind() {
    TableKind k(TableKindId::Albedo, "albedo", "directional albedo E(mu_o, alpha) = integral of f cos(theta_i) dwi (2D)",
                albedo_program, compute_albedo_table);
    k.plan_fresnel = "none (F = 1: each lobe's Fresnel enters at render time)";
    k.tileable = true;
    k.value_channels = albedo_channels;
    k.integrations = colours;
    return k;
}

TableKind eavg_kind() {
    TableKind k = variant_of(albedo_kind(), TableKindId::Eavg, "eavg",
                             "average albedo Eavg(alpha) = 2 integral of E(mu) mu dmu (1D)", compute_eavg_table);
    k.one_dimensional = true;
    k.value_channels = [](const LutRequest& r) { return colour_names(r, "Eavg"); };
    k.cells_per_texel = 48;  // 32 + 16 Gauss-Legendre nodes in mu
    // Measured: 1.0e8 samples in 0.18 s against GGX albedo's 2.2e8 samples/s (benchmarks/results/
    // plan-estimates-2c-shared.md): a sample of its short mu nodes costs less than an albedo sample.
    k.sample_cost = 0.4;
    return k;
}

}  // namespace tables
}  // namespace brdfbake

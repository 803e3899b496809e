// The directional albedo E(mu_o, alpha) and the average albedo Eavg(alpha), both with F = 1 or
// the request's Fresnel term.
#include <boost/math/quadrature/gauss.hpp>

#include <cmath>

#include "tables/lut_common.h"
#include "tables/sweep.h"

namespace brdfbake {
namespace tables {
namespace {

std::vector<std::string> albedo_program(const LutRequest& r) { return {"albedo|" + r.model + "|none"}; }

Table compute_albedo_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    return directional_albedo_table(engine, r, m, f,
                                    "directional albedo E(mu_o, alpha) = integral of f(wo, wi) cos(theta_i) dwi");
}

// Eavg = 2 int_0^1 E(mu) mu dmu by Gauss-Legendre in mu with 32 nodes; the 16-node rule on the
// same data's integrand gives the quadrature error estimate.
Table compute_eavg_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    Table t;
    t.kind = r.kind;
    bool clamped = false;
    t.quantity = "average albedo Eavg(alpha) = 2 integral_0^1 E(mu) mu dmu";
    t.x = alpha_axis(r, r.width, clamped);
    t.y = make_axis("-", "-", 0.0, 1.0, 1);
    t.y.parameter = {0.5};
    using G32 = boost::math::quadrature::gauss<double, 32>;
    using G16 = boost::math::quadrature::gauss<double, 16>;
    std::vector<double> nodes, weights32, weights16;  // on [0, 1]
    auto add_rule = [&](const auto& x, const auto& w, bool is32) {
        for (size_t i = 0; i < x.size(); ++i)
            for (int s : {-1, 1}) {
                if (x[i] == 0.0 && s == 1) continue;
                nodes.push_back(0.5 + 0.5 * s * x[i]);
                weights32.push_back(is32 ? 0.5 * w[i] : 0.0);
                weights16.push_back(is32 ? 0.0 : 0.5 * w[i]);
            }
    };
    add_rule(G32::abscissa(), G32::weights(), true);
    add_rule(G16::abscissa(), G16::weights(), false);
    const std::vector<int> slots = roughness_slots(m);
    std::vector<AlbedoCell> cells;
    for (double alpha : t.x.parameter)
        for (double mu : nodes) cells.push_back({mu, 0.0, with_alpha(m.params, slots, alpha)});
    const AlbedoResult res = integrate(engine, r, m, f, cells);
    t.channels = {"Eavg"};
    t.values.assign(1, {});
    for (size_t a = 0; a < t.x.parameter.size(); ++a) {
        double e32 = 0, e16 = 0, err = 0;
        for (size_t k = 0; k < nodes.size(); ++k) {
            const AlbedoValue& v = res.values[a * nodes.size() + k];
            e32 += 2 * weights32[k] * nodes[k] * v.value;
            e16 += 2 * weights16[k] * nodes[k] * v.value;
            err += 2 * weights32[k] * nodes[k] * v.error;  // errors add linearly: shared point sets
        }
        t.values[0].push_back(e32);
        t.error.push_back(err + std::fabs(e32 - e16));
    }
    describe(t, r, m, f.canonical, res.method, res.samples_per_cell, clamped);
    t.attributes["mu_quadrature"] = "Gauss-Legendre, 32 nodes (16-node rule for the error estimate)";
    return t;
}

}  // namespace

TableKind albedo_kind() {
    TableKind k(TableKindId::Albedo, "albedo", "directional albedo E(mu_o, alpha) = integral of f cos(theta_i) dwi (2D)",
                albedo_program, compute_albedo_table);
    k.plan_fresnel = "none (F = 1: each lobe's Fresnel enters at render time)";
    k.tileable = true;
    return k;
}

TableKind eavg_kind() {
    TableKind k = variant_of(albedo_kind(), TableKindId::Eavg, "eavg",
                             "average albedo Eavg(alpha) = 2 integral of E(mu) mu dmu (1D)", compute_eavg_table);
    k.one_dimensional = true;
    k.cells_per_texel = 48;  // 32 + 16 Gauss-Legendre nodes in mu
    return k;
}

}  // namespace tables
}  // namespace brdfbake

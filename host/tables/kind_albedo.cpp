// The directional albedo E(mu_o, alpha) and the average albedo Eavg(alpha), both with F = 1 or
// the request's Fresnel term.
#include <boost/math/quadrature/gauss.hpp>

#include <cmath>

#include "brdfbake/error.h"
#include "models/key_reader.h"
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

// Eavg = 2 int_0^1 E(mu) mu dmu by composite Gauss-Legendre in mu: the 32-node rule on each
// panel, the 16-node rule on the same panel for its error. Without a tolerance one panel [0, 1].
// With one, the rule gets half of it and the sampling the other half: panels whose |G32 - G16|
// keeps a texel above its half are halved (E(mu) bends sharply near grazing at small alpha, so
// the panels shrink toward mu = 0), and only the new panels' nodes are integrated, until every
// texel meets the tolerance; a texel that still misses it after kMaxPanelRounds is an error
// (exit status 1) naming it, as for the directional albedo.
constexpr int kMaxPanelRounds = 12;

struct Panel {
    double lo, hi;
    std::vector<double> e32, e16, err;  // per alpha texel: the panel's two rules, its sampling error
};

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
    std::vector<double> unit_nodes, weights32, weights16;  // on [0, 1]
    auto add_rule = [&](const auto& x, const auto& w, bool is32) {
        for (size_t i = 0; i < x.size(); ++i)
            for (int s : {-1, 1}) {
                if (x[i] == 0.0 && s == 1) continue;
                unit_nodes.push_back(0.5 + 0.5 * s * x[i]);
                weights32.push_back(is32 ? 0.5 * w[i] : 0.0);
                weights16.push_back(is32 ? 0.0 : 0.5 * w[i]);
            }
    };
    add_rule(G32::abscissa(), G32::weights(), true);
    add_rule(G16::abscissa(), G16::weights(), false);
    const std::vector<int> slots = roughness_slots(m);
    const size_t n_alpha = t.x.parameter.size(), n_nodes = unit_nodes.size();
    const double tolerance = r.tolerance.tolerance;

    std::vector<Panel> done, todo = {Panel{0.0, 1.0, {}, {}, {}}};
    std::string method;
    std::uint64_t samples = 0;
    for (int round = 0;; ++round) {
        // Integrate the new panels' nodes for every alpha texel in one request.
        std::vector<AlbedoCell> cells;
        for (const Panel& p : todo)
            for (double alpha : t.x.parameter)
                for (double u : unit_nodes)
                    cells.push_back({p.lo + (p.hi - p.lo) * u, 0.0, with_alpha(m.params, slots, alpha)});
        const AlbedoResult res = integrate(engine, r, m, f, cells, tolerance > 0.0 ? 0.5 : 1.0);
        method = res.method;
        samples = std::max(samples, res.samples_per_cell);
        for (size_t q = 0; q < todo.size(); ++q) {
            Panel& p = todo[q];
            const double width = p.hi - p.lo;
            p.e32.assign(n_alpha, 0.0);
            p.e16.assign(n_alpha, 0.0);
            p.err.assign(n_alpha, 0.0);
            for (size_t a = 0; a < n_alpha; ++a)
                for (size_t k = 0; k < n_nodes; ++k) {
                    const AlbedoValue& v = res.values[(q * n_alpha + a) * n_nodes + k];
                    const double mu = p.lo + width * unit_nodes[k];
                    p.e32[a] += 2 * width * weights32[k] * mu * v.value;
                    p.e16[a] += 2 * width * weights16[k] * mu * v.value;
                    p.err[a] += 2 * width * weights32[k] * mu * v.error;  // errors add linearly: shared point sets
                }
            done.push_back(p);
        }
        todo.clear();
        if (tolerance <= 0.0) break;
        // The rule's error per texel, and the panels to halve where a texel misses its half.
        std::vector<double> rule(n_alpha, 0.0);
        for (const Panel& p : done)
            for (size_t a = 0; a < n_alpha; ++a) rule[a] += std::fabs(p.e32[a] - p.e16[a]);
        std::vector<bool> failing(n_alpha);
        bool any = false;
        for (size_t a = 0; a < n_alpha; ++a) any = (failing[a] = rule[a] > 0.5 * tolerance) || any;
        if (!any || round + 1 >= kMaxPanelRounds) break;
        std::vector<Panel> keep;
        size_t worst = 0;
        double worst_excess = -1.0;
        for (size_t q = 0; q < done.size(); ++q) {
            const Panel& p = done[q];
            double excess = -1.0;  // the panel's largest rule error per unit width, over failing texels
            for (size_t a = 0; a < n_alpha; ++a)
                if (failing[a]) excess = std::max(excess, std::fabs(p.e32[a] - p.e16[a]) / (p.hi - p.lo));
            if (excess > worst_excess) {
                worst_excess = excess;
                worst = q;
            }
        }
        for (size_t q = 0; q < done.size(); ++q) {
            const Panel& p = done[q];
            double excess = 0.0;
            for (size_t a = 0; a < n_alpha; ++a)
                if (failing[a]) excess = std::max(excess, std::fabs(p.e32[a] - p.e16[a]));
            if (q == worst || excess > 0.5 * tolerance * (p.hi - p.lo)) {
                const double mid = 0.5 * (p.lo + p.hi);
                todo.push_back(Panel{p.lo, mid, {}, {}, {}});
                todo.push_back(Panel{mid, p.hi, {}, {}, {}});
            } else {
                keep.push_back(p);
            }
        }
        done = keep;
    }

    t.channels = {"Eavg"};
    t.values.assign(1, std::vector<double>(n_alpha, 0.0));
    t.error.assign(n_alpha, 0.0);
    for (const Panel& p : done)
        for (size_t a = 0; a < n_alpha; ++a) {
            t.values[0][a] += p.e32[a];
            t.error[a] += p.err[a] + std::fabs(p.e32[a] - p.e16[a]);
        }
    if (tolerance > 0.0) {
        size_t worst = 0;
        for (size_t a = 1; a < n_alpha; ++a)
            if (t.error[a] > t.error[worst]) worst = a;
        if (t.error[worst] > tolerance)
            throw Error("--tolerance " + format_number(tolerance) + " not met: the eavg texel at alpha = " +
                            format_number(t.x.parameter[worst]) + " has an error of " + format_number(t.error[worst]) +
                            " after " + std::to_string(done.size()) + " mu panels",
                        kExitViolation);
    }
    describe(t, r, m, f.canonical, method, samples, clamped);
    t.attributes["mu_quadrature"] =
        done.size() == 1 ? "Gauss-Legendre, 32 nodes (16-node rule for the error estimate)"
                         : "composite Gauss-Legendre over " + std::to_string(done.size()) +
                               " mu panels, 32 nodes each (16-node rule per panel for the error estimate)";
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

#include "tables/mu_average.h"

#include <boost/math/quadrature/gauss.hpp>

#include <algorithm>
#include <cmath>

#include "brdfbake/error.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

constexpr int kMaxPanelRounds = 12;

struct Panel {
    double lo, hi;
    std::vector<double> e32, e16, err;  // per integral: the panel's two rules, its integrand error
};

}  // namespace

MuAverage average_over_mu(size_t n_integrals, double tolerance, const MuIntegrand& integrand) {
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
    const size_t n_nodes = unit_nodes.size();

    MuAverage out;
    std::vector<Panel> done, todo = {Panel{0.0, 1.0, {}, {}, {}}};
    for (int round = 0;; ++round) {
        // Integrate the new panels' nodes for every integral in one call.
        std::vector<double> mus;
        for (const Panel& p : todo)
            for (double u : unit_nodes) mus.push_back(p.lo + (p.hi - p.lo) * u);
        const MuSamples res = integrand(mus);
        if (res.values.size() != n_integrals * mus.size()) throw Error("internal error: the mu integrand lost values");
        out.method = res.method;
        out.samples = std::max(out.samples, res.samples);
        for (size_t q = 0; q < todo.size(); ++q) {
            Panel& p = todo[q];
            const double width = p.hi - p.lo;
            p.e32.assign(n_integrals, 0.0);
            p.e16.assign(n_integrals, 0.0);
            p.err.assign(n_integrals, 0.0);
            for (size_t i = 0; i < n_integrals; ++i)
                for (size_t k = 0; k < n_nodes; ++k) {
                    const AlbedoValue& v = res.values[i * mus.size() + q * n_nodes + k];
                    const double mu = p.lo + width * unit_nodes[k];
                    p.e32[i] += 2 * width * weights32[k] * mu * v.value;
                    p.e16[i] += 2 * width * weights16[k] * mu * v.value;
                    p.err[i] += 2 * width * weights32[k] * mu * v.error;  // errors add linearly: shared point sets
                }
            done.push_back(p);
        }
        todo.clear();
        if (tolerance <= 0.0) break;
        // The rule's error per integral, and the panels to halve where an integral misses its half.
        std::vector<double> rule(n_integrals, 0.0);
        for (const Panel& p : done)
            for (size_t i = 0; i < n_integrals; ++i) rule[i] += std::fabs(p.e32[i] - p.e16[i]);
        std::vector<bool> failing(n_integrals);
        bool any = false;
        for (size_t i = 0; i < n_integrals; ++i) any = (failing[i] = rule[i] > 0.5 * tolerance) || any;
        if (!any || round + 1 >= kMaxPanelRounds) break;
        std::vector<Panel> keep;
        size_t worst = 0;
        double worst_excess = -1.0;
        for (size_t q = 0; q < done.size(); ++q) {
            const Panel& p = done[q];
            double excess = -1.0;  // the panel's largest rule error per unit width, over failing integrals
            for (size_t i = 0; i < n_integrals; ++i)
                if (failing[i]) excess = std::max(excess, std::fabs(p.e32[i] - p.e16[i]) / (p.hi - p.lo));
            if (excess > worst_excess) {
                worst_excess = excess;
                worst = q;
            }
        }
        for (size_t q = 0; q < done.size(); ++q) {
            const Panel& p = done[q];
            double excess = 0.0;
            for (size_t i = 0; i < n_integrals; ++i)
                if (failing[i]) excess = std::max(excess, std::fabs(p.e32[i] - p.e16[i]));
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
    out.value.assign(n_integrals, 0.0);
    out.error.assign(n_integrals, 0.0);
    for (const Panel& p : done)
        for (size_t i = 0; i < n_integrals; ++i) {
            out.value[i] += p.e32[i];
            out.error[i] += p.err[i] + std::fabs(p.e32[i] - p.e16[i]);
        }
    out.panels = done.size();
    out.rule = done.size() == 1 ? "Gauss-Legendre, 32 nodes (16-node rule for the error estimate)"
                                : "composite Gauss-Legendre over " + std::to_string(done.size()) +
                                      " mu panels, 32 nodes each (16-node rule per panel for the error estimate)";
    return out;
}

Table roughness_table(const LutRequest& r, const std::string& quantity, bool& clamped) {
    Table t;
    t.kind = r.kind;
    t.quantity = quantity;
    t.x = alpha_axis(r, r.width, clamped);
    t.y = make_axis("-", "-", 0.0, 1.0, 1);
    t.y.parameter = {0.5};
    return t;
}

void require_tolerance_met(const Table& t, double tolerance, size_t mu_panels) {
    const size_t worst = size_t(std::max_element(t.error.begin(), t.error.end()) - t.error.begin());
    if (t.error[worst] <= tolerance) return;
    const size_t n_alpha = t.x.parameter.size();
    std::string where = "alpha = " + format_number(t.x.parameter[worst % n_alpha]);
    if (!t.z.parameter.empty()) where += ", eta = " + format_number(t.z.parameter[worst / n_alpha]);
    throw Error("--tolerance " + format_number(tolerance) + " not met: the " + t.kind + " texel at " + where +
                    " has an error of " + format_number(t.error[worst]) + " after " + std::to_string(mu_panels) +
                    " mu panels",
                kExitViolation);
}

}  // namespace tables
}  // namespace brdfbake

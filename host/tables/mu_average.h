// The average over mu of a family of directional integrals, Eavg = 2 int_0^1 E(mu) mu dmu, by
// composite Gauss-Legendre in mu, refined to a tolerance: the one place where the eavg and
// dielectric-eavg kinds integrate over mu.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/lut.h"
#include "brdfbake/table.h"

namespace brdfbake {
namespace tables {

/// The directional integrals E_i(mu) of every integral i at the nodes `mus`: the result holds
/// n_integrals x mus.size() values, integral-major (value [i * mus.size() + k] is E_i(mus[k])),
/// each with its error estimate; `method` and `samples` say how (for the table's attributes).
struct MuSamples {
    std::vector<AlbedoValue> values;
    std::string method;
    std::uint64_t samples = 0;
};
using MuIntegrand = std::function<MuSamples(const std::vector<double>& mus)>;

struct MuAverage {
    std::vector<double> value, error;  // per integral: Eavg and its error estimate
    size_t panels = 1;
    std::string method;          // the integrand's, from its last call
    std::uint64_t samples = 0;   // the largest per-cell count over the calls
    std::string rule;            // the mu rule in words (the table's mu_quadrature attribute)
};

/// Eavg_i = 2 int_0^1 E_i(mu) mu dmu for n_integrals integrals: the 32-node Gauss-Legendre rule
/// on each mu panel, the 16-node rule on the same panel for its error. Without a tolerance
/// (tolerance <= 0) one panel [0, 1]. With one, the integrand is expected to deliver errors that
/// add up to at most half of it (the rule's weights 2 w mu sum to 1); panels whose |G32 - G16|
/// keeps an integral above the other half are halved (E(mu) bends sharply near grazing at small
/// roughness, so the panels shrink toward mu = 0), and only the new panels' nodes are
/// integrated, for up to 12 rounds. The caller checks the result against its tolerance (the
/// error is the integrand's errors, weighted as the rule weights them and added linearly, plus
/// |G32 - G16| per panel).
MuAverage average_over_mu(size_t n_integrals, double tolerance, const MuIntegrand& integrand);

/// The layout of the average-albedo kinds: kind and quantity set, x the request's roughness axis
/// (`clamped` as alpha_axis sets it), y one placeholder texel; the caller adds a z axis.
Table roughness_table(const LutRequest& r, const std::string& quantity, bool& clamped);

/// Throws Error (exit status 1) unless every texel of an average-albedo table meets `tolerance`
/// (> 0), naming the worst texel by its alpha (and eta, where the table has an eta axis) and the
/// mu panels spent.
void require_tolerance_met(const Table& t, double tolerance, size_t mu_panels);

}  // namespace tables
}  // namespace brdfbake

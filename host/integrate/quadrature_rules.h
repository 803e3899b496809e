// The quadrature rules of the albedo and rough-dielectric integrators: Gauss-Legendre and
// Gauss-Kronrod nodes on [0, 1] laid out for the kernels, the error estimate from three
// Gauss-Legendre rules, and the rule's order for a sample budget.
#pragma once

#include <cstdint>
#include <vector>

namespace brdfbake {

/// Gauss-Legendre nodes and weights of the n-point rule on [0, 1] (weights summing to 1),
/// appended to `out`: the abscissae, then the weights. With lanes > 1 (the vector kernels) each
/// is padded to a multiple of lanes with abscissa 1/2 and weight 0.
void append_gauss_legendre(unsigned n, std::vector<double>& out, unsigned lanes = 1);

/// The K-point Gauss-Kronrod rule on [0, 1] (K = 15, 21, 31, 41, 51 or 61) and its embedded
/// Gauss rule, appended to `out`: the abscissae, the Kronrod weights, then the Gauss weights
/// (0 at the Kronrod-only nodes), each padded as append_gauss_legendre pads. Throws Error for
/// another K.
void append_gauss_kronrod(unsigned points, std::vector<double>& out, unsigned lanes);

/// The error of the n-node rule from the n/2- and n/4-node rules (`kinked`: the integrand has a
/// kink everywhere, so geometric convergence is never assumed).
double quadrature_error(double fine, double coarse, double coarsest, bool kinked);

/// The fine rule's order for a sample budget: the even n nearest sqrt(samples / 4), at least 4.
unsigned quadrature_order(std::uint64_t samples);

}  // namespace brdfbake

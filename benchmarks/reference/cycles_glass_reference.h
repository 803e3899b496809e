// Blender Cycles' glass tables from their convention: ggx_glass_E, ggx_glass_inv_E (16 x 16 x 16)
// and ggx_glass_Eavg, ggx_glass_inv_Eavg (16 x 16), as intern/cycles/app/cycles_precompute.cpp
// defines them and microfacet_ggx_preserve_energy (intern/cycles/kernel/closure/bsdf_microfacet.h)
// reads them, evaluated by independent quadrature (reference.h's rough_dielectric_rt with
// Cycles' G2 = 1/(1 + Lambda_o + Lambda_t) for transmission). Nothing here calls brdfbake.
//
// The convention, texel (x, y, z) of N = 16 per axis, stored at (z * 16 + y) * 16 + x:
//   roughness r = clamp(x/15, 1e-4, 1), alpha = r^2;
//   mu        = clamp(y/15, 1e-4, 1);
//   z         = clamp(z/15, 1e-4, 0.99), eta = ior_from_F0(z^4) = (1 + z^2)/(1 - z^2);
//   E         = the mean of the sampled weight eval/pdf of Cycles' glass closure at (alpha, eta),
//               which converges to the single-scattering albedo R + T (exact dielectric Fresnel,
//               G2 = 1/(1 + Lambda_i + Lambda_o) for both lobes); "inv" is the closure at 1/eta;
//   Eavg      = the mean of 2 mu E(mu) over mu uniform on [0, 1] (no floor): 2 integral R + T mu dmu.
// Cycles' sampler has two singular cases, where each sample's weight is exactly 1 (E = 1):
// alpha_x alpha_y <= 2e-10 (roughness_is_almost_specular: the r = 1e-4 column), and refraction at
// |eta - 1| < 1e-4 (the z = 1e-4 slice, where eta = (1 + 1e-8)/(1 - 1e-8) rounds to 1 in float).
#pragma once

#include <boost/math/quadrature/gauss.hpp>

#include <algorithm>
#include <cmath>

#include "reference.h"

namespace ref {
namespace cycles_glass {

constexpr int kSize = 16;

inline double grid(int i, double lo, double hi) { return std::clamp(double(i) / (kSize - 1), lo, hi); }
inline double roughness(int x) { return grid(x, 1e-4, 1.0); }
inline double mu(int y) { return grid(y, 1e-4, 1.0); }
inline double eta(int z) {
    const double w = grid(z, 1e-4, 0.99);
    return (1 + w * w) / (1 - w * w);
}

/// Whether Cycles' sampler is singular at texel (x, z): every sample weighs 1.
inline bool singular(int x, int z) {
    const double alpha = roughness(x) * roughness(x);
    return alpha * alpha <= 2e-10 || std::fabs(float(eta(z)) - 1.0f) < 1e-4f;
}

/// R + T at (alpha, mu, eta) under Cycles' shadowing, by quadrature to relative tolerance `tol`.
inline double albedo(double alpha, double mu_o, double eta_rel, double tol) {
    double r = 0, t = 0;
    rough_dielectric_rt(mu_o, alpha, eta_rel, DielectricShadowing::Cycles, r, t, tol);
    return r + t;
}

/// ggx_glass_E (inside = false) or ggx_glass_inv_E at texel (x = roughness, y = mu, z).
inline double E(int x, int y, int z, bool inside, double tol = 1e-8) {
    if (singular(x, z)) return 1.0;
    const double e = eta(z);
    return albedo(roughness(x) * roughness(x), mu(y), inside ? 1 / e : e, tol);
}

/// ggx_glass_Eavg (inside = false) or ggx_glass_inv_Eavg at texel (x = roughness, z): 2 integral
/// of E(mu) mu dmu by composite 20-point Gauss-Legendre over `panels` equal panels of mu (the
/// integrand is smooth in mu at a rough texel; a few panels reach 1e-7).
inline double Eavg(int x, int z, bool inside, int panels = 2, double tol = 1e-8) {
    if (singular(x, z)) return 1.0;
    const double e = eta(z), alpha = roughness(x) * roughness(x);
    double sum = 0;
    for (int p = 0; p < panels; ++p) {
        const double a = double(p) / panels, b = double(p + 1) / panels;
        sum += boost::math::quadrature::gauss<double, 20>::integrate(
            [&](double m) { return 2 * m * albedo(alpha, m, inside ? 1 / e : e, tol); }, a, b);
    }
    return sum;
}

}  // namespace cycles_glass
}  // namespace ref

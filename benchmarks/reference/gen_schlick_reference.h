// Independent references for the generalized-Schlick tables (host/tables/kind_gen_schlick.cpp):
// the textbook formulas by adaptive Boost.Math quadrature in half-vector space
// (reference.h's albedo_halfvector), in long double where the integrand is formed.
#pragma once

#include <algorithm>
#include <cmath>

#include "reference.h"

namespace ref {

/// No kinks: albedo_halfvector with a `breaks` function integrates to an absolute error density
/// `tol` (a relative tolerance would refine without end where w is tiny, e.g. (1 - cos)^35 near
/// normal incidence); the absolute error is then below tol times the domain's area, pi^2 / 2.
inline std::vector<ld> no_breaks(ld) { return {}; }

/// The lobe's albedo weighted by w(wo.wh) (w = 1: at F = 1): GGX with the height-correlated
/// Smith G2 (Heitz 2014 eq. 99), at the cosine mu_o of the outgoing direction; absolute error
/// about 5 tol.
inline double ggx_albedo_weighted(ld mu_o, ld alpha, const std::function<ld(ld)>& w, double tol = 1e-10) {
    return albedo_halfvector(
        [&](Dir wo, Dir wi) {
            const Dir wh = normalize(Dir{wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
            return ggx_f(wo, wi, alpha, alpha, true) * w(dot(wo, wh));
        },
        mu_o, 0, tol, no_breaks);
}

/// The generalized-Schlick factor s = E_w / E with w = (1 - cos)^exponent (Hoffman 2019's form
/// with a free exponent, Blender Cycles' ggx_gen_schlick_s): E mix(f0, f90, s) is the albedo
/// under F = f0 + (f90 - f0)(1 - cos)^exponent.
inline double ggx_gen_schlick_s(ld mu_o, ld alpha, ld exponent, double tol = 1e-10) {
    const double e = ggx_albedo_weighted(mu_o, alpha, [](ld) { return ld(1); }, tol);
    const double ew = ggx_albedo_weighted(
        mu_o, alpha, [&](ld c) { return std::pow(std::max<ld>(0, 1 - c), exponent); }, tol);
    return ew / e;
}

/// The same with w = clamp((F(cos, eta) - F0) / (1 - F0), 0, 1), F the textbook dielectric (Born &
/// Wolf) and F0 = ((eta - 1)/(eta + 1))^2 (Cycles' ggx_gen_schlick_ior_s; the clamp as Cycles'
/// fresnel_generalized_schlick: a high index's F dips below F0 before Brewster's angle).
inline double ggx_gen_schlick_ior_s(ld mu_o, ld alpha, double eta, double tol = 1e-10) {
    const double f0 = std::pow((eta - 1) / (eta + 1), 2);
    const double e = ggx_albedo_weighted(mu_o, alpha, [](ld) { return ld(1); }, tol);
    const double ew = ggx_albedo_weighted(
        mu_o, alpha, [&](ld c) { return ld(std::clamp((fresnel_dielectric(double(c), eta) - f0) / (1 - f0), 0.0, 1.0)); }, tol);
    return ew / e;
}

/// What Cycles' Monte-Carlo estimator converges to (intern/cycles/app/cycles_precompute.cpp,
/// precompute_ggx_gen_schlick_s): the mean over visible normals wh ~ D_wo (Heitz 2018) of
/// w(wo.wh), a sample whose reflection goes below the horizon counting 0:
///   s_C = integral of w(wo.wh) G1(wo) max(0, wo.wh) D(wh) / mu_o dwh over wh with wi.z > 0.
/// albedo_halfvector integrates f wi.z 4 (wo.wh) dwh, so f = w G1(wo) D / (4 mu_o wi.z).
inline double ggx_cycles_vndf_weighted(ld mu_o, ld alpha, const std::function<ld(ld)>& w, double tol = 1e-10) {
    return albedo_halfvector(
        [&](Dir wo, Dir wi) -> ld {
            const Dir wh = normalize(Dir{wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
            return w(dot(wo, wh)) * ggx_g1(wo, alpha, alpha) * ggx_d(wh, alpha, alpha) / (4 * wo.z * wi.z);
        },
        mu_o, 0, tol, no_breaks);
}

/// Cycles' ggx_gen_schlick_s estimate: w = (1 - cos)^exponent.
inline double ggx_cycles_vndf_s(ld mu_o, ld alpha, ld exponent, double tol = 1e-10) {
    return ggx_cycles_vndf_weighted(
        mu_o, alpha, [&](ld c) { return std::pow(std::max<ld>(0, 1 - c), exponent); }, tol);
}

/// Cycles' ggx_gen_schlick_ior_s estimate: w = clamp((F(cos, eta) - F0) / (1 - F0), 0, 1) as in
/// ggx_gen_schlick_ior_s above.
inline double ggx_cycles_vndf_s_ior(ld mu_o, ld alpha, double eta, double tol = 1e-10) {
    const double f0 = std::pow((eta - 1) / (eta + 1), 2);
    return ggx_cycles_vndf_weighted(
        mu_o, alpha,
        [&](ld c) { return ld(std::clamp((fresnel_dielectric(double(c), eta) - f0) / (1 - f0), 0.0, 1.0)); }, tol);
}

}  // namespace ref

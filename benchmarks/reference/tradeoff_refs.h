// Independent reference albedos for brdfbake-tradeoff: the textbook BRDF formulas of
// benchmarks/reference/reference.h (long double, angle form, written afresh from the papers) integrated with
// Boost.Math's 31-point Gauss-Kronrod rule, adaptively bisected to an absolute error target. Nothing here calls the engine or its shared BRDF
// headers.
//
// Microfacet lobes are integrated in half-vector space (dwi = 4 (wo.wh) dwh). Lobes as narrow
// as alpha = 1e-3, and grazing directions (mu = 1e-4), put all the structure of the integrand
// in theta_h below 1e-3, which a single adaptive rule over [0, pi/2] can step over; so the
// theta_h range is cut at multiples of the lobe width and of mu before the adaptive rule runs
// on each piece. Per theta_h, the azimuths where wi is above the horizon form one interval in
// closed form (ref::albedo_halfvector's dmax), and V-groove kinks split it further
// (ref::vgroove_kinks). Each reference is computed at two tolerances; their difference is
// stored as the reference's uncertainty.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "reference/reference.h"

namespace tradeoff_ref {

using ref::Dir;
using ref::ld;

/// Adaptive 31-point Gauss-Kronrod (Boost.Math's rule, applied to one interval at a time) on
/// [a, b] to an absolute error `target`: an interval whose Kronrod-Gauss difference is above
/// its share of the target is bisected, each half getting half the target. Unlike a relative
/// criterion it does not refine pieces whose contribution is negligible (lobe tails that
/// underflow to denormals, where the error estimate is all rounding noise).
///
/// A piece is also accepted when its difference is below `floor_rel` x |its integral| +
/// `floor_abs` x its length: the integrand's own accuracy. An integrand that is itself an
/// adaptive integral (the outer integral of a 2D rule), or one with rounding steps, has steps of
/// about that size, the Kronrod-Gauss difference of a piece never falls below them, and as
/// bisection halves the target together with the piece, it would split forever (2^depth
/// pieces). What such a floor leaves is the integrand's error, not the rule's.
inline double gk_abs(const std::function<double(double)>& f, double a, double b, double target,
                     double floor_rel = 0.0, double floor_abs = 0.0, int depth = 0) {
    if (!(b > a)) return 0.0;
    double err = 0.0;
    const double v = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, a, b, 0, 0.0, &err);
    // Boost reports the non-adaptive error of the rule mapped to [-1, 1]: scale it to [a, b].
    err *= 0.5 * (b - a);
    if (err <= target || err <= floor_rel * std::fabs(v) + floor_abs * (b - a) || depth >= 48) return v;
    const double m = 0.5 * (a + b);
    return gk_abs(f, a, m, 0.5 * target, floor_rel, floor_abs, depth + 1) +
           gk_abs(f, m, b, 0.5 * target, floor_rel, floor_abs, depth + 1);
}

/// gk_abs to an error of tol x max(|integral|, 1) (the size estimated by one rule over [a, b]):
/// relative for the large inner integrals of a narrow lobe, absolute (tol) for small ones, whose
/// relative error is all rounding noise near the horizon and which the albedo hardly feels.
inline double gk(const std::function<double(double)>& f, double a, double b, double tol) {
    if (!(b > a)) return 0.0;
    double err = 0.0;
    const double v0 = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, a, b, 0, 0.0, &err);
    return gk_abs(f, a, b, tol * std::max(std::fabs(v0), 1.0));
}

/// The inner (azimuth) integrals of the 2D rules are computed this much more accurately than the
/// outer tolerance (relative to max(size, 1), see gk), so that their noise stays below the
/// outer target.
constexpr double kInnerFactor = 1e-2;
/// The outer rule's floor (gk_abs), per unit tolerance: 20 x the inner integrals' accuracy.
constexpr double kOuterFloor = 20 * kInnerFactor;

/// The relative accuracy to which the BRDF integrands themselves are known along an azimuth
/// row: at grazing (mu = 1e-4) the V-groove kinks, placed by acos near +-1, and the horizon
/// cancellations leave steps of about 1e-13 of the row's size, which no bisection removes.
constexpr double kRowNoise = 1e-13;

/// E(mu) of f by quadrature in half-vector space. `width` is the lobe's angular width in
/// theta_h; `kinks(theta_h)` gives the |phi_h - phi_o| where the integrand has kinks.
inline double albedo_halfvector(const std::function<ld(Dir, Dir)>& f, ld mu_o, double width, double tol,
                                const std::function<std::vector<ld>(ld)>& kinks = nullptr) {
    const Dir wo = ref::dir_mu(mu_o, 0);
    const ld sin_o = std::sqrt(std::max<ld>(0, 1 - mu_o * mu_o));
    const double hp = double(ref::kPi / 2);
    auto dmax = [&](ld th) -> ld {
        const ld a = sin_o * std::sin(2 * th), b = sin_o * std::sin(th);
        if (a <= 1e-300L) return std::cos(2 * th) > 0 ? ref::kPi : 0;
        const ld c = std::max(-mu_o * std::cos(2 * th) / a, -mu_o * std::cos(th) / b);
        return c >= 1 ? 0 : c <= -1 ? ref::kPi : std::acos(c);
    };
    auto inner = [&](double th) -> double {
        const ld d = dmax(th);
        if (d <= 0) return 0.0;
        auto g = [&](double ph) -> double {
            const Dir wh = ref::dir(th, ph);
            const ld c = ref::dot(wo, wh);
            const Dir wi = ref::reflect(wo, wh);
            if (c <= 0 || wi.z <= 0) return 0.0;
            return double(f(wo, wi) * wi.z * 4 * c);
        };
        std::vector<ld> cuts = {0, d};
        if (kinks)
            for (ld k : kinks(th))
                if (k > 0 && k < d) cuts.push_back(k);
        std::sort(cuts.begin(), cuts.end());
        // Symmetric in phi_h - phi_o (isotropic models, phi_o = 0). The target is relative to
        // the whole azimuth integral (or absolute where it is below 1, as in gk), shared by its
        // pieces in proportion to their length.
        double err = 0.0;
        const double whole = std::fabs(boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
            g, 0.0, double(d), 0, 0.0, &err));
        const double target = kInnerFactor * tol * std::max(whole, 1.0) / double(d);
        double sum = 0;
        for (size_t k = 0; k + 1 < cuts.size(); ++k)
            sum += 2 * gk_abs(g, double(cuts[k]), double(cuts[k + 1]), target * double(cuts[k + 1] - cuts[k]),
                              20 * kRowNoise);
        return sum * std::sin(th);
    };
    // theta_h cuts: multiples of the lobe width and of the grazing scale mu_o / 2 (where the
    // reflected direction's horizon sweeps through the lobe's centre).
    std::vector<double> cuts = {0.0, hp};
    for (double scale : {width, double(mu_o) / 2})
        for (double k : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0})
            if (k * scale < hp) cuts.push_back(k * scale);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    // The albedo is at most about 1: an absolute target of tol, shared by the pieces.
    double sum = 0;
    for (size_t k = 0; k + 1 < cuts.size(); ++k)
        sum += gk_abs(inner, cuts[k], cuts[k + 1], tol / double(cuts.size()), kOuterFloor * tol, kOuterFloor * tol);
    return sum;
}

/// Oren-Nayar 1994 (qualitative model) E(mu) by 2D quadrature over (theta_i, phi_i - phi_o),
/// split at the kinks theta_i = theta_o and |phi_i - phi_o| = pi/2.
inline double albedo_oren_nayar(ld sigma, ld rho, ld mu_o, double tol) {
    const Dir wo = ref::dir_mu(mu_o, 0);
    const double to = double(std::acos(mu_o)), hp = double(ref::kPi / 2), pi = double(ref::kPi);
    auto g = [&](double th, double ph) {
        return double(ref::oren_nayar_f(wo, ref::dir(th, ph), sigma, rho) * std::cos((ld)th) * std::sin((ld)th));
    };
    double sum = 0;
    for (auto t : {std::pair<double, double>{0.0, to}, {to, hp}})
        for (auto p : {std::pair<double, double>{0.0, hp}, {hp, pi}})
            sum += 2 * gk_abs([&](double th) {
                return gk([&](double ph) { return g(th, ph); }, p.first, p.second, kInnerFactor * tol);
            }, t.first, t.second, tol / 4, kOuterFloor * tol, kOuterFloor * tol);
    return sum;
}

/// The model families of the study, as the reference computes them.
enum class Family { Ggx, Beckmann, TsGgx, TsBlinn, OrenNayar };

/// E(mu) for family `fam` with parameter `p` (alpha; the Blinn exponent n; sigma with rho = 1),
/// F = 1, height-correlated Smith shadowing for GGX and Beckmann (brdfbake's default).
inline double albedo(Family fam, double p, double mu, double tol) {
    switch (fam) {
    case Family::Ggx:
        return albedo_halfvector([=](Dir o, Dir i) { return ref::ggx_f(o, i, p, p, true); }, mu, p, tol);
    case Family::Beckmann:
        return albedo_halfvector([=](Dir o, Dir i) { return ref::beckmann_f(o, i, p, p, true); }, mu, p, tol);
    case Family::TsGgx:
        return albedo_halfvector([=](Dir o, Dir i) { return ref::torrance_sparrow_f(o, i, ref::Dist::Ggx, p); }, mu, p,
                                 tol, [=](ld th) { return ref::vgroove_kinks(mu, th); });
    case Family::TsBlinn:
        return albedo_halfvector(
            [=](Dir o, Dir i) { return ref::torrance_sparrow_f(o, i, ref::Dist::Blinn, p); }, mu,
            std::sqrt(2.0 / (p + 2.0)), tol, [=](ld th) { return ref::vgroove_kinks(mu, th); });
    case Family::OrenNayar:
        return albedo_oren_nayar(p, 1.0, mu, tol);
    }
    return NAN;
}

}  // namespace tradeoff_ref

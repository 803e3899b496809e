// Independent references for the tests: BRDF formulas written afresh from the papers in their
// textbook (tan/angle) form, in long double, and adaptive Gauss-Kronrod quadrature from
// Boost.Math. Nothing here calls the code under test.
#pragma once

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <cmath>
#include <functional>

namespace ref {

using ld = long double;
constexpr ld kPi = 3.141592653589793238462643383279502884L;

/// Adaptive 31-point Gauss-Kronrod on [a, b] to a relative tolerance.
inline double integrate(const std::function<double(double)>& f, double a, double b, double tol = 1e-11) {
    double err = 0.0;
    return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, a, b, 18, tol, &err);
}

/// Tensor-product adaptive quadrature of f(x, y) over [ax, bx] x [ay, by].
inline double integrate2(const std::function<double(double, double)>& f, double ax, double bx, double ay,
                         double by, double tol = 1e-10) {
    return integrate([&](double x) { return integrate([&](double y) { return f(x, y); }, ay, by, tol); }, ax, bx,
                     tol);
}

struct Dir {
    ld x, y, z;
};
inline Dir dir(ld theta, ld phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}
inline Dir dir_mu(ld mu, ld phi) { return dir(std::acos(mu), phi); }
inline ld dot(Dir a, Dir b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Dir normalize(Dir a) {
    ld l = std::sqrt(dot(a, a));
    return {a.x / l, a.y / l, a.z / l};
}
inline Dir reflect(Dir w, Dir m) {
    ld c = 2 * dot(w, m);
    return {c * m.x - w.x, c * m.y - w.y, c * m.z - w.z};
}

/// GGX / Trowbridge-Reitz D in the slope form of Walter et al. 2007 eq. 33, anisotropic as in
/// Heitz 2014 eq. 85: 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2).
inline ld ggx_d(Dir m, ld ax, ld ay) {
    if (m.z <= 0) return 0;
    ld cos2 = m.z * m.z, sin2 = 1 - cos2;
    ld tan2 = sin2 / cos2;
    ld cphi2 = sin2 > 0 ? m.x * m.x / sin2 : 1, sphi2 = sin2 > 0 ? m.y * m.y / sin2 : 0;
    ld e = 1 + tan2 * (cphi2 / (ax * ax) + sphi2 / (ay * ay));
    return 1 / (kPi * ax * ay * cos2 * cos2 * e * e);
}

/// GGX Smith Lambda, Heitz 2014 eq. 86 with the projected roughness of eq. 80.
inline ld ggx_lambda(Dir w, ld ax, ld ay) {
    ld cos2 = w.z * w.z, sin2 = 1 - cos2;
    if (sin2 <= 0) return 0;
    ld alpha2 = (w.x * w.x * ax * ax + w.y * w.y * ay * ay) / sin2;
    ld tan2 = sin2 / cos2;
    return (-1 + std::sqrt(1 + alpha2 * tan2)) / 2;
}
inline ld ggx_g1(Dir w, ld ax, ld ay) { return w.z <= 0 ? 0 : 1 / (1 + ggx_lambda(w, ax, ay)); }

/// The GGX BRDF without Fresnel (F = 1): D G2 / (4 cos_o cos_i).
inline ld ggx_f(Dir wo, Dir wi, ld ax, ld ay, bool correlated) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    Dir wh = normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    ld g2 = correlated ? 1 / (1 + ggx_lambda(wo, ax, ay) + ggx_lambda(wi, ax, ay))
                       : ggx_g1(wo, ax, ay) * ggx_g1(wi, ax, ay);
    return ggx_d(wh, ax, ay) * g2 / (4 * wo.z * wi.z);
}

/// Integral of g(theta_m, phi_m) sin(theta_m) over the microfacet normals m facing wo
/// (wo.m > 0, theta_m < theta_max): per theta_m the allowed azimuths are the interval
/// |phi_m - phi_o| < acos(-mu_o cos th / (sin_o sin th)), so the inner integrand has no cut.
inline double integrate_facing(const std::function<double(double, double)>& g, ld mu_o, ld phi_o,
                               double theta_max = double(kPi / 2), double tol = 1e-10) {
    const ld sin_o = std::sqrt(std::max<ld>(0, 1 - mu_o * mu_o));
    auto inner = [&](double th) -> double {
        const ld b = sin_o * std::sin((ld)th);
        ld d = kPi;
        if (b > 1e-300L) {
            const ld c = -mu_o * std::cos((ld)th) / b;
            d = c >= 1 ? 0 : c <= -1 ? kPi : std::acos(c);
        }
        if (d <= 0) return 0.0;
        return integrate([&](double ph) { return g(th, ph); }, double(phi_o - d), double(phi_o + d), tol) *
               std::sin(th);
    };
    return integrate(inner, 0.0, theta_max, tol);
}

/// Directional albedo of a reflection BRDF f(wo, wi) by quadrature in half-vector space:
/// wi = reflect(wo, wh), dwi = 4 (wo.wh) dwh, so E = integral of f cos_i 4 (wo.wh) over wh.
/// Resolves lobes as narrow as alpha ~ 0.01 because the integrand is smooth in wh. For each
/// theta_h the azimuths where wi is above the horizon (and wo.wh > 0) form one interval
/// |phi_h - phi_o| < dmax, found in closed form, so the inner integrand has no cut.
inline double albedo_halfvector(const std::function<ld(Dir, Dir)>& f, ld mu_o, ld phi_o, double tol = 1e-9) {
    const Dir wo = dir_mu(mu_o, phi_o);
    const ld sin_o = std::sqrt(std::max<ld>(0, 1 - mu_o * mu_o));
    auto dmax = [&](ld th) -> ld {
        // wi.z = 2 (wo.wh) cos th - mu_o > 0  <=>  cos(d) > -mu_o cos 2th / (sin_o sin 2th)
        // wo.wh > 0                         <=>  cos(d) > -mu_o cos th / (sin_o sin th)
        const ld a = sin_o * std::sin(2 * th), b = sin_o * std::sin(th);
        if (a <= 1e-300L) return std::cos(2 * th) > 0 ? kPi : 0;  // normal incidence (or th = 0)
        const ld c = std::max(-mu_o * std::cos(2 * th) / a, -mu_o * std::cos(th) / b);
        return c >= 1 ? 0 : c <= -1 ? kPi : std::acos(c);
    };
    auto inner = [&](double th) -> double {
        const ld d = dmax(th);
        if (d <= 0) return 0.0;
        auto g = [&](double ph) -> double {
            Dir wh = dir(th, ph);
            ld c = dot(wo, wh);
            Dir wi = reflect(wo, wh);
            if (c <= 0 || wi.z <= 0) return 0.0;
            return double(f(wo, wi) * wi.z * 4 * c);
        };
        return integrate(g, double(phi_o - d), double(phi_o + d), tol) * std::sin(th);
    };
    return integrate(inner, 0.0, double(kPi / 2), tol);
}

}  // namespace ref

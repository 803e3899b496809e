// Independent references for the tests: BRDF formulas written afresh from the papers in their
// textbook (tan/angle) form, in long double, and adaptive Gauss-Kronrod quadrature from
// Boost.Math. Nothing here calls the code under test.
#pragma once

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <cmath>
#include <algorithm>
#include <functional>
#include <vector>

namespace ref {

using ld = long double;
constexpr ld kPi = 3.141592653589793238462643383279502884L;

/// Textbook exact dielectric Fresnel (Born & Wolf 1.5.2 eq. 21), unpolarised, for eta > 0:
/// 1 beyond the critical angle (total internal reflection).
inline double fresnel_dielectric(double cos_i, double eta) {
    const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1.0;
    const double cos_t = std::sqrt(1 - sin2_t);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/// Adaptive 31-point Gauss-Kronrod on [a, b] to a relative tolerance.
inline double integrate(const std::function<double(double)>& f, double a, double b, double tol = 1e-11) {
    double err = 0.0;
    return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, a, b, 18, tol, &err);
}

/// Adaptive 31-point Gauss-Kronrod with an absolute error target per unit length (`density`):
/// an interval is accepted when its error estimate is below density * (b - a). Unlike the
/// relative criterion it does not refine pieces where the integrand is negligibly small.
inline double integrate_abs(const std::function<double(double)>& f, double a, double b, double density,
                            int depth = 0) {
    double err = 0.0;
    const double v = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, a, b, 0, 0.0, &err);
    if (err <= density * (b - a) || depth >= 30) return v;
    const double m = 0.5 * (a + b);
    return integrate_abs(f, a, m, density, depth + 1) + integrate_abs(f, m, b, density, depth + 1);
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

/// Smith's masking G1 = 1 / (1 + Lambda) (Heitz 2014 eq. 43), 0 below the horizon, for a
/// distribution's Lambda.
template <class Lambda>
inline ld smith_g1(Dir w, ld ax, ld ay, Lambda lambda) { return w.z <= 0 ? 0 : 1 / (1 + lambda(w, ax, ay)); }

/// A Smith microfacet BRDF without Fresnel, D G2 / (4 cos_o cos_i) (Walter et al. 2007 eq. 20),
/// for a distribution D and its Lambda: G2 height-correlated 1 / (1 + Lambda_o + Lambda_i)
/// (Heitz 2014 eq. 99) or separable G1(wo) G1(wi) (eq. 98).
template <class Distribution, class Lambda>
inline ld smith_f(Dir wo, Dir wi, ld ax, ld ay, bool correlated, Distribution d, Lambda lambda) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    Dir wh = normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    ld g2 = correlated ? 1 / (1 + lambda(wo, ax, ay) + lambda(wi, ax, ay))
                       : smith_g1(wo, ax, ay, lambda) * smith_g1(wi, ax, ay, lambda);
    return d(wh, ax, ay) * g2 / (4 * wo.z * wi.z);
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
inline ld ggx_g1(Dir w, ld ax, ld ay) { return smith_g1(w, ax, ay, ggx_lambda); }

/// The GGX BRDF without Fresnel (F = 1): D G2 / (4 cos_o cos_i).
inline ld ggx_f(Dir wo, Dir wi, ld ax, ld ay, bool correlated) {
    return smith_f(wo, wi, ax, ay, correlated, ggx_d, ggx_lambda);
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
inline double albedo_halfvector(const std::function<ld(Dir, Dir)>& f, ld mu_o, ld phi_o, double tol = 1e-9,
                                const std::function<std::vector<ld>(ld)>& breaks = nullptr) {
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
        // Split the azimuth range where the integrand has kinks (|phi_h - phi_o| in `breaks`).
        std::vector<ld> cuts = {0};
        if (breaks)
            for (ld b : breaks(th))
                if (b > 0 && b < d) cuts.push_back(b);
        cuts.push_back(d);
        std::sort(cuts.begin(), cuts.end());
        double sum = 0;
        if (!breaks) return integrate(g, double(phi_o - d), double(phi_o + d), tol) * std::sin(th);
        for (size_t k = 0; k + 1 < cuts.size(); ++k) {
            sum += integrate_abs(g, double(phi_o + cuts[k]), double(phi_o + cuts[k + 1]), tol);
            sum += integrate_abs(g, double(phi_o - cuts[k + 1]), double(phi_o - cuts[k]), tol);
        }
        return sum * std::sin(th);
    };
    // With `breaks`, `tol` is an absolute error density (integrate_abs).
    if (breaks) return integrate_abs(inner, 0.0, double(kPi / 2), tol);
    return integrate(inner, 0.0, double(kPi / 2), tol);
}

/// The azimuths |phi_h - phi_o| at which the V-groove G switches branch, for a half vector at
/// theta_h and wo at mu_o: 2 (n.h)(n.o) = o.h, n.i = n.o (o.h = n.o / n.h), and
/// 2 (n.h)(n.i) = o.h with n.i = 2 (o.h)(n.h) - n.o,
/// i.e. o.h = 2 (n.h)(n.o) / (4 (n.h)^2 - 1); o.h = sin_o sin_h cos(dphi) + mu_o cos_h.
inline std::vector<ld> vgroove_kinks(ld mu_o, ld th) {
    std::vector<ld> out;
    const ld sin_o = std::sqrt(std::max<ld>(0, 1 - mu_o * mu_o)), hz = std::cos(th);
    const ld b = sin_o * std::sin(th);
    if (b <= 1e-300L) return out;
    auto add = [&](ld oh) {
        const ld c = (oh - mu_o * hz) / b;
        if (c > -1 && c < 1) out.push_back(std::acos(c));
    };
    add(2 * hz * mu_o);
    add(mu_o / hz);  // the two V-groove terms are equal: n.i = n.o
    const ld q = 4 * hz * hz - 1;
    if (std::fabs(q) > 1e-300L) add(2 * hz * mu_o / q);
    return out;
}

// ------------------------------------------------------------------------------------------
// The other models of the course notes (issue 3), again in the textbook angle form.

/// Beckmann D, Walter et al. 2007 eq. 25, anisotropic as in Heitz 2014 eq. 71:
/// exp(-tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2)) / (pi ax ay cos^4).
inline ld beckmann_d(Dir m, ld ax, ld ay) {
    if (m.z <= 0) return 0;
    ld cos2 = m.z * m.z, sin2 = 1 - cos2;
    ld tan2 = sin2 / cos2;
    ld cphi2 = sin2 > 0 ? m.x * m.x / sin2 : 1, sphi2 = sin2 > 0 ? m.y * m.y / sin2 : 0;
    return std::exp(-tan2 * (cphi2 / (ax * ax) + sphi2 / (ay * ay))) / (kPi * ax * ay * cos2 * cos2);
}

/// Beckmann Smith Lambda, Walter et al. 2007 eq. 27 / Heitz 2014 eq. 72:
/// a = 1/(alpha_o tan theta), Lambda = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)).
inline ld beckmann_lambda(Dir w, ld ax, ld ay) {
    ld cos2 = w.z * w.z, sin2 = 1 - cos2;
    if (sin2 <= 0) return 0;
    ld alpha = std::sqrt((w.x * w.x * ax * ax + w.y * w.y * ay * ay) / sin2);
    ld a = 1 / (alpha * std::sqrt(sin2 / cos2));
    return (std::erf(a) - 1) / 2 + std::exp(-a * a) / (2 * a * std::sqrt(kPi));
}
inline ld beckmann_g1(Dir w, ld ax, ld ay) { return smith_g1(w, ax, ay, beckmann_lambda); }

/// The Beckmann BRDF without Fresnel: D G2 / (4 cos_o cos_i).
inline ld beckmann_f(Dir wo, Dir wi, ld ax, ld ay, bool correlated) {
    return smith_f(wo, wi, ax, ay, correlated, beckmann_d, beckmann_lambda);
}

/// Normalised Blinn distribution (Blinn 1977; Walter et al. 2007 eq. 30): (n+2)/(2 pi) cos^n.
inline ld blinn_d(Dir m, ld n) { return m.z <= 0 ? 0 : (n + 2) / (2 * kPi) * std::pow(m.z, n); }

/// The V-groove G of Torrance-Sparrow 1967 in Cook-Torrance 1982 eq. 7.
inline ld vgroove_g(Dir wo, Dir wi) {
    Dir h = normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    ld oh = dot(wo, h);
    return std::min<ld>(1, std::min(2 * h.z * wo.z / oh, 2 * h.z * wi.z / oh));
}

enum class Dist { Blinn, Beckmann, Ggx };

/// Torrance-Sparrow with F = 1: D(h) G / (4 cos_o cos_i); `a` is n for Blinn, alpha otherwise.
inline ld torrance_sparrow_f(Dir wo, Dir wi, Dist d, ld a, ld ay = -1) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    if (ay < 0) ay = a;
    Dir h = normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    ld D = d == Dist::Blinn ? blinn_d(h, a) : d == Dist::Beckmann ? beckmann_d(h, a, ay) : ggx_d(h, a, ay);
    return D * vgroove_g(wo, wi) / (4 * wo.z * wi.z);
}

/// Phong (Lewis 1994): K cos^n(angle between wo and the mirror of wi); `original` divides by cos_i.
inline ld phong_f(Dir wo, Dir wi, ld n, ld k, bool original) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    Dir r = {-wi.x, -wi.y, wi.z};
    ld c = dot(wo, r);
    if (c <= 0) return 0;
    return k * std::pow(c, n) / (original ? wi.z : 1);
}

/// Blinn-Phong: K cos^n(theta_h).
inline ld blinn_phong_f(Dir wo, Dir wi, ld n, ld k) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    Dir h = normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    return k * std::pow(h.z, n);
}

/// Oren-Nayar 1994 eq. 30, qualitative model, with the angles themselves.
inline ld oren_nayar_f(Dir wo, Dir wi, ld sigma, ld rho) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    ld s2 = sigma * sigma;
    ld A = 1 - 0.5L * s2 / (s2 + 0.33L), B = 0.45L * s2 / (s2 + 0.09L);
    ld ti = std::acos(std::min<ld>(1, wi.z)), to = std::acos(std::min<ld>(1, wo.z));
    ld alpha = std::max(ti, to), beta = std::min(ti, to);
    ld cdphi = 0;
    if (ti > 0 && to > 0) cdphi = std::cos(std::atan2(wi.y, wi.x) - std::atan2(wo.y, wo.x));
    return rho / kPi * (A + B * std::max<ld>(0, cdphi) * std::sin(alpha) * std::tan(beta));
}

/// Directional albedo of Oren-Nayar by 2D quadrature over (theta_i, phi_i - phi_o), split where
/// the integrand has kinks (theta_i = theta_o, |phi_i - phi_o| = pi/2).
inline double albedo_oren_nayar(ld sigma, ld rho, ld mu_o, double tol = 1e-10) {
    const Dir wo = dir_mu(mu_o, 0);
    const double to = double(std::acos(mu_o));
    auto g = [&](double th, double ph) {
        return double(oren_nayar_f(wo, dir(th, ph), sigma, rho) * std::cos((ld)th) * std::sin((ld)th));
    };
    double sum = 0;
    const double hp = double(kPi / 2);
    for (auto t : {std::pair<double, double>{0.0, to}, {to, hp}}) {
        if (t.second <= t.first) continue;
        sum += integrate2(g, t.first, t.second, -hp, hp, tol);
        sum += 2 * integrate2(g, t.first, t.second, hp, double(kPi), tol);
    }
    return sum;
}

/// Directional albedo of a lobe about the mirror direction r = R(wo) (Phong): wi = cos(a) r +
/// sin(a)(cos(b) t1 + sin(b) t2) with t1 in the plane of r and n, pointing to the normal, so
/// that wi.z = cos(a) mu_o + sin(a) cos(b) sin_o > 0 is the interval |b| < bmax(a) in closed form.
/// `width` is the lobe's angular width: the a-range is split there so that narrow lobes
/// (exponent 1e4) are resolved.
inline double albedo_about_mirror(const std::function<ld(Dir, Dir)>& f, ld mu_o, double width, double tol = 1e-10) {
    const Dir wo = dir_mu(mu_o, 0);
    const ld sin_o = std::sqrt(std::max<ld>(0, 1 - mu_o * mu_o));
    const Dir r = {-wo.x, -wo.y, wo.z};
    const Dir t1 = {mu_o, 0, sin_o};  // perpendicular to r, towards the normal
    auto inner = [&](double a) -> double {
        const ld ca = std::cos((ld)a), sa = std::sin((ld)a);
        ld bmax = kPi;
        if (sa * sin_o > 1e-300L) {
            const ld c = -ca * mu_o / (sa * sin_o);
            bmax = c >= 1 ? 0 : c <= -1 ? kPi : std::acos(c);
        } else if (ca * mu_o <= 0) {
            bmax = 0;
        }
        if (bmax <= 0) return 0.0;
        auto g = [&](double b) -> double {
            const ld cb = std::cos((ld)b), sb = std::sin((ld)b);
            Dir wi = {ca * r.x + sa * cb * t1.x, ca * r.y + sa * sb, ca * r.z + sa * cb * t1.z};
            if (wi.z <= 0) return 0.0;
            return double(f(wo, wi) * wi.z);
        };
        return 2 * integrate(g, 0.0, double(bmax), tol) * double(sa);
    };
    double sum = 0, lo = 0;
    for (double k : {1.0, 3.0, 8.0}) {
        const double hi = std::min(double(kPi / 2), k * width);
        if (hi > lo) sum += integrate(inner, lo, hi, tol);
        lo = std::max(lo, hi);
    }
    if (lo < double(kPi / 2)) sum += integrate(inner, lo, double(kPi / 2), tol);
    return sum;
}

// ------------------------------------------------------------------------------------------
// Sheen (issue 18): Estevez and Kulla, "Production Friendly Microfacet Sheen BRDF", SIGGRAPH
// 2017, in the form of the KHR_materials_sheen specification (alpha = sheenRoughness^2).

/// The Charlie distribution, [EK17] eq. 2, from the angle theta_h of the half vector.
inline ld charlie_d(ld theta_h, ld alpha) {
    return (2 + 1 / alpha) * std::pow(std::sin(theta_h), 1 / alpha) / (2 * kPi);
}

/// [EK17]'s fitted Lambda: L(x) = a/(1 + b x^c) + d x + e with the coefficients of its table at
/// r = 0 and r = 1 blended by (1 - r)^2, and Lambda = exp(L(mu)) below mu = 1/2, exp(2 L(1/2) -
/// L(1 - mu)) above (the specification's "Sheen visibility").
inline ld charlie_lambda(ld mu, ld alpha) {
    const ld t = (1 - alpha) * (1 - alpha);
    auto blend = [&](ld at1, ld at0) { return at1 * (1 - t) + at0 * t; };
    auto l = [&](ld x) {
        return blend(21.5473L, 25.3245L) / (1 + blend(3.82987L, 3.32435L) * std::pow(x, blend(0.19823L, 0.16801L))) +
               blend(-1.97760L, -1.27393L) * x + blend(-4.32054L, -4.85967L);
    };
    return mu < 0.5L ? std::exp(l(mu)) : std::exp(2 * l(0.5L) - l(1 - mu));
}

/// The sheen BRDF D V: charlie V = 1/((1 + Lambda_o + Lambda_i) 4 cos_o cos_i), or the
/// Neubelt-Pettineo ("ashikhmin") V = 1/(4 (cos_i + cos_o - cos_i cos_o)).
inline ld sheen_f(Dir wo, Dir wi, ld alpha, bool charlie) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const Dir h = normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
    const ld theta_h = std::acos(std::min<ld>(1, h.z));
    const ld v = charlie ? 1 / ((1 + charlie_lambda(wo.z, alpha) + charlie_lambda(wi.z, alpha)) * 4 * wo.z * wi.z)
                         : 1 / (4 * (wi.z + wo.z - wi.z * wo.z));
    return charlie_d(theta_h, alpha) * v;
}

/// Directional albedo of the sheen by 2D tanh-sinh quadrature (Boost.Math) over (theta_i,
/// phi_i), phi_o = 0, over half the azimuths (the lobe is symmetric about the plane of wo), split
/// at theta_i = theta_o so that every feature of the integrand lies on an edge of the domain,
/// where tanh-sinh crowds its nodes: D's cone at the mirror direction (theta_o, pi), its peak on
/// the horizon of wi at phi_i = 0 for small alpha, and the x^c of the fitted Lambda at
/// cos(theta_i) = 0. `tol` is the relative tolerance of each level.
inline double albedo_sheen(ld alpha, bool charlie, ld mu_o, double tol = 1e-10) {
    boost::math::quadrature::tanh_sinh<double> ts(12);
    const Dir wo = dir_mu(mu_o, 0);
    const double to = double(std::acos(mu_o));
    auto inner = [&](double th) {
        const ld c = std::cos((ld)th), s = std::sin((ld)th);
        auto g = [&](double ph) { return double(sheen_f(wo, dir(th, ph), alpha, charlie) * c * s); };
        return ts.integrate(g, 0.0, double(kPi), 0.1 * tol);
    };
    double sum = 0;
    for (auto t : {std::pair<double, double>{0.0, to}, {to, double(kPi / 2)}})
        if (t.second > t.first) sum += 2 * ts.integrate(inner, t.first, t.second, tol);
    return sum;
}

/// The one closed form of the sheen albedo: the ashikhmin visibility at normal incidence, where
/// V = 1/4 and theta_h = theta_i / 2, so E = (2 + k)/4 int 4 s^(k+1) (1 - 2 s^2) ds over
/// s = sin(theta_i/2) in [0, 1/sqrt 2], k = 1/alpha: E = 2^(-k/2) / (k + 4).
inline double albedo_sheen_ashikhmin_normal(double alpha) {
    const double k = 1 / alpha;
    return std::pow(2.0, -k / 2) / (k + 4);
}

// ------------------------------------------------------------------------------------------
// The rough GGX dielectric interface (Walter et al. 2007) with either height-correlated
// transmission shadowing (issue 18).

/// The shadowing of transmission (brdf/rough_dielectric.h's shadowing and
/// transmission_shadowing arguments): G1 G1;
/// the Beta function B(1 + L_o, 1 + L_t) (Heitz 2014 eq. 100); 1/(1 + L_o + L_t) as Blender Cycles.
enum class DielectricShadowing { Separable, Beta, Cycles };

/// The energy fractions R and T of a rough GGX interface for light from wo (mu_o, phi_o = 0),
/// relative index eta, in half-vector space: the visible-normal density D(h) (wo.h) / cos_o
/// times F or 1 - F at the microfacet, times G2: reflection 1/(1 + L_o + L_r) (Heitz 2014 eq. 99)
/// or G1 G1 (separable), transmission by `shadowing`. The theta_h integral is split at multiples
/// of alpha so that the adaptive rule sees a narrow lobe (relative tolerance `tol`). Slow (minutes)
/// for narrow lobes seen from inside at oblique incidence, where T is tiny.
inline void rough_dielectric_rt(ld mu_o, ld alpha, ld eta, DielectricShadowing shadowing, double& r, double& t,
                                double tol = 1e-7) {
    const Dir wo = dir_mu(mu_o, 0);
    const ld lo = ggx_lambda(wo, alpha, alpha);
    auto integrand = [&](bool transmit, double th, double ph) -> double {
        const Dir h = dir(th, ph);
        const ld c = dot(wo, h);
        const ld F = fresnel_dielectric(double(c), double(eta));
        const ld vis = ggx_d(h, alpha, alpha) * c / mu_o;
        if (!transmit) {
            const Dir wi = reflect(wo, h);
            if (wi.z <= 0) return 0.0;
            const ld li = ggx_lambda(wi, alpha, alpha);
            const ld g2 = shadowing == DielectricShadowing::Separable ? 1 / ((1 + lo) * (1 + li)) : 1 / (1 + lo + li);
            return double(vis * F * g2);
        }
        const ld sin2_t = (1 - c * c) / (eta * eta);
        if (sin2_t >= 1) return 0.0;
        const ld cos_t = std::sqrt(1 - sin2_t);
        const Dir wt = {-wo.x / eta + (c / eta - cos_t) * h.x, -wo.y / eta + (c / eta - cos_t) * h.y,
                        -wo.z / eta + (c / eta - cos_t) * h.z};
        if (wt.z >= 0) return 0.0;
        const ld lt = ggx_lambda({wt.x, wt.y, -wt.z}, alpha, alpha);
        const ld g2 = shadowing == DielectricShadowing::Separable ? 1 / ((1 + lo) * (1 + lt))
                      : shadowing == DielectricShadowing::Cycles
                          ? 1 / (1 + lo + lt)
                          : std::exp(std::lgamma(1 + lo) + std::lgamma(1 + lt) - std::lgamma(2 + lo + lt));
        return double(vis * (1 - F) * g2);
    };
    // Per theta_h the azimuths phi of h in [0, pi] (the integrand is even in phi) where the
    // integrand has a cut or a kink, in closed form from wo.h = A + B cos(phi), A = mu_o cos(th),
    // B = sin_o sin(th): wo.h = 0 (visibility), wr.z = 2 (wo.h) cos(th) - mu_o = 0 (reflection),
    // wo.h = sqrt(1 - eta^2) (total internal reflection, eta < 1). The inner integral runs over the
    // pieces between them, the outer one over theta_h split at multiples of alpha.
    const ld sin_o = std::sqrt(std::max<ld>(0, 1 - mu_o * mu_o));
    const ld c_crit = eta < 1 ? std::sqrt(1 - eta * eta) : -1;
    // tanh-sinh in phi: the pieces end where 1 - F grows like a square root (total internal
    // reflection), which the double-exponential rule integrates at full speed.
    boost::math::quadrature::tanh_sinh<double> tanh_sinh;
    auto split = [&](bool transmit) {
        auto inner = [&](double th) -> double {
            const ld A = mu_o * std::cos((ld)th), B = sin_o * std::sin((ld)th);
            std::vector<double> cuts = {0.0, double(kPi)};
            auto cut_at = [&](ld c) {  // phi where wo.h = c
                if (B > 1e-300L) {
                    const ld x = (c - A) / B;
                    if (x > -1 && x < 1) cuts.push_back(double(std::acos(x)));
                }
            };
            cut_at(0);
            if (std::cos((ld)th) > 0) cut_at(mu_o / (2 * std::cos((ld)th)));
            if (c_crit > 0) cut_at(c_crit);
            std::sort(cuts.begin(), cuts.end());
            // Where the refracted direction crosses the horizon (wt.z = 0; eta < 1 only), found
            // by a scan of 64 points per piece and bisection.
            auto wt_z = [&](double ph) -> ld {
                const Dir h = dir(th, ph);
                const ld c = dot(wo, h), sin2_t = (1 - c * c) / (eta * eta);
                if (c <= 0 || sin2_t >= 1) return 1;
                return -wo.z / eta + (c / eta - std::sqrt(1 - sin2_t)) * h.z;
            };
            if (transmit && eta < 1) {
                const std::vector<double> pieces = cuts;
                for (size_t i = 0; i + 1 < pieces.size(); ++i)
                    for (int k = 0; k < 64; ++k) {
                        double lo = pieces[i] + (pieces[i + 1] - pieces[i]) * k / 64.0;
                        double hi = pieces[i] + (pieces[i + 1] - pieces[i]) * (k + 1) / 64.0;
                        const bool below = wt_z(lo) < 0;
                        if (below == (wt_z(hi) < 0)) continue;
                        for (int b = 0; b < 60; ++b) {
                            const double mid = 0.5 * (lo + hi);
                            ((wt_z(mid) < 0) == below ? lo : hi) = mid;
                        }
                        cuts.push_back(0.5 * (lo + hi));
                    }
                std::sort(cuts.begin(), cuts.end());
            }
            double sum = 0.0;
            for (size_t i = 0; i + 1 < cuts.size(); ++i) {
                // A piece where the integrand vanishes (h not facing wo, wr below the horizon,
                // total internal reflection) is skipped: a relative tolerance cannot be met on 0.
                const ld c = A + B * std::cos(0.5L * (cuts[i] + cuts[i + 1]));
                const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
                const bool live = c > 0 && (transmit ? c > c_crit && wt_z(mid) < 0 : 2 * c * std::cos((ld)th) > mu_o);
                if (cuts[i + 1] - cuts[i] > 1e-12 && live)
                    sum += tanh_sinh.integrate([&](double ph, double) { return integrand(transmit, th, ph); }, cuts[i],
                                               cuts[i + 1], 0.1 * tol);
            }
            return 2 * sum * std::sin(th);
        };
        std::vector<double> breaks = {0.0};
        for (double k : {3.0, 30.0, 300.0})
            if (std::atan(double(k * alpha)) < double(kPi / 2) - 1e-9) breaks.push_back(std::atan(double(k * alpha)));
        breaks.push_back(double(kPi / 2));
        double sum = 0.0;
        for (size_t i = 0; i + 1 < breaks.size(); ++i) sum += integrate(inner, breaks[i], breaks[i + 1], tol);
        return sum;
    };
    r = split(false);
    t = split(true);
}

}  // namespace ref

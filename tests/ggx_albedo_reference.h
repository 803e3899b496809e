// Independent references shared by the table tests: the directional albedo of isotropic GGX by
// quadrature cheap enough for whole tables, and a parallel loop to fill them.
#pragma once

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "reference/reference.h"

namespace testing {

/// Directional albedo of isotropic GGX (F = 1, height-correlated G2) from the textbook pieces in
/// reference.h, by quadrature in half-vector space, made cheap enough for 1024 texels.
///
///   E(mu_o) = integral of f cos_i dw_i, w_i = reflect(w_o, h), dw_i = 4 (o.h) dw_h
///           = (1 / mu_o) integral of D(h) G2(o, i) (o.h) dw_h  over the h with mu_i > 0,
///   mu_i = 2 (o.h) cos th - mu_o,  o.h = sin_o sin th cos dphi + mu_o cos th.
///
/// mu_i > 0 is one azimuth interval |dphi| < dmax(th), cos dmax = -mu_o cos 2th / (sin_o sin 2th)
/// (it implies o.h > 0): every azimuth up to th1 = (pi/2 - th_o)/2, none from th2 = pi/4 + th_o/2.
/// The reference depends on (mu, alpha) only: the integrand is even in dphi, D and Lambda(o) are
/// fixed per th, and G2 depends on w_i only through mu_i (isotropic), so
///   - outer: th substituted by u = tan^2 th / (alpha^2 + tan^2 th) (the cdf of D cos in th, which
///     flattens the peak of D for small alpha), Jacobian dth/du applied explicitly, split at th1
///     (where the azimuth range starts to shrink); Boost's tanh-sinh, which also takes the
///     square-root behaviour at th2 and th1;
///   - inner: dphi over [0, dmax], `n` point Gauss-Legendre (Boost), with dphi = dmax s (2 - s)
///     when dmax < pi so that the nodes cluster where mu_i -> 0 and G2 has a layer of width ~alpha.
/// `n` = 30 with tol = 1e-9 agrees with ref::albedo_halfvector (adaptive Gauss-Kronrod in (th, phi))
/// at tol 1e-10 to 2.4e-13 on 40 texels of this table including the corners; the test also checks
/// the reference against a coarser setting (n = 20, tol = 1e-8) on every texel and against
/// albedo_halfvector on a few.
template <int N>
double ggx_albedo_reference(double alpha, double mu_o, double tol) {
    using ref::ld;
    using ref::kPi;
    thread_local boost::math::quadrature::tanh_sinh<double> outer_rule;
    const ld th_o = std::acos((ld)mu_o), sin_o = std::sin(th_o);
    const ld lam_o = ref::ggx_lambda(ref::Dir{sin_o, 0, (ld)mu_o}, alpha, alpha);
    const ld a2 = (ld)alpha * alpha;
    auto u_of = [&](ld th) {
        const ld t2 = std::tan(th) * std::tan(th);
        return double(t2 / (a2 + t2));
    };
    auto outer = [&](double u) -> double {
        if (!(u > 0 && u < 1)) return 0.0;
        const ld s = std::sqrt((ld)u / (1 - (ld)u));  // tan th / alpha
        const ld th = std::atan(alpha * s);
        const ld dth_du = alpha / (1 + a2 * s * s) / (2 * s * (1 - (ld)u) * (1 - (ld)u));
        const ld st = std::sin(th), ct = std::cos(th), c2 = ct * ct - st * st, s2 = 2 * st * ct;
        ld dmax = kPi;
        if (sin_o * s2 > 1e-300L) {
            const ld c = -(ld)mu_o * c2 / (sin_o * s2);
            dmax = c >= 1 ? 0 : c <= -1 ? kPi : std::acos(c);
        } else if (c2 <= 0) {
            dmax = 0;
        }
        if (dmax <= 0) return 0.0;
        auto g = [&](double dphi) -> double {  // G2 (o.h)
            const ld oh = sin_o * st * std::cos((ld)dphi) + mu_o * ct;
            const ld mu_i = 2 * oh * ct - mu_o;
            if (oh <= 0 || mu_i <= 0) return 0.0;
            const ld lam_i = ref::ggx_lambda(ref::Dir{std::sqrt(1 - mu_i * mu_i), 0, mu_i}, alpha, alpha);
            return double(oh / (1 + lam_o + lam_i));
        };
        using GL = boost::math::quadrature::gauss<double, N>;
        const double azimuth =
            dmax >= kPi ? GL::integrate(g, 0.0, double(kPi))
                        : GL::integrate([&](double x) { return double(2 * dmax * (1 - x) * g(double(dmax * x * (2 - x)))); },
                                        0.0, 1.0);
        const ld d = ref::ggx_d(ref::Dir{st, 0, ct}, alpha, alpha);
        return double(2 * azimuth * d * st * dth_du / mu_o);
    };
    // The (x, complement) form of tanh-sinh: Boost's one-argument form asserts on intervals
    // whose ends are close to 1 (u1 and u2 for small alpha).
    auto f = [&](double u, double) { return outer(u); };
    const double u1 = u_of((kPi / 2 - th_o) / 2), u2 = u_of(kPi / 4 + th_o / 2);
    // At mu_o = 1 the two angles meet (th1 = th2 = pi/4): the second piece is empty.
    return outer_rule.integrate(f, 0.0, u1, tol) + (u2 > u1 ? outer_rule.integrate(f, u1, u2, tol) : 0.0);
}

/// Runs fn(k) for k in [0, n) on the machine's cores.
template <class Fn>
void parallel_for(size_t n, Fn fn) {
    const unsigned workers = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
    std::atomic<size_t> next{0};
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < workers; ++w)
        pool.emplace_back([&] {
            for (size_t k = next++; k < n; k = next++) fn(k);
        });
    for (auto& t : pool) t.join();
}


}  // namespace testing

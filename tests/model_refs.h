// Independent reference albedos for every model of issue 3, keyed by the model spec's
// parameters (benchmarks/reference/reference.h holds the formulas). Shared by test_models_device.cpp.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "reference/reference.h"

namespace modelref {

/// One model configuration of the accuracy grid: its spec and its reference albedo E(mu).
struct Case {
    std::string spec;
    std::function<double(double mu)> albedo;
};

inline std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

/// The Blinn exponent with the same width as a Beckmann alpha (Walter et al. 2007 sec. 5.2).
inline double blinn_n_for_alpha(double alpha) { return 2 / (alpha * alpha) - 2; }

inline Case beckmann(double a, bool corr, double tol = 1e-6) {
    return {"beckmann:alpha=" + num(a) + ",shadowing=" + (corr ? "correlated" : "separable"), [=](double mu) {
                return ref::albedo_halfvector(
                    [=](ref::Dir o, ref::Dir i) { return ref::beckmann_f(o, i, a, a, corr); }, mu, 0.0, tol);
            }};
}
inline Case ggx(double a, bool corr, double tol = 1e-6) {
    return {"ggx:alpha=" + num(a) + ",shadowing=" + (corr ? "correlated" : "separable"), [=](double mu) {
                return ref::albedo_halfvector([=](ref::Dir o, ref::Dir i) { return ref::ggx_f(o, i, a, a, corr); },
                                              mu, 0.0, tol);
            }};
}
inline Case torrance_sparrow(ref::Dist d, double a, double tol = 1e-7) {
    const std::string name = d == ref::Dist::Blinn ? "blinn" : d == ref::Dist::Beckmann ? "beckmann" : "ggx";
    const double p = d == ref::Dist::Blinn ? blinn_n_for_alpha(a) : a;
    const std::string key = d == ref::Dist::Blinn ? ",n=" : ",alpha=";
    return {"torrance-sparrow:d=" + name + key + num(p), [=](double mu) {
                return ref::albedo_halfvector(
                    [=](ref::Dir o, ref::Dir i) { return ref::torrance_sparrow_f(o, i, d, p); }, mu, 0.0, tol,
                    [=](ref::ld th) { return ref::vgroove_kinks(mu, th); });
            }};
}
inline Case blinn_phong(double n, double tol = 1e-7) {
    const double k = (n + 2) / (2 * M_PI);
    return {"blinn-phong:n=" + num(n) + ",normalized=1", [=](double mu) {
                // Absolute-error quadrature (no kinks to split at): narrow lobes stay cheap.
                return ref::albedo_halfvector([=](ref::Dir o, ref::Dir i) { return ref::blinn_phong_f(o, i, n, k); },
                                              mu, 0.0, tol, [](ref::ld) { return std::vector<ref::ld>{}; });
            }};
}
inline Case phong(double n, double tol = 1e-8) {
    const double k = (n + 2) / (2 * M_PI);
    return {"phong:n=" + num(n) + ",normalized=1", [=](double mu) {
                return ref::albedo_about_mirror([=](ref::Dir o, ref::Dir i) { return ref::phong_f(o, i, n, k, false); },
                                                mu, 1 / std::sqrt(n + 1), tol);
            }};
}
inline Case phong_original(double n, double tol = 1e-8) {
    const double ks = (n + 1) / (2 * M_PI);  // albedo 1 at normal incidence
    return {"phong-original:n=" + num(n) + ",ks=" + num(ks), [=](double mu) {
                return ref::albedo_about_mirror([=](ref::Dir o, ref::Dir i) { return ref::phong_f(o, i, n, ks, true); },
                                                mu, 1 / std::sqrt(n + 1), tol);
            }};
}
inline Case oren_nayar(double sigma, double rho) {
    return {"oren-nayar:sigma=" + num(sigma) + ",rho=" + num(rho),
            [=](double mu) { return ref::albedo_oren_nayar(sigma, rho, mu, 1e-9); }};
}

/// sheen:roughness=R (alpha = R^2) with the charlie or the ashikhmin visibility.
inline Case sheen(double roughness, bool charlie, double tol = 1e-10) {
    const double alpha = roughness * roughness;
    return {"sheen:roughness=" + num(roughness) + ",visibility=" + (charlie ? "charlie" : "ashikhmin"),
            [=](double mu) { return ref::albedo_sheen(alpha, charlie, mu, tol); }};
}

}  // namespace modelref

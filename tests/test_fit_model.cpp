// `brdfbake fit` (host/fit/model_fit.h): an analytic model fitted to MERL files that the test
// writes from the textbook GGX and Beckmann of the reference library (reference.h, long double)
// times a Fresnel term written here, so that the parameters to recover are known from outside.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <random>
#include <nlohmann/json.hpp>
#include <string>

#include "models/merl_file.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

std::string tmp(const std::string& name) { return "/tmp/brdfbake-fit-" + std::to_string(::getpid()) + "-" + name; }

/// A file of f = D G2 / (4 cos cos) (height-correlated) times Schlick's F with f0 per channel
/// (f0 = f90 = s gives the constant F = s), unmeasured below the horizon and where `hole` says.
template <typename Lobe, typename Hole>
void write_lobe(const std::string& path, Lobe lobe, std::array<double, 3> f0, std::array<double, 3> f90, Hole hole) {
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        if (o[2] <= 0 || i[2] <= 0 || hole(o, i)) return std::array<double, 3>{-1, -1, -1};
        const double f = double(lobe({o[0], o[1], o[2]}, {i[0], i[1], i[2]}));
        double h[3] = {o[0] + i[0], o[1] + i[1], o[2] + i[2]};
        const double n = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        const double c = (o[0] * h[0] + o[1] * h[1] + o[2] * h[2]) / n;
        std::array<double, 3> v;
        for (int k = 0; k < 3; ++k) v[k] = f * (f0[k] + (f90[k] - f0[k]) * std::pow(1 - c, 5));  // Schlick 1994
        return v;
    });
}

/// The fitted value of a channel's parameter, and its standard error.
double value(const nlohmann::json& ch, const std::string& name) { return ch["params"][name]["value"].get<double>(); }
double error(const nlohmann::json& ch, const std::string& name) { return ch["params"][name]["error"].get<double>(); }

nlohmann::json fit_json(const std::string& args) {
    const auto r = testing::run_cli("fit " + args + " --format json");
    INFO(args << "\n" << r.err);
    REQUIRE(r.status == 0);
    return nlohmann::json::parse(r.out);
}

}  // namespace

TEST_CASE("fit: a GGX file's alpha and per-channel scale are recovered, its distance ~ 0", "[fit][cli]") {
    const std::string path = tmp("ggx.binary");
    const double alpha = 0.3;
    const std::array<double, 3> s = {0.9, 0.6, 0.3};
    write_lobe(path, [&](ref::Dir o, ref::Dir i) { return ref::ggx_f(o, i, alpha, alpha, true); }, s, s,
               [](auto&, auto&) { return false; });
    const auto j = fit_json("--target merl:file=" + path + " --model ggx --stride 4");
    REQUIRE(j["channels"].size() == 3);
    for (int c = 0; c < 3; ++c) {
        const auto& ch = j["channels"][c];
        INFO("channel " << ch["channel"]);
        CHECK(value(ch, "alpha") == Approx(alpha).epsilon(0.02));   // the 2%
        CHECK(value(ch, "alpha") == Approx(alpha).epsilon(1e-4));   // measured: ~1e-6
        CHECK(value(ch, "s") == Approx(s[size_t(c)]).epsilon(1e-4));
        // The model matches the file: every residual is rounding, and the error estimate is the
        // optimiser's stop, which covers the deviation from the truth.
        CHECK(error(ch, "alpha") < 1e-5);
        CHECK(error(ch, "s") < 1e-5);
        CHECK(std::fabs(value(ch, "alpha") - alpha) <= error(ch, "alpha"));
        CHECK(std::fabs(value(ch, "s") - s[size_t(c)]) <= error(ch, "s"));
        // The file holds f at its nodes, which are the pairs: the perfect model's distance is
        // the rounding of f * 1500 / scale to a double and of the kernel (double): ~1e-9 at most.
        CHECK(ch["distance"].get<double>() < 1e-5);
        CHECK(ch["unmeasured_share"].get<double>() == 0.0);
        if (c > 0) continue;
        // The printed spec is one the other commands take as it stands (the red channel's).
        const auto r = testing::run_cli("albedo --model '" + ch["model"].get<std::string>() + "' --fresnel '" +
                                        ch["fresnel"].get<std::string>() + "' --mu 0.5");
        CHECK(r.status == 0);
    }
    std::remove(path.c_str());
}

TEST_CASE("fit: a Schlick f0 per channel is recovered with alpha, holes are left out and reported", "[fit][cli]") {
    const std::string path = tmp("schlick.binary");
    const double alpha = 0.15;
    const std::array<double, 3> f0 = {0.95, 0.64, 0.04}, one = {1, 1, 1};
    // Bins with theta_d >= 80 degrees unmeasured (as grazing bins often are in measured files).
    write_lobe(path, [&](ref::Dir o, ref::Dir i) { return ref::ggx_f(o, i, alpha, alpha, true); }, f0, one,
               [](const std::array<double, 3>& o, const std::array<double, 3>& i) {
                   const double c = o[0] * i[0] + o[1] * i[1] + o[2] * i[2];  // cos 2 theta_d
                   return c <= std::cos(2 * 80.0 * 3.14159265358979323846 / 180) + 1e-12;
               });
    const auto j = fit_json("--target merl:file=" + path + " --model ggx --fresnel schlick --stride 3");
    std::mt19937_64 rng(34);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 1 << 22;
    int hits = 0;
    for (int k = 0; k < n; ++k) {
        double w[2][3];
        for (auto& v : w) {  // uniform on the upper hemisphere: z uniform in [0, 1] (Archimedes)
            const double z = u(rng), phi = 2 * 3.14159265358979323846 * u(rng), r = std::sqrt(1 - z * z);
            v[0] = r * std::cos(phi);
            v[1] = r * std::sin(phi);
            v[2] = z;
        }
        hits += w[0][0] * w[1][0] + w[0][1] * w[1][1] + w[0][2] * w[1][2] <= std::cos(160 * 3.14159265358979323846 / 180);
    }
    const double share = double(hits) / n;
    INFO("Monte Carlo share " << share);
    for (int c = 0; c < 3; ++c) {
        const auto& ch = j["channels"][c];
        INFO("channel " << ch["channel"]);
        CHECK(value(ch, "alpha") == Approx(alpha).epsilon(0.02));
        CHECK(value(ch, "f0") == Approx(f0[size_t(c)]).margin(1e-3));
        CHECK(ch["distance"].get<double>() < 1e-5);
        // The share of the pair measure d wo d wi with theta_d >= 80 deg: cos 2 theta_d = wo.wi,
        // so it is P(wo.wi <= cos 160 deg) for wo, wi uniform on the hemisphere (Monte Carlo
        // here: 0.00445 +- 3e-5). The fit's grid includes a bin by its node (at the horizon too):
        // measured 0.00479, 7.5 % over.
        CHECK(std::fabs(ch["unmeasured_share"].get<double>() - share) <= 0.15 * share);
    }
    CHECK(j["unmeasured_bins"].get<double>() > 0);
    std::remove(path.c_str());
}

TEST_CASE("fit: an analytic Beckmann target, and GGX fitted to it (a worse fit: a larger distance)", "[fit][cli]") {
    const auto b = fit_json("--target beckmann:alpha=0.4 --model beckmann --fresnel none --stride 3");
    REQUIRE(b["channels"].size() == 1);
    CHECK(value(b["channels"][0], "alpha") == Approx(0.4).epsilon(1e-3));
    CHECK(b["channels"][0]["distance"].get<double>() < 1e-6);
    const auto g = fit_json("--target beckmann:alpha=0.4 --model ggx --fresnel none --stride 3");
    CHECK(g["channels"][0]["distance"].get<double>() > 1e-3);
}

TEST_CASE("fit: bad input is one error line, exit status 2", "[fit][cli][quick]") {
    for (const std::string args :
         {"--target merl:file=/nonexistent.binary", "--target ggx:alpha=0.3 --model ggx:alpha=0.2",
          "--target ggx:alpha=0.3 --metric cubic", "--target ggx:alpha=0.3 --fresnel dielectric",
          "--target merl:file=builtin:lambert --anisotropic",
          "--target ggx:alpha=0.3 --model lambert", "--target ggx:alpha=0.3 --stride 0",
          "--target merl:file=/dev/zero", "--target ggx:alpha=0.3 --plot fit.txt"}) {
        const auto r = testing::run_cli("fit " + args);
        INFO(args << "\n" << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error:", 0) == 0);
        CHECK(r.out.empty());
    }
}

namespace {

/// The exact conductor Fresnel reflectance of unpolarised light, complex index n = eta + ik
/// (Born and Wolf, Principles of Optics, sec. 13.2: the Fresnel equations with a complex index).
double conductor_fresnel(double cos_i, double eta, double k) {
    const std::complex<double> n(eta, k), c(cos_i, 0.0);
    const std::complex<double> ct = std::sqrt(1.0 - (1.0 - c * c) / (n * n));
    const double rs = std::norm((c - n * ct) / (c + n * ct)), rp = std::norm((n * c - ct) / (n * c + ct));
    return 0.5 * (rs + rp);
}

}  // namespace

TEST_CASE("fit: an anisotropic target's alpha_x and alpha_y are recovered (automatic)", "[fit][cli]") {
    const auto j = fit_json("--target ggx:alpha_x=0.2,alpha_y=0.45 --model ggx --fresnel none --stride 5");
    REQUIRE(j["channels"].size() == 1);
    const auto& ch = j["channels"][0];
    CHECK(value(ch, "alpha_x") == Approx(0.2).epsilon(0.02));  // the 2%
    CHECK(value(ch, "alpha_y") == Approx(0.45).epsilon(0.02));
    CHECK(value(ch, "alpha_x") == Approx(0.2).epsilon(1e-4));
    CHECK(value(ch, "alpha_y") == Approx(0.45).epsilon(1e-4));
    CHECK(ch["distance"].get<double>() < 1e-5);
    // The printed spec runs as it stands.
    const auto r = testing::run_cli("albedo --model '" + ch["model"].get<std::string>() + "' --fresnel none --mu 0.5");
    CHECK(r.status == 0);
    // An isotropic target with --anisotropic: alpha_x = alpha_y.
    const auto i = fit_json("--target beckmann:alpha=0.3 --model beckmann --fresnel none --stride 6 --anisotropic");
    CHECK(value(i["channels"][0], "alpha_x") == Approx(0.3).epsilon(1e-3));
    CHECK(value(i["channels"][0], "alpha_y") == Approx(0.3).epsilon(1e-3));
}

TEST_CASE("fit: a conductor's eta and k per channel are recovered from a gold file", "[fit][cli]") {
    const std::string path = tmp("gold.binary");
    const double alpha = 0.25;
    // Gold at 650, 550 and 450 nm (Johnson and Christy 1972, rounded).
    const std::array<double, 3> eta = {0.166, 0.43, 1.38}, kk = {3.15, 2.45, 1.85};
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        if (o[2] <= 0 || i[2] <= 0) return std::array<double, 3>{-1, -1, -1};
        const double f = double(ref::ggx_f({o[0], o[1], o[2]}, {i[0], i[1], i[2]}, alpha, alpha, true));
        double h[3] = {o[0] + i[0], o[1] + i[1], o[2] + i[2]};
        const double n = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        const double c = (o[0] * h[0] + o[1] * h[1] + o[2] * h[2]) / n;
        std::array<double, 3> v;
        for (int k = 0; k < 3; ++k) v[k] = f * conductor_fresnel(c, eta[k], kk[k]);
        return v;
    });
    const auto j = fit_json("--target merl:file=" + path + " --model ggx --fresnel conductor --stride 4");
    for (int c = 0; c < 3; ++c) {
        const auto& ch = j["channels"][c];
        INFO("channel " << ch["channel"] << " " << ch["fresnel"]);
        CHECK(value(ch, "alpha") == Approx(alpha).epsilon(0.02));
        CHECK(value(ch, "eta") == Approx(eta[size_t(c)]).epsilon(0.05));  // the 5%
        CHECK(value(ch, "k") == Approx(kk[size_t(c)]).epsilon(0.05));
        double worst = 0;  // the fitted F curve against gold's, cos theta in [0, 1]
        for (int m = 0; m <= 100; ++m)
            worst = std::max(worst, std::fabs(conductor_fresnel(m / 100.0, value(ch, "eta"), value(ch, "k")) -
                                              conductor_fresnel(m / 100.0, eta[size_t(c)], kk[size_t(c)])));
        CHECK(worst < 1e-3);
        CHECK(ch["fresnel"].get<std::string>().rfind("conductor:", 0) == 0);
    }
    std::remove(path.c_str());
}

TEST_CASE("fit: the standard errors of a noisy file's parameters hold its fits' scatter", "[fit][cli]") {
    // One GGX lobe (alpha 0.3, F = 0.8) in all three channels, each with its own independent
    // noise per bin: f (1 + e)^3 with e normal, sd 1 %, so that the metric's cube root sees the
    // zero-mean noise e g (noise of mean 0 in f would bias the compressed fit, which no error
    // estimate of the scatter covers): three fits of the same parameters. Their deviations
    // from the truth, in units of the reported errors, are three draws of a standard normal if
    // the errors are right: the sum of their squares is chi-square with 3 degrees of freedom,
    // inside [0.024, 16.3] (its 0.1 % and 99.9 % quantiles) unless the errors are off by a
    // factor of ~6 or more either way (or the test is unlucky, 0.2 %: the seed is fixed).
    const std::string path = tmp("noisy.binary");
    const double alpha = 0.3, s = 0.8;
    std::mt19937_64 rng(3434);
    std::normal_distribution<double> noise(0.0, 0.01);
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        if (o[2] <= 0 || i[2] <= 0) return std::array<double, 3>{-1, -1, -1};
        const double f = s * double(ref::ggx_f({o[0], o[1], o[2]}, {i[0], i[1], i[2]}, alpha, alpha, true));
        std::array<double, 3> v;
        for (double& x : v) x = f * std::pow(std::max(0.0, 1.0 + noise(rng)), 3);
        return v;
    });
    const auto j = fit_json("--target merl:file=" + path + " --model ggx --stride 4");
    double chi_alpha = 0, chi_s = 0;
    for (int c = 0; c < 3; ++c) {
        const auto& ch = j["channels"][c];
        INFO("channel " << ch["channel"] << " alpha " << value(ch, "alpha") << " +- " << error(ch, "alpha") << ", s "
                        << value(ch, "s") << " +- " << error(ch, "s"));
        CHECK(error(ch, "alpha") > 0);
        CHECK(error(ch, "s") > 0);
        chi_alpha += std::pow((value(ch, "alpha") - alpha) / error(ch, "alpha"), 2);
        chi_s += std::pow((value(ch, "s") - s) / error(ch, "s"), 2);
    }
    INFO("chi-square alpha " << chi_alpha << ", s " << chi_s);
    CHECK(chi_alpha > 0.024);
    CHECK(chi_alpha < 16.3);
    CHECK(chi_s > 0.024);
    CHECK(chi_s < 16.3);
    std::remove(path.c_str());
}

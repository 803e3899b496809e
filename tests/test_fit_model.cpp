// `brdfbake fit` (host/fit/model_fit.h): an analytic model fitted to MERL files that the test
// writes from the textbook GGX and Beckmann of the reference library (reference.h, long double)
// times a Fresnel term written here, so that the parameters to recover are known from outside.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
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
        CHECK(ch["params"]["alpha"].get<double>() == Approx(alpha).epsilon(0.02));   // the 2%
        CHECK(ch["params"]["alpha"].get<double>() == Approx(alpha).epsilon(1e-4));   // measured: ~1e-6
        CHECK(ch["params"]["amplitude"].get<double>() == Approx(s[size_t(c)]).epsilon(1e-4));
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
        CHECK(ch["params"]["alpha"].get<double>() == Approx(alpha).epsilon(0.02));
        CHECK(ch["params"]["amplitude"].get<double>() == Approx(f0[size_t(c)]).margin(1e-3));
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
    CHECK(b["channels"][0]["params"]["alpha"].get<double>() == Approx(0.4).epsilon(1e-3));
    CHECK(b["channels"][0]["distance"].get<double>() < 1e-6);
    const auto g = fit_json("--target beckmann:alpha=0.4 --model ggx --fresnel none --stride 3");
    CHECK(g["channels"][0]["distance"].get<double>() > 1e-3);
}

TEST_CASE("fit: bad input is one error line, exit status 2", "[fit][cli][quick]") {
    for (const std::string args :
         {"--target merl:file=/nonexistent.binary", "--target ggx:alpha=0.3 --model ggx:alpha=0.2",
          "--target ggx:alpha=0.3 --metric cubic", "--target ggx:alpha=0.3 --fresnel conductor",
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

// The Smith lobes' diffuse=KD (brdf/smith.h: f = f_spec + kd/pi) and `brdfbake fit --diffuse`
// (issue 34, item 5), and the fit's evaluation budget. The truths come from outside: the textbook
// GGX of the reference library (reference.h) plus kd/pi for the evaluation; the GGX albedo by
// Boost.Math quadrature (ggx_albedo_reference.h) plus kd, the closed-form albedo of kd/pi (the
// integral of kd/pi cos theta_i over the hemisphere); MERL files written here from GGX + Lambert
// with known alpha and kd.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/spec.h"
#include "ggx_albedo_reference.h"
#include "models/merl_file.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string tmp(const std::string& name) { return "/tmp/brdfbake-fitd-" + std::to_string(::getpid()) + "-" + name; }

nlohmann::json fit_json(const std::string& args, std::string* err = nullptr) {
    const auto r = testing::run_cli("fit " + args + " --format json");
    INFO(args << "\n" << r.err);
    REQUIRE(r.status == 0);
    if (err) *err = r.err;
    return nlohmann::json::parse(r.out);
}

double value(const nlohmann::json& ch, const std::string& name) { return ch["params"][name]["value"].get<double>(); }

}  // namespace

TEST_CASE("diffuse: ggx with diffuse=kd evaluates to the textbook GGX + kd/pi", "[fit][diffuse]") {
    const double alpha = 0.3, kd = 0.25;
    std::mt19937_64 rng(341);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> wo, wi;
    for (int k = 0; k < 200; ++k) {  // directions on the sphere, some below the horizon
        Vec3 d[2];
        for (Vec3& v : d) {
            do v = {u(rng), u(rng), u(rng)};
            while (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] > 1 || v[0] * v[0] + v[1] * v[1] + v[2] * v[2] < 1e-2);
            const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (double& x : v) x /= n;
        }
        wo.push_back(d[0]);
        wi.push_back(d[1]);
    }
    const std::vector<double> f = evaluate_on_device(testing::engine(), resolve_model("ggx:alpha=0.3,diffuse=0.25"),
                                                     resolve_fresnel("none"), Precision::Double, wo, wi);
    for (size_t k = 0; k < wo.size(); ++k) {
        const bool above = wo[k][2] > 0 && wi[k][2] > 0;
        const double want = above ? double(ref::ggx_f({wo[k][0], wo[k][1], wo[k][2]}, {wi[k][0], wi[k][1], wi[k][2]},
                                                      alpha, alpha, true)) + kd / kPi
                                  : 0.0;
        INFO("pair " << k);
        CHECK(f[k] == Approx(want).epsilon(1e-9).margin(1e-12));
    }
}

TEST_CASE("diffuse: the albedo of ggx with diffuse=kd is GGX's albedo + kd", "[fit][diffuse]") {
    const double alpha = 0.3, kd = 0.25;
    const std::vector<double> mus{0.1, 0.5, 1.0};
    for (Method method : {Method::Importance, Method::Quadrature}) {
        const AlbedoResult r = compute_albedo(
            testing::engine(), testing::albedo_request("ggx:alpha=0.3,diffuse=0.25", mus, method, Precision::Double, 1 << 16));
        for (size_t k = 0; k < mus.size(); ++k) {
            const double exact = testing::ggx_albedo_reference<30>(alpha, mus[k], 1e-10) + kd;
            INFO("method " << int(method) << " mu " << mus[k] << ": " << r.values[k].value << " +- " << r.values[k].error
                           << ", reference " << exact);
            CHECK(std::fabs(r.values[k].value - exact) <= r.values[k].error + 1e-12);
            CHECK(r.values[k].error < 1e-2);
        }
    }
}

TEST_CASE("diffuse: the registry's diffuse_key is exactly the models whose spec takes diffuse=KD", "[fit][diffuse]") {
    // compute_albedo adds kd in closed form for the models the registry marks; a model whose
    // parser took diffuse= without the mark would integrate without its Lambert part.
    for (const ModelTraits& t : model_registry()) {
        bool accepted = true;
        try {
            resolve_model(std::string(t.example) + ",diffuse=0.1");
        } catch (const Error&) {
            accepted = false;
        }
        INFO(t.name);
        CHECK(accepted == t.diffuse_key);
    }
}

TEST_CASE("fit --diffuse: kd and alpha of a GGX + Lambert file are recovered, the spec runs as printed",
          "[fit][diffuse][cli]") {
    const std::string path = tmp("ggx-lambert.binary");
    const double alpha = 0.2;
    const std::array<double, 3> s = {0.9, 0.6, 0.4}, kd = {0.1, 0.35, 0.6};
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        if (o[2] <= 0 || i[2] <= 0) return std::array<double, 3>{-1, -1, -1};
        const double f = double(ref::ggx_f({o[0], o[1], o[2]}, {i[0], i[1], i[2]}, alpha, alpha, true));
        std::array<double, 3> v;
        for (int k = 0; k < 3; ++k) v[size_t(k)] = s[size_t(k)] * f + kd[size_t(k)] / kPi;
        return v;
    });
    std::string err;
    const auto j = fit_json("--target merl:file=" + path + " --model ggx --diffuse --stride 5", &err);
    CHECK(err.empty());
    REQUIRE(j["channels"].size() == 3);
    for (size_t c = 0; c < 3; ++c) {
        const auto& ch = j["channels"][c];
        INFO("channel " << ch["channel"] << ": " << ch["model"]);
        CHECK(value(ch, "alpha") == Approx(alpha).epsilon(0.02));  // the 2%
        CHECK(value(ch, "diffuse") == Approx(kd[c]).epsilon(0.02));
        CHECK(value(ch, "s") == Approx(s[c]).epsilon(0.02));
        CHECK(ch["converged"].get<bool>());
        // The printed spec runs as it stands, and its albedo at normal incidence is the lobe's
        // (alpha, F = s) plus kd: the reference's at the fitted alpha.
        const auto r = testing::run_cli("albedo --model '" + ch["model"].get<std::string>() + "' --fresnel '" +
                                        ch["fresnel"].get<std::string>() + "' --mu 1 --format json");
        REQUIRE(r.status == 0);
        const auto a = nlohmann::json::parse(r.out);
        INFO(r.out);
        const double e = a["results"][0]["albedo"].get<double>(), de = a["results"][0]["error"].get<double>();
        const double want = value(ch, "s") * testing::ggx_albedo_reference<30>(value(ch, "alpha"), 1.0, 1e-10) +
                            value(ch, "diffuse");
        CHECK(std::fabs(e - want) <= de + 1e-9);
    }
    std::remove(path.c_str());
}

TEST_CASE("fit: a fit the evaluation budget stops says so, in the output and on stderr", "[fit][cli]") {
    const auto r = testing::run_cli("fit --target ggx:alpha=0.3 --target-fresnel conductor:eta=0.2,k=3 --model ggx "
                                    "--fresnel conductor --stride 6 --max-evaluations 20 --format json");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK_FALSE(j["channels"][0]["converged"].get<bool>());
    CHECK(j["channels"][0]["budget"].get<int>() == 20);
    CHECK(r.err.rfind("brdfbake: warning: the fit stopped at its budget of 20 evaluations", 0) == 0);
    const auto t = testing::run_cli("fit --target ggx:alpha=0.3 --model ggx --fresnel none --stride 6 --max-evaluations 20");
    CHECK(t.out.find("stopped at its budget of 20 evaluations") != std::string::npos);
}

TEST_CASE("diffuse: bad keys and flags are one error line, exit status 2", "[fit][diffuse][cli][quick]") {
    for (const std::string args :
         {"albedo --model ggx:alpha=0.3,diffuse=1.5 --mu 0.5", "albedo --model ggx:alpha=0.3,diffuse=-0.1 --mu 0.5",
          "albedo --model lambert:diffuse=0.2 --mu 0.5",
          "albedo --model ggx:alpha=0.3,scattering=multiple,diffuse=0.2 --mu 0.5",
          "fit --target ggx:alpha=0.3 --model phong --diffuse",
          "fit --target ggx:alpha=0.3 --model ggx:diffuse=0.2 --diffuse",
          "fit --target ggx:alpha=0.3 --model ggx --max-evaluations 5"}) {
        const auto r = testing::run_cli(args);
        INFO(args << "\n" << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error:", 0) == 0);
        CHECK(r.out.empty());
    }
}

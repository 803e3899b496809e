// f(wo, wi) of the multiple-scattering Smith microsurface by the walks' next-event estimation
// (brdf/random_walk.h, integrate/random_walk.h walk_eval; Heitz et al. 2016's eval), from outside:
// its first order against the textbook height-correlated GGX and Beckmann f (benchmarks/reference,
// long double, times the Fresnel term computed here); its integral of f cos over wi (by cosine-
// weighted directions drawn here) against the walk's own albedo (an independent estimator: the
// escaping weight, not the next-event sum); reciprocity f(wo, wi) = f(wi, wo) from walks started on
// either side; and the commands that now take scattering=multiple (check, lobe, lut albedo).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <sstream>

#include "brdfbake/brdf/random_walk.h"
#include "integrate/random_walk.h"
#include "model_refs.h"
#include "support.h"
#include "test_random_walk_pairs.h"

using namespace brdfbake;

namespace {

Vec3 unit(double mu, double phi) {
    const double s = std::sqrt(1 - mu * mu);
    return {s * std::cos(phi), s * std::sin(phi), mu};
}

WalkEvalRequest eval_request(const ModelConfig& m, const std::string& fresnel, std::uint64_t walks) {
    REQUIRE(m.simulated);
    WalkEvalRequest req;
    req.model = m.id;
    req.fresnel = resolve_fresnel(fresnel);
    req.samples = walks;
    return req;
}

double schlick(double c, double f0) { return f0 + (1 - f0) * std::pow(1 - c, 5); }

}  // namespace

TEST_CASE("walk eval: the first order is the textbook height-correlated lobe's f", "[random-walk]") {
    // f1 = F(wo.h) D(h) G2(wo, wi) / (4 wo.z wi.z), G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) [H14 eq. 99]:
    // benchmarks/reference's D and Lambda; the conductor with Schlick f0 = 0.5, the dielectric with
    // the exact Fresnel term of eta 1.5 (reference.h).
    const std::vector<std::array<double, 4>> dirs = {
        {0.9, 0.0, 0.7, 3.0}, {0.5, 0.0, 0.5, M_PI}, {0.3, 0.4, 0.8, 2.0}, {0.95, 0.0, 0.2, 1.0}};
    for (bool beckmann : {false, true})
        for (const std::string& keys : {std::string("alpha_x=0.3,alpha_y=0.6"), std::string("alpha=0.8")})
            for (bool dielectric : {false, true}) {
                const std::string spec = std::string(beckmann ? "beckmann:" : "ggx:") + keys + ",scattering=multiple" +
                                         (dielectric ? ",eta=1.5" : "");
                const ModelConfig m = resolve_model_simulated(spec);
                WalkEvalRequest req = eval_request(m, dielectric ? "none" : "schlick:f0=0.5", 1 << 14);
                for (const auto& d : dirs) req.pairs.push_back({unit(d[0], d[1]), unit(d[2], d[3]), m.params});
                const WalkEvalResult r = walk_eval(testing::engine(), req);
                const double ax = m.params[BB_SMITH_ALPHA_X], ay = m.params[BB_SMITH_ALPHA_Y];
                for (size_t k = 0; k < dirs.size(); ++k) {
                    const auto& d = dirs[k];
                    const ref::Dir wo = ref::dir_mu(d[0], d[1]), wi = ref::dir_mu(d[2], d[3]);
                    const ref::ld f = beckmann ? ref::beckmann_f(wo, wi, ax, ay, true) : ref::ggx_f(wo, wi, ax, ay, true);
                    const double c = double(ref::dot(wo, ref::normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z})));
                    const double expected = double(f) * (dielectric ? ref::fresnel_dielectric(c, 1.5) : schlick(c, 0.5));
                    INFO(spec << " pair " << k << ": " << r.single[k].value << " +- " << r.single[k].error << " vs "
                              << expected);
                    CHECK(std::fabs(r.single[k].value - expected) <= r.single[k].error + 1e-5 * expected);
                    CHECK(r.f[k].value >= r.single[k].value);  // the higher orders add (they can round to nothing)
                }
            }
}

TEST_CASE("walk eval: f cos integrated over wi is the walk's albedo (two estimators)", "[random-walk]") {
    // E(wo) = integral of f cos = pi E[f(wo, wi)] over cosine-distributed wi (drawn here, 4096
    // directions, 64 walks each): against walk_albedo's escaping weight, and the first orders
    // against each other; 4 standard errors of the difference (the spread over the directions is
    // the integral's whole noise: every pair has its own walks).
    struct Case {
        std::string spec, fresnel;
    };
    for (const Case& c : {Case{"ggx:alpha=0.9,scattering=multiple", "schlick:f0=0.5"},
                          Case{"beckmann:alpha=0.8,scattering=multiple", "none"},
                          Case{"ggx:alpha=0.6,scattering=multiple,eta=1.5", "none"}}) {
        const ModelConfig m = resolve_model_simulated(c.spec);
        const double mu = 0.6;
        WalkEvalRequest req = eval_request(m, c.fresnel, 64);
        req.replicas = 2;
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (int k = 0; k < 4096; ++k)
            req.pairs.push_back({unit(mu, 0.0), unit(std::sqrt(u(rng)), 2 * M_PI * u(rng)), m.params});
        const WalkEvalResult r = walk_eval(testing::engine(), req);
        const WalkAlbedo a = testing::walk_albedo_at_mu(m, c.fresnel, mu);
        for (bool single : {false, true}) {
            const std::vector<AlbedoValue>& f = single ? r.single : r.f;
            double se = 0;
            const double mean = testing::pi_mean(f, &se);
            const AlbedoValue& e = single ? a.single : a.energy;
            INFO(c.spec << (single ? " first order" : " every order") << ": integral " << mean << " +- " << se
                        << ", walk albedo " << e.value << " +- " << e.error / 3);
            CHECK(std::fabs(mean - e.value) <= 4 * std::hypot(se, e.error / 3));
            CHECK(se < 0.01);  // the test can see a 4% error
        }
    }
}

TEST_CASE("walk eval: reciprocity f(wo, wi) = f(wi, wo) within the estimates' noise", "[random-walk]") {
    // The two values come from different walks (started from wo, and from wi): their difference
    // within 4/3 of the combined error (errors are 3 standard errors: 4 standard deviations).
    for (const std::string& spec : {std::string("ggx:alpha=0.7,scattering=multiple"),
                                    std::string("beckmann:alpha_x=0.4,alpha_y=0.9,scattering=multiple"),
                                    std::string("ggx:alpha=0.5,scattering=multiple,eta=1.5")}) {
        const ModelConfig m = resolve_model_simulated(spec);
        WalkEvalRequest req = eval_request(m, m.dielectric_walk ? "none" : "schlick:f0=0.3", 1 << 14);
        const std::vector<std::array<double, 4>> dirs = {
            {0.95, 0.0, 0.3, 1.0}, {0.2, 0.5, 0.6, 2.5}, {0.4, 0.0, 0.4, M_PI}, {0.8, 1.0, 0.15, 1.3}};
        for (const auto& d : dirs) {
            req.pairs.push_back({unit(d[0], d[1]), unit(d[2], d[3]), m.params});
            req.pairs.push_back({unit(d[2], d[3]), unit(d[0], d[1]), m.params});
        }
        const WalkEvalResult r = walk_eval(testing::engine(), req);
        for (size_t k = 0; k < r.f.size(); k += 2) {
            const AlbedoValue &a = r.f[k], &b = r.f[k + 1];
            INFO(spec << " pair " << k / 2 << ": " << a.value << " +- " << a.error << " vs " << b.value << " +- " << b.error);
            CHECK(std::fabs(a.value - b.value) <= 4.0 / 3.0 * std::hypot(a.error, b.error));
            CHECK(std::hypot(a.error, b.error) < 0.25 * a.value);  // the comparison can see a 33% asymmetry
        }
    }
}

TEST_CASE("walk eval: Beckmann's multiple scattering passes check's reciprocity (the heavy tail)", "[random-walk]") {
    // Reciprocity is a law of the model: f(a, b) = f(b, a). Beckmann's Lambda of a steep upward ray
    // is exponentially small, so the next event sampled at the intersection's height had infinite
    // variance and the replicas' error hid rare walks carrying most of f: check failed by 7-10
    // standard errors (alpha 0.3-0.5, float and double, 84 pairs; 8.8 at 0.3, 7.1 at 0.5). The pair
    // that failed worst (theta 7.5 and 67.5 deg), from both ends on 4 seeds in float and double,
    // and the whole check at alpha 0.3 and 0.5.
    const ModelConfig m = resolve_model_simulated("beckmann:alpha=0.4,scattering=multiple");
    WalkEvalRequest req = eval_request(m, "none", 4096);
    const Vec3 a = unit(std::cos(67.5 * M_PI / 180), 0.0), b = unit(std::cos(7.5 * M_PI / 180), 22.5 * M_PI / 180);
    testing::check_both_ends(req, a, b, m.params, 0.01, "beckmann alpha 0.4");  // can see a 6% asymmetry
    for (const char* alpha : {"0.3", "0.5"}) {
        const auto r = testing::run_cli(std::string("check --model beckmann:alpha=") + alpha +
                                        ",scattering=multiple --directions 8 --samples 16384");
        INFO(r.out << r.err);
        CHECK(r.status == 0);
        CHECK(r.out.find("verdict: PASS") != std::string::npos);
    }
}

TEST_CASE("walk eval: check, lobe and lut albedo take scattering=multiple", "[random-walk]") {
    // check: reciprocity of the walk estimates passes for GGX (conductor and dielectric), and a
    // scattering=multiple furnace is E <= 1; lobe: the CSV's f against the textbook single lobe
    // (multiple scattering only adds) with an f_error column; lut albedo: a walk table whose E with
    // F = 1 is 1 less the cut-off (within its error, which holds the cut-off).
    for (const std::string& spec : {std::string("ggx:alpha=0.6,scattering=multiple"),
                                    std::string("ggx:alpha=0.4,scattering=multiple,eta=1.5")}) {
        const auto r = testing::run_cli("check --model " + spec + " --directions 8 --samples 16384");
        INFO(r.out << r.err);
        CHECK(r.status == 0);
        CHECK(r.out.find("standard errors") != std::string::npos);
        CHECK(r.out.find("verdict: PASS") != std::string::npos);
    }
    const auto lobe = testing::run_cli(
        "lobe --model ggx:alpha=0.5,scattering=multiple --theta-i 40 --resolution 7 --walks 4096 --data -");
    REQUIRE(lobe.status == 0);
    std::istringstream in(lobe.out);
    std::string line;
    int rows = 0;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (line.rfind("model,", 0) == 0) {
            CHECK(line == "model,theta_i_deg,theta_o_deg,f,f_cos_theta_i,f_error");
            continue;
        }
        std::vector<double> v;
        std::stringstream cells(line.substr(line.rfind('"') + 2));
        for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
        REQUIRE(v.size() == 5);
        if (std::fabs(v[1]) > 80) continue;  // near the horizon f's error is large (divided by cos)
        const double t = v[1] * M_PI / 180, ti = 40 * M_PI / 180;
        const ref::Dir wi = ref::dir(ti, M_PI), wo = ref::dir(std::fabs(t), t < 0 ? M_PI : 0.0);
        const double single = double(ref::ggx_f(wo, wi, 0.5, 0.5, true));
        INFO(line);
        CHECK(v[2] >= single - v[4]);
        CHECK(v[4] < 0.1 * v[2]);  // 4096 walks: the error is a few percent of f
        ++rows;
    }
    CHECK(rows >= 5);
    const std::string exr = "/tmp/brdfbake-walk3-albedo.exr";
    const auto lut = testing::run_cli("lut albedo --model ggx:scattering=multiple --size 4x4 --samples 16384 -o " + exr);
    INFO(lut.err);
    CHECK(lut.status == 0);
    CHECK(lut.err.find("scattering=multiple") != std::string::npos);
}

// The sheen model (Estevez and Kulla 2017, KHR_materials_sheen) and its tables: the spec, the
// evaluation against the textbook formula (benchmarks/reference/reference.h), the albedo against
// independent Boost.Math quadrature and the closed form of the ashikhmin visibility at normal
// incidence, the energy gain that `check` reports, and the extremes.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/check.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/spec.h"
#include "model_refs.h"
#include "models/params.h"
#include "parity.h"
#include "support.h"

using namespace brdfbake;

namespace {

const bb_params kNoFresnel = {{0}};

double eval(const ModelConfig& m, bb_vec3 wo, bb_vec3 wi) {
    return bb_model_eval(m.id, to_bb_params(m.params), BB_FRESNEL_NONE, kNoFresnel, wo, wi);
}

}  // namespace

TEST_CASE("sheen: spec keys, defaults and the canonical spelling", "[sheen][quick]") {
    const ModelConfig m = resolve_model("sheen:roughness=0.5");
    CHECK(m.params[BB_SHEEN_ALPHA] == 0.25);  // alpha = sheenRoughness^2
    CHECK(m.params[BB_SHEEN_VISIBILITY] == BB_SHEEN_V_CHARLIE);
    CHECK(m.canonical == "sheen:alpha=0.25,visibility=charlie");
    CHECK(resolve_model(m.canonical).params == m.params);
    const ModelConfig a = resolve_model("sheen:alpha=0.09,visibility=ashikhmin");
    CHECK(a.params[BB_SHEEN_VISIBILITY] == BB_SHEEN_V_ASHIKHMIN);
    CHECK_FALSE(a.uses_fresnel);
    CHECK(roughness_slots(a) == std::vector<int>{BB_SHEEN_ALPHA, BB_SHEEN_ALPHA});
    // the ends of the ranges are accepted
    CHECK(resolve_model("sheen:roughness=1").params[BB_SHEEN_ALPHA] == 1.0);
    CHECK(resolve_model("sheen:roughness=0.01").params[BB_SHEEN_ALPHA] == Approx(1e-4));
}

TEST_CASE("sheen: bad keys give one line and exit status 2", "[sheen][cli]") {
    for (const char* spec : {"sheen", "sheen:roughness=0", "sheen:roughness=0.005", "sheen:roughness=1.5",
                             "sheen:roughness=nan", "sheen:alpha=2", "sheen:alpha=0.25,roughness=0.5",
                             "sheen:roughness=0.5,visibility=neubelt", "sheen:roughness=0.5,alpha_x=0.3",
                             "sheen:roughness=0.5,visibility="}) {
        const testing::CliResult r = testing::run_cli(std::string("albedo --model '") + spec + "' --mu 0.5");
        INFO(spec << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(r.out.empty());
    }
}

TEST_CASE("sheen: evaluation equals the textbook formula", "[sheen][quick]") {
    // The shared header (sin^2 of the half vector from the tangential part of wo + wi, the
    // branch-free Lambda) against the angle form of reference.h, in double.
    std::mt19937 rng(18);
    for (double roughness : {0.01, 0.05, 0.3, 0.7, 1.0})
        for (bool charlie : {true, false}) {
            const double alpha = roughness * roughness;
            const ModelConfig m = resolve_model("sheen:roughness=" + modelref::num(roughness) +
                                                ",visibility=" + (charlie ? "charlie" : "ashikhmin"));
            int worse = 0, compared = 0;
            for (int i = 0; i < 2000; ++i) {
                const Vec3 o = testing::random_dir(rng, 1e-4), in = testing::random_dir(rng, 1e-4);
                const double got = eval(m, bb_v3(o[0], o[1], o[2]), bb_v3(in[0], in[1], in[2]));
                const double want = double(ref::sheen_f({o[0], o[1], o[2]}, {in[0], in[1], in[2]}, alpha, charlie));
                if (want < 1e-250) continue;  // D underflows alike
                ++compared;
                worse += !(std::fabs(got - want) <= 1e-9 * want);
            }
            INFO("roughness " << roughness << (charlie ? " charlie" : " ashikhmin") << ": " << worse << " of "
                              << compared << " beyond 1e-9");
            CHECK(compared > 100);
            CHECK(worse == 0);
        }
}

TEST_CASE("sheen: finite and non-negative at the extremes", "[sheen][quick]") {
    // roughness at the floor (0.01) and 1, wo and wi down to mu = 1e-7 and at the normal, both
    // visibilities, and the sampler's weights at u1 = 0 and u1 -> 1.
    int bad = 0;
    for (const char* spec : {"sheen:roughness=0.01", "sheen:roughness=1", "sheen:roughness=0.01,visibility=ashikhmin",
                             "sheen:roughness=1,visibility=ashikhmin"}) {
        const ModelConfig m = resolve_model(spec);
        for (double mo : {1e-7, 1e-3, 0.5, 1.0})
            for (double mi : {1e-7, 1e-3, 0.5, 1.0})
                for (double dphi : {0.0, 0.5 * M_PI, M_PI}) {
                    const double f = eval(m, bb_dir_from_mu_phi(mo, 0.0), bb_dir_from_mu_phi(mi, dphi));
                    bad += !(std::isfinite(f) && f >= 0.0);
                    for (double u1 : {0.0, 1e-9, 0.5, 1.0 - 1e-16})
                        for (double u2 : {0.0, 0.5}) {
                            const bb_sample s = bb_model_sample(m.id, to_bb_params(m.params), BB_FRESNEL_NONE,
                                                                kNoFresnel, bb_dir_from_mu_phi(mo, 0.0), u1, u2);
                            bad += !(std::isfinite(s.weight) && s.weight >= 0.0);
                        }
                }
    }
    CHECK(bad == 0);
}

TEST_CASE("sheen: the ashikhmin albedo at normal incidence has its closed form 2^(-k/2)/(k+4)", "[sheen][device]") {
    // k = 1/alpha; the closed form is derived in reference.h, the kernel integrates numerically.
    std::vector<double> roughness = {0.1, 0.3, 0.5, 0.7, 1.0};
    std::vector<AlbedoCell> cells;
    for (double r : roughness) {
        const ModelConfig m = resolve_model("sheen:roughness=" + modelref::num(r) + ",visibility=ashikhmin");
        cells.push_back({1.0, 0.0, m.params});
    }
    AlbedoRequest req = testing::albedo_request("sheen:roughness=1,visibility=ashikhmin", {1.0}, Method::Quadrature,
                                                Precision::Double, 4 * 64 * 64);
    req.cells = cells;
    const AlbedoResult res = compute_albedo(testing::engine(), req);
    for (size_t i = 0; i < roughness.size(); ++i) {
        const double exact = ref::albedo_sheen_ashikhmin_normal(roughness[i] * roughness[i]);
        INFO("roughness " << roughness[i] << ": " << res.values[i].value << " +- " << res.values[i].error << ", exact "
                          << exact);
        CHECK(std::fabs(res.values[i].value - exact) <= res.values[i].error + 1e-12);
        CHECK(res.values[i].error < 1e-8);
    }
    CHECK(std::fabs(ref::albedo_sheen_ashikhmin_normal(1.0) - std::sqrt(2.0) / 10) < 1e-15);
}

TEST_CASE("sheen: albedo against independent quadrature, both visibilities, float and double", "[sheen][device]") {
    const std::vector<double> mus = {1e-3, 0.02, 0.2, 0.6, 1.0};
    for (bool charlie : {true, false})
        for (double roughness : {0.05, 0.2, 0.5, 1.0}) {
            const modelref::Case c = modelref::sheen(roughness, charlie);
            std::vector<double> want;
            for (double mu : mus) want.push_back(c.albedo(mu));
            for (Precision p : {Precision::Double, Precision::Float}) {
                // double: the quadrature; float: the default importance sampling
                const bool dbl = p == Precision::Double;
                const AlbedoRequest req = testing::albedo_request(
                    c.spec, mus, dbl ? Method::Quadrature : Method::Importance, p, dbl ? 4 * 128 * 128 : 1u << 18);
                const AlbedoResult r = compute_albedo(testing::engine(), req);
                for (size_t i = 0; i < mus.size(); ++i) {
                    const AlbedoValue& v = r.values[i];
                    INFO(c.spec << " " << precision_name(p) << " mu " << mus[i] << ": " << v.value << " +- " << v.error
                                << ", reference " << want[i]);
                    CHECK(std::fabs(v.value - want[i]) <= v.error + (dbl ? 1e-10 : 1e-6));
                    if (dbl) CHECK(v.error <= 2e-6);  // the comparison has teeth
                }
            }
        }
}

TEST_CASE("sheen: check reports the energy gain, where it is and how much", "[sheen][device]") {
    // charlie at sheenRoughness 0.5 stays below 1; ashikhmin's visibility is no shadowing function
    // and gains at grazing angles, and [EK17]'s fitted Lambda underestimates the shadowing of the
    // narrowest lobes at grazing (E = 4.0 at sheenRoughness 0.05, mu = 1e-3 by the reference).
    CheckOptions o;
    o.precision = Precision::Double;
    SECTION("charlie, sheenRoughness 0.5: no gain") {
        const CheckReport r = run_check(testing::engine(), resolve_model("sheen:roughness=0.5"), resolve_fresnel("none"), o);
        CHECK_FALSE(r.energy_violation);
        CHECK(r.max_albedo < 1.0);
        CHECK(r.passed());
    }
    for (const char* spec : {"sheen:roughness=0.3,visibility=ashikhmin", "sheen:roughness=0.05"}) {
        const ModelConfig m = resolve_model(spec);
        const CheckReport r = run_check(testing::engine(), m, resolve_fresnel("none"), o);
        const double want = ref::albedo_sheen(m.params[BB_SHEEN_ALPHA], m.params[BB_SHEEN_VISIBILITY] == BB_SHEEN_V_CHARLIE,
                                              r.max_albedo_mu);
        INFO(spec << ": max E " << r.max_albedo << " +- " << r.max_albedo_error << " at mu " << r.max_albedo_mu
                  << ", reference " << want);
        CHECK(r.energy_violation);
        CHECK_FALSE(r.passed());
        CHECK(r.max_albedo > 1.2);
        CHECK(r.max_albedo_mu < 0.05);  // at grazing
        CHECK(std::fabs(r.max_albedo - want) <= r.max_albedo_error + 1e-6);
        const testing::CliResult cli = testing::run_cli(std::string("check --model ") + spec);
        CHECK(cli.status == 1);
        CHECK_THAT(cli.out, Catch::Contains("energy       FAIL  max E = "));
    }
}

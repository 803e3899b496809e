// The models of issue 3 on the host (double): spec registry, published values, normalisation
// identities, the shared functions against the textbook forms of benchmarks/reference/reference.h,
// reciprocity, non-negativity and finiteness down to grazing, and the analytic delta lobes.
#include <catch2/catch.hpp>

#include <boost/math/special_functions/erf.hpp>
#include <random>

#include "brdfbake/analytic.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "models/params.h"
#include "model_refs.h"
#include "reference/reference.h"
#include "spec_checks.h"

using namespace brdfbake;

namespace {

bb_vec3 v3(ref::Dir d) { return bb_v3(double(d.x), double(d.y), double(d.z)); }

const bb_params kNoFresnel = {{0}};

double eval(const ModelConfig& m, bb_vec3 wo, bb_vec3 wi) {
    return bb_model_eval(m.id, to_bb_params(m.params), BB_FRESNEL_NONE, kNoFresnel, wo, wi);
}

// Integral of D(m) cos(theta_m) over the hemisphere (Heitz 2014 eq. 4), split at theta_split
// so that narrow lobes are resolved.
double projected_area(const std::function<double(bb_vec3)>& d, double theta_split = 0.3) {
    auto g = [&](double th, double ph) { return d(v3(ref::dir(th, ph))) * std::cos(th) * std::sin(th); };
    return ref::integrate2(g, 0.0, theta_split, 0.0, 2 * M_PI, 1e-10) +
           ref::integrate2(g, theta_split, M_PI / 2, 0.0, 2 * M_PI, 1e-10);
}

// Every registered spec of the sweeps below: each model, each distribution, each option.
const std::vector<std::string> kAllSpecs = {
    "lambert:rho=0.9",
    "oren-nayar:sigma=0.6,rho=0.9",
    "oren-nayar:sigma=1.5",
    "phong:n=0",
    "phong:n=30,ks=0.7",
    "phong:n=10000,normalized=1",
    "phong-original:n=30",
    "phong-original:n=10000",
    "blinn-phong:n=0",
    "blinn-phong:n=40,normalized=1",
    "blinn-phong:n=10000,normalized=1",
    "torrance-sparrow:d=blinn,n=10000",
    "torrance-sparrow:d=blinn,n=0",
    "torrance-sparrow:d=beckmann,alpha=0.0001",
    "torrance-sparrow:d=beckmann,alpha=10",
    "torrance-sparrow:d=ggx,alpha_x=0.05,alpha_y=0.7",
    "beckmann:alpha=0.0001",
    "beckmann:alpha=0.3",
    "beckmann:alpha=10,shadowing=separable",
    "beckmann:alpha_x=0.02,alpha_y=0.9",
    "ggx:alpha=0.3",
    "mirror",
    "dielectric-specular:eta=1.5",
};

}  // namespace

// ------------------------------------------------------------------------------ registry

TEST_CASE("every model of the course notes is registered", "[models][quick]") {
    const std::vector<std::string> names = model_names();
    for (const char* n : {"lambert", "oren-nayar", "phong", "phong-original", "blinn-phong", "torrance-sparrow", "ggx",
                          "beckmann", "mirror", "dielectric-specular"}) {
        INFO(n);
        CHECK(std::find(names.begin(), names.end(), n) != names.end());
    }
}

TEST_CASE("model specs resolve to slots, defaults and canonical strings", "[models][quick]") {
    using testing::check_resolves;
    const ModelConfig on = check_resolves("oren-nayar:sigma=0.3", BB_MODEL_OREN_NAYAR, {{BB_OREN_NAYAR_RHO, 1.0}},
                                          "oren-nayar:sigma=0.3,rho=1");
    CHECK_FALSE(on.uses_fresnel);

    check_resolves("phong:n=20,normalized=1", BB_MODEL_PHONG,
                   {{BB_PHONG_N, 20.0}, {BB_PHONG_KS, 1.0}, {BB_PHONG_NORMALIZED, 1.0}}, "phong:n=20,ks=1,normalized=1");
    CHECK(resolve_model("phong-original:n=5,ks=0.5").canonical == "phong-original:n=5,ks=0.5");
    CHECK(resolve_model("blinn-phong:n=8").canonical == "blinn-phong:n=8,ks=1,normalized=0");

    const ModelConfig ts = check_resolves("torrance-sparrow:d=blinn,n=50", BB_MODEL_TORRANCE_SPARROW,
                                          {{BB_TORRANCE_SPARROW_DIST, BB_TS_D_BLINN}}, "torrance-sparrow:d=blinn,n=50");
    CHECK(ts.uses_fresnel);
    const ModelConfig tsd = resolve_model("torrance-sparrow:roughness=0.5");
    CHECK(tsd.params[BB_TORRANCE_SPARROW_DIST] == BB_TS_D_BECKMANN);
    CHECK(tsd.params[BB_TORRANCE_SPARROW_ALPHA_X] == 0.25);
    CHECK(tsd.canonical == "torrance-sparrow:d=beckmann,alpha=0.25");
    const ModelConfig tsa = resolve_model("torrance-sparrow:d=ggx,alpha_x=0.1,alpha_y=0.2");
    CHECK(tsa.anisotropic);
    CHECK(tsa.canonical == "torrance-sparrow:d=ggx,alpha_x=0.1,alpha_y=0.2");

    const ModelConfig b =
        check_resolves("beckmann:alpha=0.2", BB_MODEL_BECKMANN, {}, "beckmann:alpha=0.2,shadowing=correlated");
    CHECK(b.uses_fresnel);
    CHECK_FALSE(b.anisotropic);
    const ModelConfig ba = resolve_model("beckmann:alpha_x=0.1,alpha_y=0.4,shadowing=separable");
    CHECK(ba.anisotropic);
    CHECK(ba.params[BB_BECKMANN_SHADOWING] == 0.0);
    CHECK(ba.canonical == "beckmann:alpha_x=0.1,alpha_y=0.4,shadowing=separable");

    const ModelConfig mi = resolve_model("mirror");
    CHECK(mi.id == BB_MODEL_MIRROR);
    CHECK(mi.uses_fresnel);
    const ModelConfig ds = check_resolves("dielectric-specular:eta=1.5", BB_MODEL_DIELECTRIC_SPECULAR,
                                          {{BB_DIELECTRIC_SPECULAR_ETA, 1.5}}, "dielectric-specular:eta=1.5");
    CHECK_FALSE(ds.uses_fresnel);
    // Canonical strings resolve to themselves.
    for (const auto& s : kAllSpecs) {
        INFO(s);
        const ModelConfig m = resolve_model(s);
        CHECK(resolve_model(m.canonical).canonical == m.canonical);
        CHECK(resolve_model(m.canonical).params == m.params);
    }
}

TEST_CASE("bad specs of the new models are refused", "[models][quick]") {
    for (const char* s : {"oren-nayar", "oren-nayar:sigma=-0.1", "oren-nayar:sigma=2", "oren-nayar:sigma=nan",
                          "phong", "phong:n=-1", "phong:n=10001", "phong:n=5,ks=-1", "phong:n=5,normalized=2",
                          "phong-original:n=5,normalized=1", "blinn-phong:n=inf",
                          "torrance-sparrow:d=blinn", "torrance-sparrow:d=blinn,n=10,alpha=0.2",
                          "torrance-sparrow:d=ggx,n=10", "torrance-sparrow:d=phong,alpha=0.2",
                          "torrance-sparrow:d=beckmann,alpha=0", "beckmann", "beckmann:alpha=1e-5",
                          "beckmann:alpha=0.3,shadowing=none", "mirror:eta=1.5", "dielectric-specular",
                          "dielectric-specular:eta=0", "dielectric-specular:eta=-1.5"}) {
        INFO(s);
        CHECK_THROWS_AS(resolve_model(s), Error);
    }
}

// ------------------------------------------------------------------------ published values

TEST_CASE("published values: Beckmann D and Smith G1", "[models][quick]") {
    // Beckmann alpha = 0.1 at the normal: 1/(pi alpha^2) = 31.830988618...; the issue quotes
    // 31.8309879 (a float evaluation), hence the margin.
    CHECK(bb_beckmann_d(bb_v3(0, 0, 1), 0.1, 0.1) == Approx(31.8309879).margin(1e-6));
    CHECK(bb_beckmann_d(bb_v3(0, 0, 1), 0.1, 0.1) == Approx(1 / (M_PI * 0.01)).epsilon(1e-15));
    const double th = 0.98 * M_PI / 2;
    const bb_vec3 w = bb_v3(std::sin(th), 0, std::cos(th));
    // The issue quotes 0.67333597 for Beckmann: that is Walter et al. 2007 eq. 27's rational
    // approximation (3.535a + 2.181a^2)/(1 + 2.276a + 2.577a^2). The exact erf form, which the
    // shared code implements, gives 0.673463648110502519 (mpmath, 30 digits).
    CHECK(bb_beckmann_g1(w, 0.1, 0.1) == Approx(0.673463648110502519).epsilon(1e-14));
    const double a = 1 / (0.1 * std::tan(th));
    CHECK((3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a) == Approx(0.67333597).margin(5e-9));
    CHECK(bb_ggx_g1(w, 0.1, 0.1) == Approx(0.46130955).margin(5e-9));
    // Edge-case policy: G1 = 1 at the normal, 0 at and below the horizon; D = 0 back-facing.
    CHECK(bb_beckmann_g1(bb_v3(0, 0, 1), 0.7, 0.3) == 1.0);
    CHECK(bb_beckmann_g1(bb_v3(1, 0, 0), 0.7, 0.3) == 0.0);
    CHECK(bb_beckmann_g1(bb_v3(0.6, 0, -0.8), 0.7, 0.3) == 0.0);
    CHECK(bb_beckmann_lambda(bb_v3(0, 0, 1), 0.7, 0.3) == 0.0);
    CHECK(bb_beckmann_d(bb_v3(0.6, 0, -0.8), 0.5, 0.5) == 0.0);
    CHECK(bb_beckmann_d(bb_v3(1, 0, 0), 0.5, 0.5) == 0.0);
    CHECK(bb_blinn_d(bb_v3(0.6, 0, -0.8), 10) == 0.0);
    // Oren-Nayar A and B (ON94 eq. 30) at sigma = 0.5: 1 - 0.125/0.58 and 0.1125/0.34.
    CHECK(bb_oren_nayar_a(0.5) == Approx(1 - 0.125 / 0.58).epsilon(1e-15));
    CHECK(bb_oren_nayar_b(0.5) == Approx(0.1125 / 0.34).epsilon(1e-15));
}

// ---------------------------------------------------------------- normalisation identities

TEST_CASE("every distribution is normalised: integral of D cos(theta_m) = 1", "[models][quick][slow]") {
    for (double n : {0.0, 1.0, 10.0, 100.0, 1e4}) {
        INFO("Blinn n = " << n);
        CHECK(projected_area([&](bb_vec3 m) { return bb_blinn_d(m, n); }, std::fmin(0.3, 8 / std::sqrt(n + 1))) ==
              Approx(1.0).margin(1e-8));
    }
    for (auto a : {std::pair<double, double>{0.05, 0.05}, {0.3, 0.3}, {1.0, 1.0}, {0.1, 0.5}, {0.8, 0.2}}) {
        INFO("Beckmann " << a.first << " x " << a.second);
        CHECK(projected_area([&](bb_vec3 m) { return bb_beckmann_d(m, a.first, a.second); }) ==
              Approx(1.0).margin(1e-8));
        INFO("GGX " << a.first << " x " << a.second);
        CHECK(projected_area([&](bb_vec3 m) { return bb_ggx_d(m, a.first, a.second); }) == Approx(1.0).margin(1e-7));
    }
}

TEST_CASE("the (n+2)/(2 pi) normalisation of Blinn-Phong and Phong", "[models][quick][slow]") {
    // blinn-phong normalized=1 is K = (n+2)/(2 pi): K cos^n(theta_h) is a normalised distribution.
    for (double n : {0.0, 3.0, 50.0, 1e4}) {
        const ModelConfig m = resolve_model("blinn-phong:n=" + modelref::num(n) + ",normalized=1");
        const double k = bb_blinn_phong_k(to_bb_params(m.params));
        CHECK(k == Approx((n + 2) / (2 * M_PI)).epsilon(1e-15));
        CHECK(projected_area([&](bb_vec3 h) { return h.z > 0 ? k * std::pow(h.z, n) : 0.0; },
                             std::fmin(0.3, 8 / std::sqrt(n + 1))) == Approx(1.0).margin(1e-8));
        CHECK(bb_blinn_phong_k(to_bb_params(resolve_model("blinn-phong:n=" + modelref::num(n) + ",ks=0.5").params)) == 0.5);
    }
    // phong normalized=1: the albedo at normal incidence is exactly ks (the lobe about the
    // normal integrates K cos^(n+1)).
    for (double n : {0.0, 7.0, 1e3}) {
        const double e = modelref::phong(n).albedo(1.0);
        INFO("n = " << n);
        CHECK(e == Approx(1.0).margin(1e-8));
    }
}

TEST_CASE("Oren-Nayar with sigma = 0 is Lambert", "[models][quick]") {
    const ModelConfig on = resolve_model("oren-nayar:sigma=0,rho=0.7");
    const ModelConfig la = resolve_model("lambert:rho=0.7");
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 1000; ++i) {
        const bb_vec3 wo = bb_dir_from_mu_phi(u(rng), 2 * M_PI * u(rng)), wi = bb_dir_from_mu_phi(u(rng), 2 * M_PI * u(rng));
        CHECK(eval(on, wo, wi) == eval(la, wo, wi));
    }
    CHECK(modelref::oren_nayar(0.0, 0.7).albedo(0.3) == Approx(0.7).epsilon(1e-10));
}

TEST_CASE("Beckmann weak white furnace: integral of G1 D <wo,m> / cos_o = 1", "[models][quick]") {
    for (auto a : {std::pair<double, double>{0.1, 0.1}, {0.5, 0.5}, {1.0, 1.0}, {0.08, 0.5}})
        for (double th : {0.0, 0.7, 1.3, 1.55}) {
            const ref::Dir wo = ref::dir(th, 0.9);
            const double g1 = bb_beckmann_g1(v3(wo), a.first, a.second);
            const double w = ref::integrate_facing(
                [&](double t, double p) {
                    const ref::Dir m = ref::dir(t, p);
                    return g1 * bb_beckmann_d(v3(m), a.first, a.second) * double(ref::dot(wo, m)) / double(wo.z);
                },
                wo.z, 0.9);
            INFO("alpha " << a.first << " x " << a.second << ", theta_o = " << th);
            CHECK(w == Approx(1.0).margin(1e-6));
        }
}

// ------------------------------------------------------------------- samplers and helpers

TEST_CASE("erfinv approximation is accurate to 2e-6", "[models][quick]") {
    double worst = 0;
    for (int i = 1; i < 200000; ++i) {
        const double x = -1 + 2.0 * i / 200000;
        worst = std::fmax(worst, std::fabs(bb_erfinv(x) / boost::math::erf_inv(x) - 1));
    }
    // The samplers use |x| <= 1 - 2e-6 (u clamped to [1e-6, 1 - 1e-6]).
    for (double x : {1 - 2e-6, -(1 - 2e-6)}) worst = std::fmax(worst, std::fabs(bb_erfinv(x) / boost::math::erf_inv(x) - 1));
    INFO("worst relative error " << worst);
    CHECK(worst < 2e-6);
    CHECK(std::isfinite(bb_erfinv(1.0)));
    CHECK(std::isfinite(bb_erfinv(-1.0)));
}

TEST_CASE("Beckmann visible-slope inversion converges in its fixed iteration count", "[models][quick]") {
    double worst = 0;
    for (int t = 0; t <= 200; ++t) {
        const double th = 1.5707 * t / 200, c = std::cos(th), s = std::sin(th);
        for (int k = 0; k <= 1000; ++k) {
            const double u = k / 1000.0 * (1 - 1e-9);
            const double x = bb_beckmann_sample_slope11(c, s, u, 0.5).x;
            const double tn = s / c, cot = c / s, k1 = tn / std::sqrt(M_PI);
            const double cdf = (1 + std::erf(x) + k1 * std::exp(-x * x)) / (1 + std::erf(cot) + k1 * std::exp(-cot * cot));
            worst = std::fmax(worst, std::fabs(cdf - std::clamp(u, 1e-6, 1 - 1e-6)));
        }
    }
    CHECK(worst < 1e-7);
}

TEST_CASE("Beckmann visible-normal samples have the density the weight assumes", "[models][quick]") {
    // The fraction of VNDF samples whose microfacet lies in a cap equals the VNDF mass of the
    // cap by quadrature (as for GGX in test_microfacet.cpp), isotropic and anisotropic.
    for (auto a : {std::pair<double, double>{0.4, 0.4}, {0.15, 0.6}})
        for (double th_o : {0.0, 1.1, 1.5}) {
            const ref::Dir wo = ref::dir(th_o, 0.4);
            const double cap = 0.35;
            const double g1 = double(1 / (1 + ref::beckmann_lambda(wo, a.first, a.second)));
            const double mass = ref::integrate_facing(
                [&](double t, double p) {
                    const ref::Dir m = ref::dir(t, p);
                    return g1 * double(ref::beckmann_d(m, a.first, a.second) * ref::dot(wo, m) / wo.z);
                },
                wo.z, 0.4, cap);
            const int n = 400;
            int inside = 0;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const bb_vec3 m = bb_beckmann_sample_vndf(v3(wo), a.first, a.second, (i + 0.5) / n, (j + 0.5) / n);
                    inside += std::acos(std::fmin(1.0, m.z)) < cap;
                }
            INFO("alpha " << a.first << " x " << a.second << ", theta_o " << th_o);
            CHECK(double(inside) / (n * n) == Approx(mass).margin(2e-3));
        }
}

TEST_CASE("D cos samplers and the Phong lobe sampler have the densities they assume", "[models][quick]") {
    // Mass of a cap theta_m < cap under D cos, by quadrature and by a stratified sample set.
    struct Dist {
        const char* name;
        std::function<double(bb_vec3)> d;
        std::function<bb_vec3(double, double)> sample;
    };
    const std::vector<Dist> dists = {
        {"blinn 20", [](bb_vec3 m) { return bb_blinn_d(m, 20); }, [](double a, double b) { return bb_blinn_sample_dcos(20, a, b); }},
        {"beckmann 0.3x0.6", [](bb_vec3 m) { return bb_beckmann_d(m, 0.3, 0.6); },
         [](double a, double b) { return bb_beckmann_sample_dcos(0.3, 0.6, a, b); }},
        {"ggx 0.5x0.2", [](bb_vec3 m) { return bb_ggx_d(m, 0.5, 0.2); },
         [](double a, double b) { return bb_ggx_sample_dcos(0.5, 0.2, a, b); }},
    };
    const double cap = 0.3;
    for (const auto& d : dists) {
        const double mass = ref::integrate2(
            [&](double t, double p) { return d.d(v3(ref::dir(t, p))) * std::cos(t) * std::sin(t); }, 0, cap, 0,
            2 * M_PI, 1e-10);
        const int n = 300;
        int inside = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) inside += std::acos(std::fmin(1.0, d.sample((i + 0.5) / n, (j + 0.5) / n).z)) < cap;
        INFO(d.name);
        CHECK(double(inside) / (n * n) == Approx(mass).margin(2e-3));
    }
    // The Phong lobe: the angle to R(wo) has CDF 1 - cos^(n+1).
    const bb_vec3 wo = bb_dir_from_mu_phi(0.4, 1.0);
    const bb_vec3 r = bb_mirror_dir(wo);
    int inside = 0;
    const int n = 300;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) inside += bb_dot(bb_phong_sample_dir(30, wo, (i + 0.5) / n, (j + 0.5) / n), r) > std::cos(0.2);
    CHECK(double(inside) / (n * n) == Approx(1 - std::pow(std::cos(0.2), 31)).margin(2e-3));
}

// ------------------------------------------------------------------- against the textbook

TEST_CASE("shared model functions match the textbook forms", "[models][quick]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 3000; ++i) {
        const double ax = 0.02 + u(rng), ay = 0.02 + u(rng), n = std::floor(200 * u(rng)), sigma = 1.5 * u(rng);
        const ref::Dir wo = ref::dir_mu(1e-4 + (1 - 1e-4) * u(rng), 2 * M_PI * u(rng));
        const ref::Dir wi = ref::dir_mu(1e-4 + (1 - 1e-4) * u(rng), 2 * M_PI * u(rng));
        const ref::Dir m = ref::normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
        INFO("ax " << ax << " ay " << ay << " n " << n << " wo.z " << double(wo.z) << " wi.z " << double(wi.z));
        CHECK(bb_beckmann_d(v3(m), ax, ay) == Approx(double(ref::beckmann_d(m, ax, ay))).epsilon(1e-11).margin(1e-300));
        CHECK(bb_beckmann_g1(v3(wo), ax, ay) == Approx(double(ref::beckmann_g1(wo, ax, ay))).epsilon(1e-11));
        CHECK(bb_beckmann_lambda(v3(wo), ax, ay) ==
              Approx(double(ref::beckmann_lambda(wo, ax, ay))).epsilon(1e-9).margin(1e-14));
        CHECK(bb_blinn_d(v3(m), n) == Approx(double(ref::blinn_d(m, n))).epsilon(1e-11).margin(1e-300));
        CHECK(bb_vgroove_g(v3(wo), v3(wi)) == Approx(double(ref::vgroove_g(wo, wi))).epsilon(1e-12));
        for (bool corr : {true, false}) {
            const bb_params p = {{ax, ay, corr ? 1.0 : 0.0}};
            CHECK(bb_beckmann_eval(p, BB_FRESNEL_NONE, kNoFresnel, v3(wo), v3(wi)) ==
                  Approx(double(ref::beckmann_f(wo, wi, ax, ay, corr))).epsilon(1e-10).margin(1e-300));
        }
        const bb_params ts_b = {{BB_TS_D_BLINN, n, 0, 0}}, ts_k = {{BB_TS_D_BECKMANN, 0, ax, ay}},
                        ts_g = {{BB_TS_D_GGX, 0, ax, ay}};
        CHECK(bb_torrance_sparrow_eval(ts_b, BB_FRESNEL_NONE, kNoFresnel, v3(wo), v3(wi)) ==
              Approx(double(ref::torrance_sparrow_f(wo, wi, ref::Dist::Blinn, n))).epsilon(1e-10).margin(1e-300));
        CHECK(bb_torrance_sparrow_eval(ts_k, BB_FRESNEL_NONE, kNoFresnel, v3(wo), v3(wi)) ==
              Approx(double(ref::torrance_sparrow_f(wo, wi, ref::Dist::Beckmann, ax, ay))).epsilon(1e-10).margin(1e-300));
        CHECK(bb_torrance_sparrow_eval(ts_g, BB_FRESNEL_NONE, kNoFresnel, v3(wo), v3(wi)) ==
              Approx(double(ref::torrance_sparrow_f(wo, wi, ref::Dist::Ggx, ax, ay))).epsilon(1e-10));
        const bb_params ph = {{n, 0.8, 1.0}};
        const double k = 0.8 * (n + 2) / (2 * M_PI);
        CHECK(bb_phong_eval(ph, v3(wo), v3(wi)) == Approx(double(ref::phong_f(wo, wi, n, k, false))).epsilon(1e-9).margin(1e-300));
        CHECK(bb_phong_original_eval(ph, v3(wo), v3(wi)) ==
              Approx(double(ref::phong_f(wo, wi, n, 0.8, true))).epsilon(1e-9).margin(1e-300));
        CHECK(bb_blinn_phong_eval(ph, v3(wo), v3(wi)) ==
              Approx(double(ref::blinn_phong_f(wo, wi, n, k))).epsilon(1e-10).margin(1e-300));
        const bb_params on = {{sigma, 0.9}};
        CHECK(bb_oren_nayar_eval(on, v3(wo), v3(wi)) == Approx(double(ref::oren_nayar_f(wo, wi, sigma, 0.9))).epsilon(1e-10));
    }
}

TEST_CASE("Fresnel multiplies the microfacet models at wo.wh", "[models][quick]") {
    const FresnelConfig f = resolve_fresnel("schlick:f0=0.04");
    const bb_vec3 wo = bb_dir_from_mu_phi(0.3, 0.2), wi = bb_dir_from_mu_phi(0.8, 2.5);
    const bb_vec3 wh = bb_normalize(bb_add(wo, wi));
    const double fr = bb_fresnel_schlick(bb_dot(wo, wh), 0.04);
    for (const char* s : {"beckmann:alpha=0.4", "torrance-sparrow:d=ggx,alpha=0.4", "ggx:alpha=0.4"}) {
        const ModelConfig m = resolve_model(s);
        INFO(s);
        CHECK(bb_model_eval(m.id, to_bb_params(m.params), f.kind, to_bb_params(f.params), wo, wi) ==
              Approx(fr * eval(m, wo, wi)).epsilon(1e-14));
    }
}

// --------------------------------------------- reciprocity, sign and finiteness to grazing

TEST_CASE("every model is reciprocal except phong-original", "[models][quick]") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const auto& s : kAllSpecs) {
        const ModelConfig m = resolve_model(s);
        double worst = 0;
        for (int i = 0; i < 20000; ++i) {
            const bb_vec3 wo = bb_dir_from_mu_phi(std::pow(u(rng), 3), 2 * M_PI * u(rng));
            const bb_vec3 wi = bb_dir_from_mu_phi(std::pow(u(rng), 3), 2 * M_PI * u(rng));
            const double a = eval(m, wo, wi), b = eval(m, wi, wo), mx = std::fmax(a, b);
            if (mx > 0) worst = std::fmax(worst, std::fabs(a - b) / mx);
        }
        INFO(s << ": worst relative reciprocity error " << worst);
        if (m.id == BB_MODEL_PHONG_ORIGINAL)
            CHECK(worst > 0.5);  // f(wo,wi)/f(wi,wo) = cos_o/cos_i: far from reciprocal
        else
            CHECK(worst < 1e-9);
    }
    // The exact ratio for phong-original.
    const ModelConfig po = resolve_model("phong-original:n=5");
    const bb_vec3 wo = bb_dir_from_mu_phi(0.8, 0.0), wi = bb_dir_from_mu_phi(0.4, M_PI);
    CHECK(eval(po, wo, wi) / eval(po, wi, wo) == Approx(0.8 / 0.4).epsilon(1e-12));
}

TEST_CASE("every model is non-negative and finite down to mu = 1e-5 (host, double)", "[models][quick]") {
    std::vector<double> mus = {1.0, 0.9, 0.5, 0.1};
    for (double mu = 1e-2; mu >= 1e-5; mu /= 3) mus.push_back(mu);
    mus.push_back(1e-5);
    mus.push_back(0.0);
    mus.push_back(-0.3);  // below the horizon: must give 0
    for (const auto& s : kAllSpecs) {
        const ModelConfig m = resolve_model(s);
        const bb_params p = to_bb_params(m.params);
        int bad = 0, negative_below = 0;
        for (double mo : mus)
            for (double mi : mus)
                for (int k = 0; k < 24; ++k) {
                    const bb_vec3 wo = bb_dir_from_mu_phi(mo, 0.3), wi = bb_dir_from_mu_phi(mi, 0.3 + k * M_PI / 12);
                    const double f = eval(m, wo, wi);
                    bad += !(std::isfinite(f) && f >= 0);
                    negative_below += (mo <= 0 || mi <= 0) && f != 0;
                }
        int bad_sample = 0;
        for (double mo : mus)
            for (double u1 : {0.0, 1e-9, 0.25, 0.5, 0.999, 1 - 1e-12})
                for (double u2 : {0.0, 0.3, 0.999999}) {
                    const bb_sample smp = bb_model_sample(m.id, p, BB_FRESNEL_NONE, kNoFresnel, bb_dir_from_mu_phi(mo, 1.0), u1, u2);
                    bad_sample += !(std::isfinite(smp.weight) && smp.weight >= 0);
                    bad_sample += mo <= 0 && smp.weight != 0;
                    bad_sample += smp.weight > 0 && !(std::isfinite(smp.wi.z) && smp.wi.z > 0);
                }
        INFO(s);
        CHECK(bad == 0);
        CHECK(negative_below == 0);
        CHECK(bad_sample == 0);
    }
}

TEST_CASE("the estimator weights are those of f cos / pdf", "[models][quick]") {
    // Deterministic check of each sampler's weight: a stratified host estimate of the albedo
    // against the independent reference, at a moderate tolerance (the device tests are tight).
    struct C {
        std::string spec;
        modelref::Case ref;
    };
    const std::vector<modelref::Case> cases = {
        modelref::oren_nayar(0.8, 0.9), modelref::phong(12), modelref::phong_original(12), modelref::blinn_phong(12),
        modelref::torrance_sparrow(ref::Dist::Blinn, 0.4), modelref::torrance_sparrow(ref::Dist::Beckmann, 0.4),
        modelref::torrance_sparrow(ref::Dist::Ggx, 0.4), modelref::beckmann(0.4, true), modelref::beckmann(0.4, false),
    };
    for (const auto& c : cases) {
        const ModelConfig m = resolve_model(c.spec);
        for (double mu : {0.9, 0.35}) {
            const bb_vec3 wo = bb_dir_from_mu_phi(mu, 0.0);
            const int n = 512;
            double sum = 0;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    sum += bb_model_sample(m.id, to_bb_params(m.params), BB_FRESNEL_NONE, kNoFresnel, wo, (i + 0.5) / n,
                                           (j + 0.5) / n).weight;
            INFO(c.spec << " mu " << mu);
            CHECK(sum / (n * n) == Approx(c.albedo(mu)).margin(2e-3));
        }
    }
}

// --------------------------------------------------------------------- the delta lobes

TEST_CASE("delta lobes: analytic albedo and transmission", "[models][quick]") {
    const ModelConfig mirror = resolve_model("mirror");
    const ModelConfig glass = resolve_model("dielectric-specular:eta=1.5");
    const ModelConfig inside = resolve_model("dielectric-specular:eta=0.6666666666666666");
    double v = -1;
    CHECK(has_analytic_albedo(mirror));
    CHECK_FALSE(has_analytic_albedo(resolve_model("ggx:alpha=0.2")));
    REQUIRE(analytic_albedo(mirror, resolve_fresnel("none"), 0.3, v));
    CHECK(v == 1.0);
    REQUIRE(analytic_albedo(mirror, resolve_fresnel("schlick:f0=0.04"), 1.0, v));
    CHECK(v == Approx(0.04).epsilon(1e-14));
    REQUIRE(analytic_albedo(mirror, resolve_fresnel("dielectric:eta=1.5"), 0.5, v));
    CHECK(v == Approx(ref::fresnel_dielectric(0.5, 1.5)).epsilon(1e-13));
    // Known values from physics: F = 0.04 at normal incidence for eta = 1.5.
    REQUIRE(analytic_albedo(glass, resolve_fresnel("none"), 1.0, v));
    CHECK(v == Approx(0.04).epsilon(1e-14));
    for (double mu : {1.0, 0.7, 0.3, 0.05, 0.001}) {
        REQUIRE(analytic_albedo(glass, resolve_fresnel("none"), mu, v));
        CHECK(v == Approx(ref::fresnel_dielectric(mu, 1.5)).epsilon(1e-12));
        SpecularTransmission t;
        REQUIRE(analytic_transmission(glass, mu, t));
        CHECK(t.energy == Approx(1 - v).epsilon(1e-14));
        CHECK(t.radiance_factor == Approx(2.25).epsilon(1e-15));
        CHECK(analytic_albedo_error(v) < 1e-13);
    }
    // Seen from inside the glass: total internal reflection beyond the critical angle.
    REQUIRE(analytic_albedo(inside, resolve_fresnel("none"), 0.5, v));
    CHECK(v == 1.0);
    SpecularTransmission t;
    REQUIRE(analytic_transmission(inside, 0.5, t));
    CHECK(t.energy == 0.0);
    CHECK_FALSE(analytic_albedo(resolve_model("beckmann:alpha=0.3"), resolve_fresnel("none"), 0.5, v));
    CHECK_FALSE(analytic_transmission(mirror, 0.5, t));
    CHECK_THROWS_AS(analytic_albedo(mirror, resolve_fresnel("none"), 0.0, v), Error);
    // The delta lobes have no finite value anywhere: eval is 0 for every pair.
    CHECK(eval(mirror, bb_dir_from_mu_phi(0.5, 0), bb_dir_from_mu_phi(0.5, M_PI)) == 0.0);
    CHECK(eval(glass, bb_dir_from_mu_phi(0.5, 0), bb_dir_from_mu_phi(0.5, M_PI)) == 0.0);
}

TEST_CASE("roughness_slots: the swept alpha slots of the registry, and the refusals", "[models][quick]") {
    CHECK(roughness_slots(resolve_model("ggx:alpha=0.5")) == std::vector<int>{BB_GGX_ALPHA_X, BB_GGX_ALPHA_Y});
    CHECK(roughness_slots(resolve_model("beckmann:alpha=0.5")) ==
          std::vector<int>{BB_BECKMANN_ALPHA_X, BB_BECKMANN_ALPHA_Y});
    CHECK(roughness_slots(resolve_model("torrance-sparrow:d=ggx,alpha=0.5")) ==
          std::vector<int>{BB_TORRANCE_SPARROW_ALPHA_X, BB_TORRANCE_SPARROW_ALPHA_Y});
    CHECK_THROWS_WITH(roughness_slots(resolve_model("torrance-sparrow:d=blinn,n=30")),
                      "torrance-sparrow with d=blinn has an exponent, not alpha, to sweep; use d=beckmann or d=ggx");
    CHECK_THROWS_WITH(roughness_slots(resolve_model("lambert")),
                      "model 'lambert' has no roughness alpha to sweep; tables need a model with a roughness axis "
                      "(alpha, oren-nayar's sigma or the Phong lobes' n)");
    // The models without alpha whose key the registry maps (issue 33): sigma = alpha, and the
    // exponent n = 2/alpha^2 - 2 of Walter et al. 2007 sec. 5.2 (alpha 0.5: n = 6; alpha 0.1: n = 198).
    CHECK(roughness_slots(resolve_model("blinn-phong:n=20")) == std::vector<int>{BB_BLINN_PHONG_N});
    CHECK(with_roughness(resolve_model("blinn-phong:n=20"), {}, 0.5)[BB_BLINN_PHONG_N] == Approx(6.0).epsilon(1e-15));
    CHECK(with_roughness(resolve_model("phong:n=20"), {}, 0.1)[BB_PHONG_N] == Approx(198.0).epsilon(1e-14));
    CHECK(with_roughness(resolve_model("oren-nayar:sigma=0"), {}, 0.7)[BB_OREN_NAYAR_SIGMA] == 0.7);
}

// diffuse=KD's importance sampler (brdf/smith.h, bb_smith_sample: a one-sample mixture of the
// visible-normal sampler and the cosine warp, brdf/sampling.h), checked from outside: the mean of
// its weights at random unit-square points, a Monte-Carlo integral of the whole f cos, equals the
// specular lobe's albedo by Boost.Math quadrature in half-vector space of the textbook formulas
// (benchmarks/reference) plus kd, the Lambert part's albedo in closed form, within 4 standard
// errors; the device's sample (float and double) equals the host's. The lobe's sampler alone
// would miss kd (0.2 to 0.5 here, hundreds of standard errors).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include "brdfbake/brdf/models.h"
#include "brdfbake/spec.h"
#include "models/params.h"
#include "parity.h"
#include "reference/reference.h"

using namespace brdfbake;

namespace {

struct MixtureCase {
    std::string spec;  // a Smith lobe with diffuse=KD, shadowing correlated (the reference's G2)
    bool beckmann;
    double ax, ay, kd, mu, phi;
};

/// The mean of the sampler's weights at n random points, and its standard error.
std::pair<double, double> sampled_albedo(const ModelConfig& m, bb_vec3 wo, int n) {
    const FresnelConfig f = resolve_fresnel("none");
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    double sum = 0.0, sum2 = 0.0;
    int bad = 0;
    for (int i = 0; i < n; ++i) {
        const double u1 = uni(rng), u2 = uni(rng);
        const bb_sample s = bb_model_sample(m.id, to_bb_params(m.params), f.kind, to_bb_params(f.params), wo, u1, u2);
        bad += !(std::isfinite(s.weight) && s.weight >= 0.0);
        sum += s.weight;
        sum2 += s.weight * s.weight;
    }
    CHECK(bad == 0);
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

}  // namespace

TEST_CASE("diffuse: the mixture sampler's Monte-Carlo integral is the lobe's quadrature albedo plus kd",
          "[diffuse][sampling]") {
    const MixtureCase cases[] = {
        {"ggx:alpha=0.3,diffuse=0.25", false, 0.3, 0.3, 0.25, 0.7, 0.0},
        {"ggx:alpha=0.05,diffuse=0.5", false, 0.05, 0.05, 0.5, 0.3, 0.0},
        {"ggx:alpha_x=0.6,alpha_y=0.2,diffuse=0.2", false, 0.6, 0.2, 0.2, 0.45, 0.8},
        {"beckmann:alpha=0.5,diffuse=0.3", true, 0.5, 0.5, 0.3, 0.2, 0.0},
        {"beckmann:alpha_x=0.15,alpha_y=0.4,diffuse=0.4", true, 0.15, 0.4, 0.4, 0.9, 2.0},
    };
    for (const MixtureCase& c : cases) {
        INFO(c.spec << " at mu = " << c.mu << ", phi = " << c.phi);
        const ModelConfig m = resolve_model(c.spec + ",shadowing=correlated");
        const bb_vec3 wo = bb_dir_from_mu_phi(c.mu, c.phi);
        const double lobe = ref::albedo_halfvector(
            [&](ref::Dir o, ref::Dir i) {
                return c.beckmann ? ref::beckmann_f(o, i, c.ax, c.ay, true) : ref::ggx_f(o, i, c.ax, c.ay, true);
            },
            c.mu, c.phi, 1e-7);  // far below the Monte-Carlo error (about 1e-3)
        const auto [mean, se] = sampled_albedo(m, wo, 1 << 18);
        INFO("sampled " << mean << " +- " << se << ", quadrature lobe " << lobe << " + kd " << c.kd);
        CHECK(std::fabs(mean - (lobe + c.kd)) <= 4.0 * se + 1e-6);
        CHECK(se < 0.01 * c.kd);  // the test tells the mixture from the lobe's sampler alone
    }
}

TEST_CASE("diffuse: the device's mixture sample equals the host's", "[diffuse][sampling][parity]") {
    for (const char* spec : {"ggx:alpha=0.3,diffuse=0.25", "beckmann:alpha_x=0.15,alpha_y=0.4,diffuse=0.4"})
        testing::check_host_device_parity(resolve_model(spec), spec, 256);
}

TEST_CASE("diffuse: the mixture's per-sample variance is the one benchmarks/mixture_variance.py integrates",
          "[diffuse][sampling]") {
    // Var W of the weight W = f cos / (c cos/pi + (1 - c) pdf_lobe), c = kd / (kd + F(cos theta_o)),
    // by the benchmark's deterministic numpy quadrature of GGX (height-correlated) written from the
    // papers (benchmarks/results/mixture-variance-amd-epyc-2c.md: 8 x 96 nodes in u, 384 in phi; its
    // Monte Carlo check agrees): the variance that record compares is that of brdfbake's sampler.
    struct Case {
        const char *spec, *fresnel;
        double mu, mean, variance;
    };
    const Case cases[] = {
        {"ggx:alpha=0.2,diffuse=0.5,shadowing=correlated", "none", 0.5, 1.39523, 8.6823e-02},
        {"ggx:alpha=0.7,diffuse=0.5,shadowing=correlated", "schlick:f0=0.04", 0.5, 0.52925, 8.9354e-03},
    };
    // Other chances give other variances there (the record): c from the lobe's albedo 8.3414e-2 and
    // 4.0187e-3, c = 1/2 1.6194e-1 and 5.2403e-2, each many of the check's standard errors away.
    for (const Case& c : cases) {
        INFO(c.spec << " " << c.fresnel << " at mu " << c.mu);
        const ModelConfig m = resolve_model(c.spec);
        const FresnelConfig f = resolve_fresnel(c.fresnel);
        const bb_vec3 wo = bb_dir_from_mu_phi(c.mu, 0.0);
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> uni(0.0, 1.0);
        const int n = 1 << 20;
        double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
        for (int i = 0; i < n; ++i) {
            const double u1 = uni(rng), u2 = uni(rng);
            const double w = bb_model_sample(m.id, to_bb_params(m.params), f.kind, to_bb_params(f.params), wo, u1, u2).weight;
            sum += w;
            sum2 += w * w;
            sum4 += w * w * w * w;
        }
        const double mean = sum / n, variance = sum2 / n - mean * mean;
        // The sample variance's standard error from the fourth moment (about the origin: an upper bound).
        const double variance_se = std::sqrt(std::max(0.0, sum4 / n - (sum2 / n) * (sum2 / n)) / n);
        INFO("mean " << mean << ", variance " << variance << " +- " << variance_se);
        CHECK(std::fabs(mean - c.mean) <= 4.0 * std::sqrt(variance / n) + 1e-5);
        CHECK(std::fabs(variance - c.variance) <= 4.0 * variance_se + 1e-3 * c.variance);
        CHECK(variance_se < 0.01 * c.variance);  // the check tells those chances apart
    }
}

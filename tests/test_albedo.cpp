// The albedo kernel against closed forms and independent host quadrature.
#include <catch2/catch.hpp>

#include "brdfbake/albedo.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

AlbedoResult run(const std::string& model_spec, const std::vector<double>& mus, Precision p,
                 std::uint64_t samples = 1 << 18) {
    return compute_albedo(testing::engine(), testing::albedo_request(model_spec, mus, Method::Importance, p, samples));
}

double ggx_reference(double alpha, double mu, bool correlated) {
    return ref::albedo_halfvector(
        [&](ref::Dir wo, ref::Dir wi) { return ref::ggx_f(wo, wi, alpha, alpha, correlated); }, mu, 0.0);
}

}  // namespace

TEST_CASE("Lambert albedo equals rho at every mu", "[albedo][device]") {
    const std::vector<double> mus = {1e-3, 0.1, 0.5, 0.9, 1.0};
    for (Precision p : {Precision::Float, Precision::Double}) {
        const AlbedoResult r = run("lambert:rho=0.8", mus, p);
        for (size_t i = 0; i < mus.size(); ++i) {
            INFO(precision_name(p) << " mu = " << mus[i]);
            CHECK(std::fabs(r.values[i].value - 0.8) <= 1e-6);
            CHECK(std::fabs(r.values[i].value - 0.8) <= r.values[i].error);
        }
    }
}

TEST_CASE("GGX albedo matches half-vector quadrature within its error estimate", "[albedo][device]") {
    const std::vector<double> mus = {0.05, 0.2, 0.5, 1.0};
    for (const char* shadowing : {"correlated", "separable"})
        for (double alpha : {0.1, 0.5, 1.0}) {
            const std::string spec = "ggx:alpha=" + std::to_string(alpha) + ",shadowing=" + shadowing;
            const bool corr = std::string(shadowing) == "correlated";
            for (Precision p : {Precision::Float, Precision::Double}) {
                const AlbedoResult r = run(spec, mus, p);
                for (size_t i = 0; i < mus.size(); ++i) {
                    const double expect = ggx_reference(alpha, mus[i], corr);
                    INFO(spec << " " << precision_name(p) << " mu = " << mus[i] << " got " << r.values[i].value
                              << " +- " << r.values[i].error << " expected " << expect);
                    CHECK(std::fabs(r.values[i].value - expect) <= 1e-4);
                    CHECK(std::fabs(r.values[i].value - expect) <= r.values[i].error);
                    CHECK(r.values[i].error < 1e-4);
                }
            }
        }
}

TEST_CASE("GGX albedo is at most 1 and falls with roughness at normal incidence", "[albedo][device]") {
    // Single-scattering microfacet models lose energy: E < 1, increasingly with alpha.
    double previous = 1.0;
    for (double alpha : {0.05, 0.3, 0.6, 1.0}) {
        const AlbedoResult r = run("ggx:alpha=" + std::to_string(alpha), {1.0}, Precision::Float);
        CHECK(r.values[0].value <= 1.0 + r.values[0].error);
        CHECK(r.values[0].value < previous);
        previous = r.values[0].value;
    }
}

TEST_CASE("Anisotropic GGX albedo depends on phi_o as quadrature says", "[albedo][device]") {
    const ModelConfig m = resolve_model("ggx:alpha_x=0.1,alpha_y=0.6");
    REQUIRE(m.anisotropic);
    for (double phi : {0.0, M_PI / 2}) {
        AlbedoRequest req;
        req.model = m.id;
        req.fresnel = resolve_fresnel("none");
        req.cells = cells_for({0.3}, phi, m.params);
        const AlbedoResult r = compute_albedo(testing::engine(), req);
        const double expect = ref::albedo_halfvector(
            [&](ref::Dir wo, ref::Dir wi) { return ref::ggx_f(wo, wi, 0.1, 0.6, true); }, 0.3, phi);
        INFO("phi = " << phi << " got " << r.values[0].value << " expected " << expect);
        CHECK(std::fabs(r.values[0].value - expect) <= r.values[0].error);
    }
}

TEST_CASE("Float and double albedo agree within the float error estimate", "[albedo][device]") {
    const std::vector<double> mus = {0.01, 0.3, 1.0};
    const AlbedoResult f = run("ggx:alpha=0.3", mus, Precision::Float);
    const AlbedoResult d = run("ggx:alpha=0.3", mus, Precision::Double);
    for (size_t i = 0; i < mus.size(); ++i) {
        INFO("mu = " << mus[i]);
        CHECK(std::fabs(f.values[i].value - d.values[i].value) <= f.values[i].error);
    }
}

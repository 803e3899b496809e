// The one-call C++ API (include/brdfbake/api.h) against independent references: GGX's albedo by
// boost's quadrature in half-vector space (ggx_albedo_reference.h) and Lambert's closed form; bad
// input refused with an Error naming it.
#include <catch2/catch.hpp>

#include "brdfbake/api.h"
#include "brdfbake/error.h"
#include "ggx_albedo_reference.h"

TEST_CASE("brdfbake::albedo: one call, the model given once, values within their errors", "[api][quick]") {
    brdfbake::AlbedoOptions o;
    o.tolerance = 1e-5;
    o.precision = "double";
    const std::vector<double> mu{0.2, 0.5, 1.0};
    const brdfbake::AlbedoValues e = brdfbake::albedo("ggx:alpha=0.5", mu, o);
    REQUIRE(e.albedo.size() == 3);
    REQUIRE(e.error.size() == 3);
    CHECK(e.model == "ggx:alpha=0.5,shadowing=correlated");
    for (size_t i = 0; i < mu.size(); ++i) {
        const double ref = testing::ggx_albedo_reference<30>(0.5, mu[i], 1e-10);
        INFO("mu " << mu[i] << ": " << e.albedo[i] << " +- " << e.error[i] << ", reference " << ref);
        CHECK(e.error[i] <= 1e-5);
        CHECK(std::fabs(e.albedo[i] - ref) <= std::max(e.error[i], 1e-9));
    }
    brdfbake::AlbedoOptions qmc;
    qmc.method = "qmc";
    qmc.samples = 1 << 14;
    const brdfbake::AlbedoValue lambert = brdfbake::albedo("lambert:rho=0.5", 0.3, qmc);
    CHECK(std::fabs(lambert.value - 0.5) <= lambert.error);  // Lambert: E = rho at every mu
    CHECK_THROWS_AS(brdfbake::albedo("ggx:alpah=0.5", 0.5), brdfbake::Error);
    CHECK_THROWS_WITH(brdfbake::albedo("ggx:alpha=0.5", 1.5), Catch::Contains("mu"));
}

TEST_CASE("brdfbake::lut: a table as `brdfbake lut` computes it", "[api][quick]") {
    brdfbake::LutOptions o;
    o.model = "ggx";
    o.size = {3, 2};
    o.tolerance = 1e-5;
    o.precision = "double";
    const brdfbake::Table t = brdfbake::lut("albedo", o);
    REQUIRE(t.width() == 3);
    REQUIRE(t.height() == 2);
    REQUIRE(t.values.size() == 1);
    for (int y = 0; y < t.height(); ++y)
        for (int x = 0; x < t.width(); ++x) {
            const double v = t.values[0][size_t(y * t.width() + x)];
            const double ref = testing::ggx_albedo_reference<30>(t.y.parameter[size_t(y)], t.x.parameter[size_t(x)], 1e-10);
            INFO("mu " << t.x.parameter[size_t(x)] << ", alpha " << t.y.parameter[size_t(y)] << ": " << v << " vs " << ref);
            CHECK(std::fabs(v - ref) <= 1.5e-5);
        }
    brdfbake::LutOptions none;
    CHECK_THROWS_WITH(brdfbake::lut("albedo", none), Catch::Contains("model"));
}

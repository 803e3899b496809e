// Blender Cycles' glass tables (ggx_glass_E, ggx_glass_inv_E, ggx_glass_Eavg, ggx_glass_inv_Eavg)
// from `lut dielectric|dielectric-eavg --preset cycles`: the layout against Cycles' convention
// (intern/cycles/app/cycles_precompute.cpp, written out in benchmarks/reference/cycles_glass_reference.h)
// and the values against an independent quadrature of Cycles' definition at Cycles' grid points —
// never against a copy of Cycles' tables.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/table.h"
#include "reference/cycles_glass_reference.h"
#include "support.h"

using namespace brdfbake;
namespace cg = ref::cycles_glass;

namespace {

LutRequest cycles_request(const std::string& kind) {
    LutRequest r;
    r.kind = kind;
    lut_preset("cycles").apply(r);
    return r;
}

size_t texel(int x, int y, int z) { return (size_t(z) * cg::kSize + size_t(y)) * cg::kSize + size_t(x); }

}  // namespace

TEST_CASE("preset cycles: the glass tables' layout is Cycles' (x = roughness, y = mu, z = cycles_z, edges, clamps)",
          "[cycles-glass][presets][device]") {
    LutRequest r = cycles_request("dielectric");
    CHECK(r.model.find("transmission_shadowing=cycles") != std::string::npos);
    // The layout only: a few samples per texel (the values are the next test's).
    r.tolerance.tolerance = 0.0;
    r.samples = 16;
    const Table t = compute_lut(testing::engine(), r);
    REQUIRE(t.x.name == "roughness");
    REQUIRE(t.y.name == "mu");
    REQUIRE(t.z.name == "cycles_z");
    REQUIRE(t.width() == cg::kSize);
    REQUIRE(t.height() == cg::kSize);
    REQUIRE(t.depth() == cg::kSize);
    REQUIRE(t.channels == std::vector<std::string>{"R", "T", "R_inside", "T_inside"});
    for (int i = 0; i < cg::kSize; ++i) {
        INFO("texel " << i);
        // Cycles' r = 1e-4 column and z = 1e-4 slice are singular in its sampler (E = 1); brdfbake
        // holds them as alpha = 0 (the smooth interface) and eta = 1 (no interface).
        CHECK(t.x.parameter[size_t(i)] == Approx(i == 0 ? 0.0 : cg::roughness(i) * cg::roughness(i)).epsilon(1e-14));
        CHECK(t.y.parameter[size_t(i)] == Approx(cg::mu(i)).epsilon(1e-14));
        CHECK(t.z.parameter[size_t(i)] == Approx(i == 0 ? 1.0 : cg::eta(i)).epsilon(1e-12));
        CHECK(t.z.coordinate[size_t(i)] == Approx(i / 15.0).margin(1e-15));
    }
    // The singular texels hold E = 1 on both sides, in closed form, at any sample count.
    for (int a = 0; a < cg::kSize; ++a)
        for (int b = 0; b < cg::kSize; ++b)
            for (size_t k : {texel(0, a, b), texel(a, b, 0)}) {
                CHECK(t.values[0][k] + t.values[1][k] == Approx(1.0).margin(1e-14));
                CHECK(t.values[2][k] + t.values[3][k] == Approx(1.0).margin(1e-14));
            }

    LutRequest e = cycles_request("dielectric-eavg");
    e.tolerance.tolerance = 0.0;
    e.samples = 16;
    validate_lut(e);
    CHECK(e.width == cg::kSize);
    CHECK(e.depth == cg::kSize);
}

TEST_CASE("preset cycles: ggx_glass_E, ggx_glass_inv_E and ggx_glass_Eavg against Cycles' definition",
          "[cycles-glass][presets][device]") {
    // A sub-grid of Cycles' grid through the preset's own axes (edges; z up to 1, computed at
    // 0.99): roughness x in {10, 15}, mu y in {5, 15}, z in {5, 15}, at the preset's --precision
    // double --tolerance 1e-6; within 2.2e-7 of the reference (itself to 1e-7) on both sides, as
    // the README states.
    LutRequest r = cycles_request("dielectric");
    REQUIRE(r.tolerance.tolerance == 1e-6);
    REQUIRE(std::isinf(r.eta_hi));
    r.width = r.height = r.depth = 2;
    r.alpha_lo = 10.0 / 15.0;
    r.mu_lo = 5.0 / 15.0;
    r.eta_lo = cg::eta(5);
    const Table t = compute_lut(testing::engine(), r);
    REQUIRE(t.x.name == "roughness");
    REQUIRE(t.z.name == "cycles_z");
    const int xs[] = {10, 15}, ys[] = {5, 15}, zs[] = {5, 15};
    for (int i = 0; i < 2; ++i) {
        CHECK(t.x.parameter[size_t(i)] == Approx(std::pow(cg::roughness(xs[i]), 2)).epsilon(1e-13));
        CHECK(t.y.parameter[size_t(i)] == Approx(cg::mu(ys[i])).epsilon(1e-13));
        CHECK(t.z.parameter[size_t(i)] == Approx(cg::eta(zs[i])).epsilon(1e-12));
    }
    double worst = 0.0;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                const size_t at = (size_t(k) * 2 + size_t(j)) * 2 + size_t(i);
                for (bool inside : {false, true}) {
                    const double expect = cg::E(xs[i], ys[j], zs[k], inside, 1e-7);
                    const double got = inside ? t.values[2][at] + t.values[3][at] : t.values[0][at] + t.values[1][at];
                    INFO("x " << xs[i] << ", y " << ys[j] << ", z " << zs[k] << (inside ? " inside" : " outside")
                              << ": brdfbake " << got << ", reference " << expect << ", error estimate " << t.error[at]);
                    CHECK(std::fabs(got - expect) <= 2.2e-7);
                    worst = std::max(worst, std::fabs(got - expect));
                }
            }
    std::cout << "preset cycles ggx_glass_E / inv_E: worst |E - reference| " << worst << " (16 values)\n";

    // ggx_glass_Eavg at x = 10, z = 10: one centre texel of the preset's axes over roughness
    // [5/15, 1] and z [5/15, 1] (eta from eta(5) to infinity). At --tolerance 1e-5 (R and T each to
    // 2.5e-6, 12 s; at 4e-6, the preset's, 37 s): within its error estimate plus the reference's 1e-6.
    LutRequest e = cycles_request("dielectric-eavg");
    e.tolerance.tolerance = 1e-5;
    e.texels = Texels::Centre;
    e.width = e.depth = 1;
    e.alpha_lo = 5.0 / 15.0;
    e.eta_lo = cg::eta(5);
    const Table avg = compute_lut(testing::engine(), e);
    REQUIRE(avg.channels == std::vector<std::string>{"Eavg", "Eavg_inside"});
    CHECK(avg.x.parameter[0] == Approx(std::pow(cg::roughness(10), 2)).epsilon(1e-13));
    CHECK(avg.z.parameter[0] == Approx(cg::eta(10)).epsilon(1e-12));
    const double expect = cg::Eavg(10, 10, false, 1, 1e-6);
    INFO("Eavg brdfbake " << avg.values[0][0] << ", reference " << expect << ", error estimate " << avg.error[0]);
    std::cout << "preset cycles ggx_glass_Eavg: |Eavg - reference| " << std::fabs(avg.values[0][0] - expect)
              << " (error estimate " << avg.error[0] << ")\n";
    CHECK(std::fabs(avg.values[0][0] - expect) < avg.error[0] + 1e-6);
    CHECK(std::fabs(avg.values[0][0] - expect) <= 4e-8);  // the README's figure
}

TEST_CASE("an eta range up to infinity is Cycles' z axis only", "[cycles-glass][cli]") {
    LutRequest r = cycles_request("dielectric");
    CHECK_NOTHROW(validate_lut(r));
    for (const char* map : {"linear", "f0"}) {
        LutRequest bad = r;
        bad.eta_map = map;
        CHECK_THROWS_AS(validate_lut(bad), Error);
    }
    LutRequest bad = r;
    bad.eta_lo = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(validate_lut(bad), Error);
    bad = r;
    bad.eta_hi = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(validate_lut(bad), Error);
    // The command line: the preset's range with another map is refused, nothing written.
    const std::string never = "/tmp/brdfbake-cycles-glass-never-" + std::to_string(::getpid()) + ".h";
    const testing::CliResult run = testing::run_cli("lut dielectric --preset cycles --eta-map f0 -o " + never);
    INFO(run.err);
    CHECK(run.status == 2);
    CHECK(testing::count_lines(run.err) == 1);
    CHECK(run.err.find("--eta-map cycles") != std::string::npos);
    CHECK(::access(never.c_str(), F_OK) != 0);
}

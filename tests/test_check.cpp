// Validation: the white furnace, reciprocity and value scans, their verdicts and exit codes,
// and the pictures they draw.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/ggx.h"
#include "brdfbake/check.h"
#include <cmath>
#include <vector>

#include "image_readers.h"
#include "model_refs.h"
#include "support.h"

using namespace brdfbake;

namespace {

CheckReport check(const std::string& spec, const std::string& fresnel = "none") {
    CheckOptions o;
    o.directions = 16;
    o.samples = 1 << 14;
    o.resolution = 16;
    o.phi_resolution = 16;
    return run_check(testing::engine(), resolve_model(spec), resolve_fresnel(fresnel), o);
}

using testing::png_colours;

std::string tmp(const std::string& name) { return "/tmp/brdfbake-check-" + std::to_string(::getpid()) + "-" + name; }

}  // namespace

TEST_CASE("energy-conserving reciprocal models pass the check", "[check][device]") {
    for (const char* spec : {"lambert:rho=1", "ggx:alpha=0.3", "ggx:alpha=0.3,shadowing=separable",
                             "ggx:alpha_x=0.05,alpha_y=0.7", "ggx:alpha=1"}) {
        const CheckReport r = check(spec);
        INFO(spec << ": max E " << r.max_albedo << " +- " << r.max_albedo_error << ", reciprocity " << r.max_rel);
        CHECK(r.passed());
        CHECK(r.max_albedo <= 1.0 + r.max_albedo_error);
        CHECK(r.max_rel <= 1e-12);
        CHECK(r.nonfinite == 0);
        CHECK(r.min_value >= 0.0);
    }
    // With a conductor's Fresnel term the albedo only drops.
    CHECK(check("ggx:alpha=0.3", "schlick:f0=0.9").passed());
}

TEST_CASE("a Lambertian surface with rho > 1 is found to create energy", "[check][device]") {
    const CheckReport r = check("lambert:rho=1.01");
    CHECK(r.energy_violation);
    CHECK_FALSE(r.passed());
    CHECK(r.max_albedo == Approx(1.01).margin(1e-5));
}

TEST_CASE("a NaN reaching a kernel is caught, not reported as a value", "[check][device]") {
    // Bypass the spec checks: an alpha of NaN reaches the kernel.
    ModelConfig m = resolve_model("ggx:alpha=0.5");
    m.params[BB_GGX_ALPHA_X] = m.params[BB_GGX_ALPHA_Y] = std::nan("");
    const FresnelConfig f = resolve_fresnel("none");
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = f;
    req.cells = cells_for({0.5}, 0.0, m.params);
    req.samples = 1 << 10;
    CHECK_THROWS_AS(compute_albedo(testing::engine(), req), NonFiniteError);
    CheckOptions o;
    o.directions = 4;
    o.samples = 1 << 10;
    o.resolution = 8;
    o.phi_resolution = 8;
    const CheckReport r = run_check(testing::engine(), m, f, o);
    CHECK(r.value_violation);
    CHECK(r.nonfinite > 0);
    CHECK_FALSE(r.passed());
    // alpha = 0 is a mirror: its importance samples stay finite, but f itself is 1/0 off the
    // specular direction, which the value scan catches.
    m.params[BB_GGX_ALPHA_X] = m.params[BB_GGX_ALPHA_Y] = 0.0;
    const CheckReport z = run_check(testing::engine(), m, f, o);
    CHECK(z.value_violation);
    CHECK(z.nonfinite > 0);
}

TEST_CASE("check exits 0 on a pass, 1 on a violation, 2 on bad input", "[check][cli]") {
    const auto pass = testing::run_cli("check --model ggx:alpha=0.5 --directions 8 --samples 4096 --format json");
    CHECK(pass.status == 0);
    const auto j = nlohmann::json::parse(pass.out);
    CHECK(j.at("passed").get<bool>());
    CHECK(j.at("reciprocity").at("max_relative_error").get<double>() == 0.0);
    CHECK(j.at("energy").at("max_albedo").get<double>() < 1.0);

    const auto gain = testing::run_cli("check --model lambert:rho=1.2 --directions 8 --samples 4096");
    CHECK(gain.status == 1);
    CHECK(gain.out.find("energy       FAIL") != std::string::npos);
    CHECK(gain.out.find("verdict: VIOLATION") != std::string::npos);

    const auto bad = testing::run_cli("check --model ggx:alpha=-1");
    CHECK(bad.status == 2);
    CHECK(bad.err.rfind("brdfbake: error: ", 0) == 0);
}

TEST_CASE("reciprocity writes its map as EXR and heatmap, furnace and albedo draw their pictures",
          "[check][cli]") {
    const std::string exr = tmp("recip.exr"), png = tmp("recip.png"), furnace = tmp("furnace.png"),
                      curves = tmp("albedo.png");
    // The map read with OpenEXR: GGX is reciprocal exactly, 0 at every pair (README).
    auto r = testing::run_cli("reciprocity --model ggx:alpha=0.4 --resolution 16 --phi-resolution 8 -o " + exr +
                              " --plot " + png);
    REQUIRE(r.status == 0);
    int w = 0, h = 0;
    for (float v : testing::exr_channel(exr, "rel_error", w, h)) CHECK(v == 0.0f);
    CHECK(w == 16);
    CHECK(h == 16);
    CHECK(png_colours(png) > 2);  // axes, labels and the map on a background
    // The original Phong model divides by cos theta_i: f(wo,wi)/f(wi,wo) = cos theta_o / cos
    // theta_i wherever the lobe is lit (README), so the map's texel at the centres theta_i =
    // (i + 0.5) 90/16 degrees and theta_o = (j + 0.5) 90/16 degrees holds 1 - min/max of the two
    // cosines: 0 on the diagonal, growing away from it.
    r = testing::run_cli("reciprocity --model phong-original:n=10,ks=0.5 --resolution 16 --phi-resolution 8 -o " + exr +
                         " --plot " + png);
    REQUIRE(r.status == 0);
    const std::vector<float> phong = testing::exr_channel(exr, "rel_error", w, h);
    REQUIRE(phong.size() == 256u);
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            const double ci = std::cos((i + 0.5) / 16 * M_PI / 2), co = std::cos((j + 0.5) / 16 * M_PI / 2);
            const double want = 1 - std::min(ci, co) / std::max(ci, co);
            INFO("theta_i texel " << i << ", theta_o texel " << j << ": " << phong[size_t(j) * 16 + size_t(i)]
                                  << ", closed form " << want);
            CHECK(std::fabs(phong[size_t(j) * 16 + size_t(i)] - want) <= 1e-5);
        }
    CHECK(png_colours(png) > 16);  // a map that varies, not one colour
    // The furnace picture: the environment light blue (README: "drawn in light blue"), not grey
    // and not white, in a corner of the first panel.
    r = testing::run_cli("furnace --model ggx --roughness 0.2,0.8 --pixels 32 --nodes 8 --samples 1024 -o " + furnace);
    REQUIRE(r.status == 0);
    const testing::Png fp = testing::read_png8(furnace);
    REQUIRE(fp.channels >= 3);
    const size_t corner = (size_t(fp.height - 4) * size_t(fp.width) + 4) * size_t(fp.channels);
    const unsigned red = fp.samples[corner], blue = fp.samples[corner + 2];
    INFO("furnace corner: " << red << ", " << fp.samples[corner + 1] << ", " << blue);
    CHECK(blue >= red + 40);
    CHECK(blue >= 160);
    // The albedo curves: a figure with its curves, not a blank picture.
    r = testing::run_cli("albedo --model ggx:alpha=0.2 --model ggx:alpha=0.8 --samples 1024 --plot " + curves);
    REQUIRE(r.status == 0);
    CHECK(png_colours(curves) > 4);
    for (const auto& p : {exr, png, furnace, curves}) std::remove(p.c_str());
    CHECK(testing::run_cli("albedo --model ggx:alpha=0.2 --plot out.gif").status == 2);
    CHECK(testing::run_cli("reciprocity --model ggx:alpha=0.2").status == 2);
    CHECK(testing::run_cli("furnace --model ggx --roughness 0.1 --model lambert -o x.png").status == 2);
}

TEST_CASE("check: phong-original is not reciprocal, unnormalised Blinn-Phong gains energy", "[check][cli]") {
    const auto po = testing::run_cli("check --model phong-original:n=10,ks=0.5 --directions 8 --samples 4096 --format json");
    CHECK(po.status == 1);
    const auto j = nlohmann::json::parse(po.out);
    CHECK(j.at("reciprocity").at("violation").get<bool>());
    CHECK(j.at("reciprocity").at("max_relative_error").get<double>() > 0.1);

    const auto bp = testing::run_cli("check --model blinn-phong:n=10,ks=5 --directions 8 --samples 4096 --format json");
    CHECK(bp.status == 1);
    const auto k = nlohmann::json::parse(bp.out);
    CHECK(k.at("energy").at("violation").get<bool>());
    CHECK_FALSE(k.at("reciprocity").at("violation").get<bool>());

    for (const char* spec : {"beckmann:alpha=0.3", "beckmann:alpha=0.3,shadowing=separable", "torrance-sparrow:d=blinn,n=20",
                             "torrance-sparrow:d=ggx,alpha=0.4", "oren-nayar:sigma=0.5,rho=0.9", "mirror",
                             "dielectric-specular:eta=1.5"}) {
        INFO(spec);
        CHECK(testing::run_cli(std::string("check --model ") + spec + " --directions 8 --samples 4096").status == 0);
    }
}

TEST_CASE("check's energy verdict agrees with independent host integrals", "[check][device]") {
    // Each case: the check's verdict against the reference albedo's maximum over a few mu.
    const std::vector<modelref::Case> cases = {
        modelref::blinn_phong(10),              // (n+2)/2pi normalises D, not the BRDF: E > 1
        modelref::phong(10),                    // normalised Phong: E <= 1
        modelref::oren_nayar(0.8, 1.0),         // E <= rho
        modelref::beckmann(0.5, true),          // single scattering loses energy
        modelref::torrance_sparrow(ref::Dist::Ggx, 0.4),
    };
    for (const auto& c : cases) {
        double ref_max = 0;
        for (double mu : {0.3, 1.0}) ref_max = std::max(ref_max, c.albedo(mu));
        const CheckReport r = check(c.spec);
        INFO(c.spec << ": reference max E " << ref_max << ", check max E " << r.max_albedo << " +- " << r.max_albedo_error);
        CHECK(r.energy_violation == (ref_max > 1.0 + 1e-4));
    }
}

// Tables of a spectral Fresnel term (issue 36, item 2): `lut conductor` with metal:X or thin-film
// and no --wavelength holds the colour integrated over the spectrum, through three tabulated
// Fresnel curves (host/tables/spectral_fresnel.h). Checked against brute force (one table per
// wavelength, summed with the colour weights), the white point (a wavelength-independent F gives
// R = G = B = the albedo at that F) and the mirror limit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "checks.h"
#include "models/spectrum.h"
#include "spectral_checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

/// A small GGX table by the same fixed quadrature rule in double: the rule is linear in the
/// integrand, so a sum of tables over wavelengths is the table of the summed Fresnel curve up to
/// rounding.
LutRequest small_request(const std::string& kind, const std::string& fresnel) {
    LutRequest r = testing::lut_request(kind, "ggx", 3, 2);
    r.fresnel = fresnel;
    r.alpha_lo = 0.1;
    r.alpha_hi = 0.6;
    r.method = Method::Quadrature;
    r.samples = 1u << 12;
    r.precision = Precision::Double;
    return r;
}

}  // namespace

TEST_CASE("spectral conductor table: the colour of single-wavelength tables summed at 5 nm", "[fresnel][colour][lut]") {
    for (const std::string fresnel : {"metal:Au", "thin-film:eta=1.33,thickness=350,base_eta=1.5"}) {
        INFO(fresnel);
        const LutRequest r = small_request("conductor", fresnel);
        const Table t = compute_lut(testing::engine(), r);
        REQUIRE(t.channels == std::vector<std::string>{"R", "G", "B"});
        // Brute force: 81 tables at 380, 385, ..., 780 nm, weighed by the 5 nm colour weights.
        const SpectralWeights& w = srgb_weights(5);
        std::vector<std::array<double, 3>> sum(t.error.size(), {0.0, 0.0, 0.0});
        for (size_t k = 0; k < w.nm.size(); ++k) {
            LutRequest one = r;
            one.wavelength_nm = w.nm[k];
            const Table e = compute_lut(testing::engine(), one);
            REQUIRE(e.channels == std::vector<std::string>{"E"});
            for (size_t i = 0; i < sum.size(); ++i)
                for (int ch = 0; ch < 3; ++ch) sum[i][ch] += w.rgb[k][ch] * e.values[0][i];
        }
        const std::array<double, 3> step = testing::step_difference(fresnel);
        for (size_t i = 0; i < sum.size(); ++i)
            for (int ch = 0; ch < 3; ++ch) {
                INFO("texel " << i << " channel " << ch << ": " << t.values[ch][i] << " vs " << sum[i][ch]);
                // The curve's interpolation error and the 1 nm vs 5 nm sums (at most the largest
                // difference of the curves: the lobe's albedo at F = 1 is below 1), plus rounding.
                CHECK(std::fabs(t.values[ch][i] - sum[i][ch]) <= t.error[i] + step[ch] + 1e-9);
                // A gap the size of those bounds only: far below the channels' differences.
                CHECK(std::fabs(t.values[ch][i] - sum[i][ch]) < 5e-4);
            }
    }
}

TEST_CASE("spectral conductor table: a wavelength-independent F gives R = G = B = its albedo", "[fresnel][colour][lut]") {
    // A film of index 1 is no film: F is the bare glass's at every wavelength (thin_film.h), so each
    // channel's curve is F times the sum of its weights, which is 1 (white = (1, 1, 1)) in sRGB and
    // in ACEScg alike.
    const Table plain = compute_lut(testing::engine(), small_request("albedo", "dielectric:eta=1.5"));
    for (const std::string colour : {"srgb", "acescg"}) {
        INFO(colour);
        LutRequest r = small_request("conductor", "thin-film:eta=1,thickness=300,base_eta=1.5");
        r.colour = colour;
        const Table t = compute_lut(testing::engine(), r);
        for (size_t i = 0; i < t.error.size(); ++i)
            for (int ch = 0; ch < 3; ++ch) {
                INFO("texel " << i << " channel " << ch);
                CHECK(std::fabs(t.values[ch][i] - plain.values[0][i]) <= t.error[i] + 1e-9);
                CHECK(std::fabs(t.values[ch][i] - plain.values[0][i]) < 1e-5);
            }
    }
}

TEST_CASE("spectral conductor table: at mu = 1 and alpha -> 0, fresnel --rgb at normal incidence", "[fresnel][colour][lut]") {
    const auto f = testing::run_cli("fresnel --fresnel metal:Au --rgb --theta 0 --precision double --format json");
    REQUIRE(f.status == 0);
    const auto rgb = nlohmann::json::parse(f.out)["results"][0]["rgb"];
    LutRequest r = small_request("conductor", "metal:Au");
    r.texels = Texels::Edge;  // mu 0 (at the floor) and 1; alpha 0 (the mirror limit) and 0.002
    r.width = r.height = 2;
    r.alpha_lo = 0.0;
    r.alpha_hi = 0.002;
    r.samples = 1u << 16;
    const Table t = compute_lut(testing::engine(), r);
    for (int ch = 0; ch < 3; ++ch) {
        const double normal = rgb[size_t(ch)].get<double>();
        INFO("channel " << ch << ": " << normal);
        CHECK(std::fabs(t.values[ch][1] - normal) < 1e-6);  // alpha = 0, mu = 1: the curve's last node
        CHECK(std::fabs(t.values[ch][3] - normal) < 1e-4);  // alpha = 0.002 integrated on the device
    }
    // Gold's linear-sRGB red at normal incidence is beyond 1 (outside the gamut): kept, not clamped.
    CHECK(t.values[0][1] > 1.0);
}

TEST_CASE("spectral conductor table: --rgb-wavelengths keeps 650, 550 and 450 nm, bad colour spaces are refused",
          "[fresnel][colour][lut][cli]") {
    LutRequest r = small_request("conductor", "metal:Cu");
    r.colour = "wavelengths";
    const Table t = compute_lut(testing::engine(), r);
    const double nm[3] = {650.0, 550.0, 450.0};
    for (int ch = 0; ch < 3; ++ch) {
        LutRequest one = small_request("conductor", "metal:Cu");
        one.wavelength_nm = nm[ch];
        const Table e = compute_lut(testing::engine(), one);
        for (size_t i = 0; i < t.error.size(); ++i) CHECK(t.values[ch][i] == Approx(e.values[0][i]).margin(1e-12));
    }
    const std::string out = "/tmp/brdfbake-colour-" + std::to_string(::getpid()) + ".csv";
    testing::check_refused("lut conductor --model ggx --fresnel metal:Au --size 4 --colour-space xyz -o ", out);
    testing::check_refused("lut conductor --model ggx --fresnel metal:Au --size 4 --colour-space srgb --rgb-wavelengths -o ",
                           out);
    testing::check_refused("lut conductor --model ggx --fresnel metal:Au --size 4 --tolerance 1e-6 -o ", out);
    // A colour option where the table holds no colour would be ignored: refused, naming the option.
    for (const char* args : {"lut albedo --model ggx --size 4 --colour-space acescg -o ",
                             "lut conductor --model ggx --fresnel schlick:f0=0.5 --size 4 --colour-space acescg -o ",
                             "lut conductor --model ggx --fresnel metal:Au --wavelength 500 --size 4 --rgb-wavelengths -o "}) {
        testing::check_refused(args, out);
        const auto refused = testing::run_cli(std::string(args) + out);
        CHECK((refused.err.find("--colour-space") != std::string::npos ||
               refused.err.find("--rgb-wavelengths") != std::string::npos));
    }
    const auto r2 = testing::run_cli("fresnel --fresnel metal:Au --colour-space acescg");
    testing::check_usage_error(r2);
}

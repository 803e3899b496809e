// `brdfbake albedo --fresnel metal:X` (or thin-film:) without --wavelength: the albedo's colour
// (issue 36). Checked against brute force from outside the command: the library's single-wavelength
// albedos at 380, 385, ..., 780 nm summed with the 5 nm colour weights (the albedo is linear in
// F), within the command's error plus the 1 nm vs 5 nm gap of the spectrum itself.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "brdfbake/albedo.h"
#include "brdfbake/spec.h"
#include "models/spectrum.h"
#include "spectral_checks.h"
#include "support.h"

using namespace brdfbake;

TEST_CASE("albedo colour: single-wavelength albedos summed with the colour weights", "[fresnel][colour][albedo]") {
    const std::vector<double> mus = {0.15, 0.6, 1.0};
    for (const std::string fresnel : {"metal:Au", "thin-film:eta=1.33,thickness=350,base_eta=1.5"}) {
        INFO(fresnel);
        const auto run = testing::run_cli("albedo --model ggx:alpha=0.4 --fresnel " + fresnel +
                                          " --mu 0.15,0.6,1 --method quadrature --samples 4096 --precision double "
                                          "--format json");
        REQUIRE(run.status == 0);
        const auto results = nlohmann::json::parse(run.out)["results"];
        REQUIRE(results.size() == mus.size());
        // Brute force: 81 albedos at 5 nm steps by the library, each at its wavelength's n, k or film.
        const ModelConfig m = resolve_model("ggx:alpha=0.4");
        const SpectralWeights& w = srgb_weights(5);
        std::vector<std::array<double, 3>> sum(mus.size(), {0.0, 0.0, 0.0});
        std::vector<double> brute_error(mus.size(), 0.0);
        for (size_t k = 0; k < w.nm.size(); ++k) {
            AlbedoRequest r;
            r.model = m.id;
            r.fresnel = resolve_fresnel(fresnel, w.nm[k]);
            r.method = Method::Quadrature;
            r.samples = 4096;
            r.precision = Precision::Double;
            r.cells = cells_for(mus, 0.0, m.params);
            const AlbedoResult e = compute_albedo(testing::engine(), r);
            for (size_t i = 0; i < mus.size(); ++i) {
                double weight = 0.0;
                for (int ch = 0; ch < 3; ++ch) {
                    sum[i][ch] += w.rgb[k][ch] * e.values[i].value;
                    weight = std::max(weight, std::fabs(w.rgb[k][ch]));
                }
                brute_error[i] += weight * e.values[i].error;
            }
        }
        const std::array<double, 3> step = testing::step_difference(fresnel);
        for (size_t i = 0; i < mus.size(); ++i)
            for (int ch = 0; ch < 3; ++ch) {
                const double value = results[i]["rgb"][ch], error = results[i]["rgb_error"][ch];
                INFO("mu " << mus[i] << " channel " << ch << ": " << value << " +- " << error << " vs " << sum[i][ch]);
                CHECK(error > 0.0);
                CHECK(std::fabs(value - sum[i][ch]) <= error + brute_error[i] + step[ch] + 1e-9);
                CHECK(std::fabs(value - sum[i][ch]) < 5e-4);  // far below the channels' differences
            }
    }
}

TEST_CASE("albedo colour: a wavelength-independent F gives R = G = B = its albedo, and refusals", "[fresnel][colour][albedo]") {
    // A film of index 1 is no film: F is the bare glass's at every wavelength.
    const auto film = testing::run_cli("albedo --model ggx:alpha=0.4 --fresnel thin-film:eta=1,thickness=300,base_eta=1.5 "
                                       "--mu 0.3,1 --method quadrature --precision double --format json");
    const auto glass = testing::run_cli("albedo --model ggx:alpha=0.4 --fresnel dielectric:eta=1.5 --mu 0.3,1 "
                                        "--method quadrature --precision double --format json");
    REQUIRE(film.status == 0);
    REQUIRE(glass.status == 0);
    const auto f = nlohmann::json::parse(film.out)["results"], g = nlohmann::json::parse(glass.out)["results"];
    for (size_t i = 0; i < 2; ++i)
        for (int ch = 0; ch < 3; ++ch) {
            const double v = f[i]["rgb"][ch], e = f[i]["rgb_error"][ch], ref = g[i]["albedo"], ref_e = g[i]["error"];
            CHECK(std::fabs(v - ref) <= e + ref_e + 1e-9);
        }
    // One line, exit 2: a random walk takes one wavelength; --colour-space needs a spectral term.
    const auto walk = testing::run_cli("albedo --model ggx:alpha=0.4,scattering=multiple --fresnel metal:Au --mu 0.5");
    CHECK(walk.status == 2);
    CHECK(walk.err.find("--wavelength") != std::string::npos);
    const auto space = testing::run_cli("albedo --model ggx:alpha=0.4 --fresnel dielectric:eta=1.5 --colour-space acescg");
    CHECK(space.status == 2);
    CHECK(space.err.find("--colour-space") != std::string::npos);
}

// The thin-film table over film thickness (issue 36, item 4; host/tables/kind_thin_film.cpp) and
// glTF's KHR_materials_iridescence planned to it. A slice is checked against brute force by
// another path: one single-wavelength conductor table per 5 nm (the Airy term at that wavelength,
// no tabulated curve), summed with the colour weights; thickness 0 against the bare substrate's
// own conductor table (a physical law: no film, no interference); the glTF mapping against the
// extension's documented defaults (KhronosGroup/glTF, KHR_materials_iridescence/README.md:
// iridescenceIor 1.3, thickness 100 to 400 nm, thickness = maximum without a texture).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <fstream>
#include <sys/stat.h>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "checks.h"
#include "models/spectrum.h"
#include "scene/scene.h"
#include "scene_support.h"
#include "spectral_checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

/// A small GGX table by a fixed quadrature rule in double (linear in the integrand: a sum of
/// tables over wavelengths is the table of the summed curve up to rounding).
LutRequest film_request(const std::string& fresnel, int depth, double lo, double hi) {
    LutRequest r = testing::lut_request("thin-film", "ggx", 3, 2, depth);
    r.fresnel = fresnel;
    r.alpha_lo = 0.1;
    r.alpha_hi = 0.6;
    r.thickness_lo = lo;
    r.thickness_hi = hi;
    r.texels = depth > 1 ? Texels::Edge : Texels::Centre;
    r.method = Method::Quadrature;
    r.samples = 1u << 12;
    r.precision = Precision::Double;
    return r;
}

/// The conductor kind's request on the same grid (x, y) with `fresnel`.
LutRequest conductor_request(const LutRequest& film, const std::string& fresnel) {
    LutRequest c = film;
    c.kind = "conductor";
    c.fresnel = fresnel;
    c.depth = LutRequest{}.depth;
    return c;
}

}  // namespace

TEST_CASE("thin-film table: each thickness slice is the colour of single-wavelength tables summed at 5 nm",
          "[fresnel][colour][lut][thin-film]") {
    const LutRequest r = film_request("thin-film:eta=1.33,base_eta=1.5", 2, 100.0, 400.0);
    const Table t = compute_lut(testing::engine(), r);
    REQUIRE(t.channels == std::vector<std::string>{"R", "G", "B"});
    REQUIRE(t.depth() == 2);
    REQUIRE(t.z.name == "thickness_nm");
    CHECK(t.z.parameter == std::vector<double>{100.0, 400.0});
    const size_t slice = size_t(t.width() * t.height());
    const SpectralWeights& w = srgb_weights(5);
    for (int z = 0; z < 2; ++z) {
        const std::string film = "thin-film:eta=1.33,base_eta=1.5,thickness=" + std::string(z ? "400" : "100");
        INFO(film);
        std::vector<std::array<double, 3>> sum(slice, {0.0, 0.0, 0.0});
        for (size_t k = 0; k < w.nm.size(); ++k) {
            LutRequest one = conductor_request(r, film);
            one.wavelength_nm = w.nm[k];
            const Table e = compute_lut(testing::engine(), one);
            REQUIRE(e.channels == std::vector<std::string>{"E"});
            for (size_t i = 0; i < slice; ++i)
                for (int ch = 0; ch < 3; ++ch) sum[i][ch] += w.rgb[k][ch] * e.values[0][i];
        }
        const std::array<double, 3> step = testing::step_difference(film);
        for (size_t i = 0; i < slice; ++i)
            for (int ch = 0; ch < 3; ++ch) {
                const double v = t.values[size_t(ch)][size_t(z) * slice + i];
                INFO("texel " << i << " channel " << ch << ": " << v << " vs " << sum[i][ch]);
                CHECK(std::fabs(v - sum[i][ch]) <= t.error[size_t(z) * slice + i] + step[size_t(ch)] + 1e-9);
                CHECK(std::fabs(v - sum[i][ch]) < 5e-4);
            }
    }
    // The two slices differ by far more than that: the thickness changes the colour.
    double spread = 0.0;
    for (size_t i = 0; i < slice; ++i)
        for (int ch = 0; ch < 3; ++ch)
            spread = std::max(spread, std::fabs(t.values[size_t(ch)][i] - t.values[size_t(ch)][slice + i]));
    CHECK(spread > 0.01);
}

TEST_CASE("thin-film table: thickness 0 is the bare substrate (gold's conductor table), --wavelength gives E",
          "[fresnel][colour][lut][thin-film]") {
    const LutRequest r = film_request("thin-film:eta=1.4,base=metal:Au", 1, 0.0, 0.0);
    const Table t = compute_lut(testing::engine(), r);
    const Table gold = compute_lut(testing::engine(), conductor_request(r, "metal:Au"));
    REQUIRE(gold.channels == t.channels);
    for (size_t i = 0; i < t.error.size(); ++i)
        for (size_t ch = 0; ch < 3; ++ch) {
            INFO("texel " << i << " channel " << ch);
            CHECK(std::fabs(t.values[ch][i] - gold.values[ch][i]) <= t.error[i] + gold.error[i] + 1e-9);
        }
    // One wavelength: one channel, the conductor table of the film at that thickness.
    LutRequest one = film_request("thin-film:eta=1.4,base=metal:Au", 1, 250.0, 250.0);
    one.wavelength_nm = 550.0;
    const Table e = compute_lut(testing::engine(), one);
    LutRequest c = conductor_request(one, "thin-film:eta=1.4,base=metal:Au,thickness=250");
    const Table ce = compute_lut(testing::engine(), c);
    REQUIRE(e.channels == std::vector<std::string>{"E"});
    for (size_t i = 0; i < e.error.size(); ++i) CHECK(std::fabs(e.values[0][i] - ce.values[0][i]) <= 1e-12);
}

TEST_CASE("thin-film table: bad requests are refused with one line", "[fresnel][lut][thin-film][quick]") {
    LutRequest r = film_request("metal:Au", 2, 100.0, 400.0);
    CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("needs --fresnel thin-film:"));
    r = film_request("thin-film:eta=1.3,base_eta=1.5", 2, 400.0, 100.0);
    CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("--thickness-range"));
    r = film_request("thin-film:eta=1.3,base_eta=1.5", 4, 300.0, 300.0);
    CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("one thickness"));
    r = film_request("thin-film:eta=1.3,base_eta=1.5", 2, 100.0, 400.0);
    r.colour = "wavelengths";
    CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("--rgb-wavelengths"));
    const auto cli = testing::run_cli("lut thin-film --model ggx --fresnel thin-film:eta=1.3,base_eta=1.5 --thickness-range=-5,100 "
                                      "-o /tmp/brdfbake-film-never.csv");
    CHECK(cli.status == 2);
    CHECK_FALSE(std::ifstream("/tmp/brdfbake-film-never.csv").good());
    CHECK(cli.err.find("brdfbake: error: --thickness-range") != std::string::npos);
}

TEST_CASE("glTF: KHR_materials_iridescence plans a thin-film table over the film's thickness range",
          "[scene][gltf][thin-film][quick]") {
    using namespace testing::scene;
    const std::string dir = fresh_tmp_dir("iridescence");
    ::mkdir(dir.c_str(), 0755);
    auto doc = [](const std::string& ext) {
        return R"({"asset": {"version": "2.0"}, "materials": [{"name": "bubble", "pbrMetallicRoughness": )"
               R"({"metallicFactor": 0, "roughnessFactor": 0.3}, "extensions": {"KHR_materials_ior": {"ior": 1.4}, )"
               R"("KHR_materials_iridescence": )" + ext + "}}]}";
    };
    // The extension's defaults: iridescenceIor 1.3, no thickness texture: the maximum, 400 nm.
    std::ofstream(dir + "/a.gltf") << doc(R"({"iridescenceFactor": 1})");
    const Plan a = make_plan(load_scene(dir + "/a.gltf"));
    const PlannedTable* t = find_kind(a, "thin-film");
    REQUIRE(t);
    CHECK(t->request.fresnel == "thin-film:eta=1.3,base_eta=1.4");
    CHECK(t->request.thickness_lo == 400.0);
    CHECK(t->request.thickness_hi == 400.0);
    CHECK(t->request.depth == 1);
    CHECK(t->unavailable.empty());
    // Given values; a factor of 0 has no effect and plans no film.
    std::ofstream(dir + "/b.gltf") << doc(
        R"({"iridescenceFactor": 0.5, "iridescenceIor": 1.8, "iridescenceThicknessMinimum": 200, )"
        R"("iridescenceThicknessMaximum": 900})");
    const Plan pb = make_plan(load_scene(dir + "/b.gltf"));
    const PlannedTable* b = find_kind(pb, "thin-film");
    REQUIRE(b);
    CHECK(b->request.fresnel == "thin-film:eta=1.8,base_eta=1.4");
    CHECK(b->request.thickness_hi == 900.0);
    std::ofstream(dir + "/c.gltf") << doc(R"({"iridescenceFactor": 0})");
    CHECK_FALSE(find_kind(make_plan(load_scene(dir + "/c.gltf")), "thin-film"));
    std::ofstream(dir + "/d.gltf") << doc(R"({"iridescenceFactor": 1, "iridescenceIor": -2})");
    CHECK_THROWS_WITH(load_scene(dir + "/d.gltf"), Catch::Contains("iridescenceIor"));
}

TEST_CASE("scene files: a film's base=nk: path is read from the scene file's folder", "[scene][thin-film][quick]") {
    using namespace testing::scene;
    const std::string dir = fresh_tmp_dir("film-nk");
    ::mkdir(dir.c_str(), 0755);
    const std::string here = __FILE__;
    const std::string root = here.substr(0, here.find_last_of('/', here.find_last_of('/') - 1));
    std::ofstream(dir + "/copper.yml") << testing::slurp(root + "/data/nk/Cu-Johnson.yml");
    std::ofstream(dir + "/s.json") << R"({"materials": [{"name": "film", "model": "ggx", "roughness": 0.3,
        "fresnel": "thin-film:eta=1.4,thickness=300,base=nk:copper.yml"}]})";
    // The test runs in the build folder, which has no copper.yml: reading the film's substrate
    // (the scene is checked at 550 nm) fails unless the path is taken beside the scene.
    const Scene s = load_scene(dir + "/s.json");
    REQUIRE(s.materials.size() == 1);
    CHECK(s.materials[0].lobes[0].fresnel == "thin-film:eta=1.4,thickness=300,base=nk:" + dir + "/copper.yml");
    CHECK(make_plan(s).tables.at(0).unavailable.empty());
}

TEST_CASE("scene files: a thin film's thickness range plans a thin-film table, sliced by thickness_step",
          "[scene][thin-film][quick]") {
    using namespace testing::scene;
    const std::string dir = fresh_tmp_dir("film-json");
    ::mkdir(dir.c_str(), 0755);
    auto scene = [&](const std::string& name, const std::string& material, const std::string& settings = "{}") {
        std::ofstream(dir + "/" + name) << R"({"materials": [{"name": "film", "model": "ggx", "roughness": 0.3, )" +
                                              material + R"(}], "settings": )" + settings + "}";
        return dir + "/" + name;
    };
    // "thickness": [lo, hi] with a spec without one: the thin-film kind by default. The documented
    // rule, ceil((hi - lo) / thickness_step) + 1 slices: 16 for glTF's 100-400 nm at the default
    // 20 nm, 7 at 50 nm, 51 for 0-1000 nm at 20 nm.
    struct Case {
        std::string range, settings;
        double lo, hi;
        int depth;
    };
    for (const Case& c : {Case{"[100, 400]", "{}", 100, 400, 16}, Case{"[100, 400]", R"({"thickness_step": 50})", 100, 400, 7},
                          Case{"[0, 1000]", "{}", 0, 1000, 51}, Case{"[100, 110]", R"({"thickness_step": 30})", 100, 110, 2}}) {
        INFO(c.range << " " << c.settings);
        const Plan p = make_plan(load_scene(scene(
            "a.json", R"("fresnel": "thin-film:eta=1.3,base_eta=1.5", "thickness": )" + c.range, c.settings)));
        REQUIRE(p.tables.size() == 1);
        const PlannedTable* t = find_kind(p, "thin-film");
        REQUIRE(t);
        CHECK(t->request.thickness_lo == c.lo);
        CHECK(t->request.thickness_hi == c.hi);
        CHECK(t->request.depth == c.depth);
        CHECK(t->unavailable.empty());
    }
    // The spec's own thickness, with "tables" naming the kind: one slice at it.
    const Plan one = make_plan(load_scene(scene(
        "b.json", R"("fresnel": "thin-film:eta=1.45,thickness=300,base=metal:Au", "tables": ["thin-film"])")));
    const PlannedTable* t = find_kind(one, "thin-film");
    REQUIRE(t);
    CHECK(t->request.thickness_lo == 300.0);
    CHECK(t->request.depth == 1);
    // Refused with the reason: a thickness on another term, twice, a thin-film table without a
    // film, a bad step.
    CHECK_THROWS_WITH(load_scene(scene("c.json", R"("fresnel": "metal:Au", "thickness": [100, 200])")),
                      Catch::Contains("'thickness' is a thin film's"));
    CHECK_THROWS_WITH(load_scene(scene("d.json", R"("fresnel": "thin-film:eta=1.3,thickness=300,base_eta=1.5", "thickness": 200)")),
                      Catch::Contains("thickness once"));
    CHECK_THROWS_WITH(load_scene(scene("e.json", R"("fresnel": "dielectric:eta=1.5", "tables": ["thin-film"])")),
                      Catch::Contains("thin-film Fresnel"));
    CHECK_THROWS_WITH(load_scene(scene("f.json", R"("fresnel": "thin-film:eta=1.3,base_eta=1.5", "thickness": [100, 400])",
                                       R"({"thickness_step": 0})")),
                      Catch::Contains("thickness_step"));
}

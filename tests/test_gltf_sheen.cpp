// The glTF Sample Viewer's sheen LUTs (--preset gltf, kind sheen-viewer; bake --target gltf): the
// 16-bit PNGs decoded the way the viewer's shaders read them (texture(u_SheenELUT, vec2(NdotV,
// sheenRoughness)).r, texture(u_CharlieLUT, ...).b, row 0 at roughness 0, texel centres) and
// compared with an independent quadrature of the viewer's definition: the directional albedo of
// D_Charlie (Estevez and Kulla 2017, eq. 2) times its visibility clamped to [0, 1] (V_Sheen of
// brdf.glsl with the fitted Lambda of Estevez-Kulla's Table 1; V_Ashikhmin of
// ibl_filtering.frag), integrated over the outgoing direction l in spherical coordinates by
// adaptive Gauss-Kronrod (brdfbake integrates over half vectors in the Charlie inverse CDF).
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "image_readers.h"
#include "scene_support.h"
#include "support.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Estevez-Kulla's fitted sheen Lambda, interpolated in (1 - alpha)^2 between their two rows.
double ek_l(double x, double alpha) {
    const double t = (1 - alpha) * (1 - alpha);
    const double a = (1 - t) * 21.5473 + t * 25.3245, b = (1 - t) * 3.82987 + t * 3.32435,
                 c = (1 - t) * 0.19823 + t * 0.16801, d = (1 - t) * -1.97760 + t * -1.27393,
                 e = (1 - t) * -4.32054 + t * -4.85967;
    return a / (1 + b * std::pow(x, c)) + d * x + e;
}
double ek_lambda(double mu, double alpha) {
    return mu < 0.5 ? std::exp(ek_l(mu, alpha)) : std::exp(2 * ek_l(0.5, alpha) - ek_l(1 - mu, alpha));
}

/// E(mu, r) of the viewer's sheen: integral over l of D(h) min(V, 1) cos(theta_l).
double viewer_albedo(double mu, double r, bool charlie) {
    const double alpha = r * r, sv = std::sqrt(1 - mu * mu);
    auto integrand = [&](double theta, double phi) {
        const double cl = std::cos(theta), sl = std::sin(theta);
        const double hx = sv + sl * std::cos(phi), hy = sl * std::sin(phi), hz = mu + cl;
        const double cos_h = hz / std::sqrt(hx * hx + hy * hy + hz * hz), sin2_h = 1 - cos_h * cos_h;
        const double d = (2 + 1 / alpha) * std::pow(std::max(sin2_h, 0.0), 0.5 / alpha) / (2 * kPi);
        const double v = charlie ? 1 / ((1 + ek_lambda(mu, alpha) + ek_lambda(cl, alpha)) * 4 * mu * cl)
                                 : 1 / (4 * (cl + mu - cl * mu));
        return d * std::min(v, 1.0) * cl * sl;
    };
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    const double outer = GK::integrate(
        [&](double phi) {
            return GK::integrate([&](double theta) { return integrand(theta, phi); }, 0.0, kPi / 2, 12, 1e-11);
        },
        0.0, kPi, 12, 1e-10);
    return 2 * outer;  // phi over [0, 2 pi]: the lobe is mirror symmetric in phi
}

struct Decoded {
    int w = 0, h = 0;
    std::vector<double> rgb;  // 3 per texel, in [0, 1]
    double at(int x, int y, int c) const { return rgb[(size_t(y) * w + x) * 3 + c]; }
};

Decoded decode(const std::string& path) {
    const testing::Png p = testing::read_png(path);
    Decoded d;
    d.w = p.width;
    d.h = p.height;
    REQUIRE(p.channels == 3);
    for (unsigned s : p.samples) d.rgb.push_back(s / 65535.0);
    return d;
}

void check_against_definition(const Decoded& d, bool charlie) {
    // texel (x, y): NdotV = (x + 0.5)/w, sheenRoughness = (y + 0.5)/h (row 0 at 0)
    const int probes[][2] = {{0, 15}, {7, 7}, {15, 5}, {3, 10}, {10, 12}, {2, 6}};
    for (const auto& p : probes) {
        const double mu = (p[0] + 0.5) / d.w, r = (p[1] + 0.5) / d.h;
        const double expect = std::min(viewer_albedo(mu, r, charlie), 1.0);
        INFO((charlie ? "lut_sheen_E" : "lut_charlie") << " texel (" << p[0] << ", " << p[1] << "): mu " << mu
                                                        << ", roughness " << r << ", reference " << expect);
        CHECK(d.at(p[0], p[1], 0) == d.at(p[0], p[1], 2));  // R = G = B: .r and .b read the same
        CHECK(d.at(p[0], p[1], 0) == d.at(p[0], p[1], 1));
        // 16-bit quantization (7.6e-6) and the table's quadrature (its error channel: below 1e-6)
        CHECK(std::fabs(d.at(p[0], p[1], charlie ? 0 : 2) - expect) < 1e-4);
    }
    for (double v : d.rgb) CHECK((v >= 0.0 && v <= 1.0));
}

}  // namespace

TEST_CASE("preset gltf: lut_sheen_E and lut_charlie hold the viewer's sheen albedo where its shaders read it",
          "[presets][sheen][gltf]") {
    const std::string dir = testing::scene::fresh_tmp_dir("gltf-sheen");
    ::mkdir(dir.c_str(), 0755);
    const auto e = testing::run_cli("lut sheen-viewer --preset gltf --size 16x16 -o " + dir + "/lut_sheen_E.png --no-preview");
    INFO(e.err);
    REQUIRE(e.status == 0);
    const auto c = testing::run_cli("lut sheen-viewer --preset gltf --model sheen:visibility=ashikhmin --size 16x16 -o " +
                                    dir + "/lut_charlie.png --no-preview");
    INFO(c.err);
    REQUIRE(c.status == 0);
    const Decoded sheen_e = decode(dir + "/lut_sheen_E.png"), charlie = decode(dir + "/lut_charlie.png");
    REQUIRE(sheen_e.w == 16);
    REQUIRE(sheen_e.h == 16);
    check_against_definition(sheen_e, true);
    check_against_definition(charlie, false);
    // the two visibilities differ: a table of the wrong one would fail above, and this says they are distinct
    CHECK(std::fabs(sheen_e.at(2, 6, 0) - charlie.at(2, 6, 0)) > 0.05);
    std::system(("rm -rf " + dir).c_str());
}

TEST_CASE("bake --target gltf of a sheen material plans and writes lut_charlie and lut_sheen_E in the time it plans",
          "[scene][gltf][sheen]") {
    using testing::scene::data;
    const std::string out = testing::scene::fresh_tmp_dir("gltf-sheen-bake");
    const auto plan = testing::run_cli("plan " + data("materials.gltf") + " --target gltf --size 16 --samples 64 --format json");
    INFO(plan.err);
    REQUIRE(plan.status == 0);
    const nlohmann::json p = nlohmann::json::parse(plan.out);
    double planned = 0;
    for (const auto& t : p["tables"])
        if (t["file"] == "lut_sheen_E.png" || t["file"] == "lut_charlie.png") {
            CHECK(t["kind"] == "sheen-viewer");
            planned += t["estimated_seconds"].get<double>();
        }
    const auto t0 = std::chrono::steady_clock::now();
    const auto bake = testing::run_cli("bake " + data("materials.gltf") + " --target gltf --size 16 --samples 64 -o " + out);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    INFO(bake.err);
    REQUIRE(bake.status == 0);  // a plan that exits 0 bakes
    check_against_definition(decode(out + "/lut_sheen_E.png"), true);
    check_against_definition(decode(out + "/lut_charlie.png"), false);
    INFO("planned " << planned << " s for the two sheen tables; the whole bake took " << took << " s");
    CHECK(planned > 0);
    std::system(("rm -rf " + out).c_str());
}

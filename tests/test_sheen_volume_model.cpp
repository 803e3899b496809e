// The volumetric sheen layer of Zeltner, Burley and Chiang 2022 as a model spec,
// `sheen-volume:roughness=R[,bounces=N]` (brdf/sheen_volume_model.h, BB_TRAIT_LAYER_WALK): its albedo,
// check, lobe and lut albedo by the layer's walks (integrate/sheen_volume.h), and every pointwise use
// refused. From outside: the albedo against the R column of the shipped table `lut sheen-ltc` baked
// (data/sheen_ltc/, the same simulation run by another command: a consistency check), each walk
// ending in one of R, T and the cut-off (R + T = 1 - cutoff: the layer absorbs nothing), the white
// furnace and reciprocity of `check` (reciprocity: the flux between two theta bands is the same both
// ways for a reciprocal medium), and the lobe's histogram integrated over the hemisphere against R.
// The independent numpy walk of the same layer: tests/python/test_sheen_volume_walk.py.
#include <catch2/catch.hpp>

#include <cmath>

#include "brdfbake/albedo.h"
#include "brdfbake/check.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "integrate/random_walk.h"
#include "integrate/sheen_volume.h"
#include "support.h"

using namespace brdfbake;

namespace {

std::string exact(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

}  // namespace

TEST_CASE("sheen-volume: the spec, and every pointwise use refused in one line", "[sheen-volume][quick]") {
    const ModelConfig m = resolve_model_simulated("sheen-volume:roughness=0.5");
    CHECK(m.simulated);
    CHECK(m.traits().layer_walk);
    CHECK(m.traits().stochastic);
    CHECK_FALSE(m.uses_fresnel);
    CHECK(m.canonical == "sheen-volume:alpha=0.25,bounces=1000");
    CHECK(resolve_model_simulated("sheen-volume:alpha=0.25,bounces=20").canonical == "sheen-volume:alpha=0.25,bounces=20");
    CHECK_THROWS_WITH(resolve_model_simulated("sheen-volume:roughness=0.5,bounces=2.5"), Catch::Contains("not an integer"));
    CHECK_THROWS_WITH(resolve_model("sheen-volume:roughness=0.5"), Catch::Contains("no pointwise value"));
    // commands that evaluate f pointwise: one line, exit 2
    for (const char* cmd : {"reciprocity --model sheen-volume:roughness=0.5", "furnace --model sheen-volume:roughness=0.5",
                            "albedo --model sheen-volume:roughness=0.5 --method quadrature",
                            "albedo --model sheen-volume:roughness=0.5 --fresnel schlick:f0=0.04"}) {
        const auto r = testing::run_cli(cmd);
        INFO(cmd << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
    }
}

TEST_CASE("sheen-volume: albedo by walks, R + T + cut-off = 1, and the shipped sheen-ltc table's R", "[sheen-volume]") {
    // The table (data/sheen_ltc/sheen_ltc_cycles.csv) was baked by `lut sheen-ltc --preset cycles`
    // at 2^18 walks a texel, its R's error in the `error` channel: the same layer's walks run by
    // another command (a consistency check of the routing and the roughness mapping, not the truth).
    const Table t = read_table(std::string(BRDFBAKE_SOURCE_DIR) + "/data/sheen_ltc/sheen_ltc_cycles.csv");
    int r_ch = -1;  // the table's error is R's (its header's error_channel)
    for (size_t c = 0; c < t.channels.size(); ++c)
        if (t.channels[c] == "R") r_ch = int(c);
    REQUIRE(r_ch >= 0);
    REQUIRE(t.error.size() == t.values[size_t(r_ch)].size());
    const int w = t.width();
    for (int j : {8, 20, 31}) {
        const double r = t.y.coordinate[size_t(j)];
        const ModelConfig m = resolve_model_simulated("sheen-volume:roughness=" + exact(r));
        AlbedoRequest req;
        req.model = m.id;
        req.samples = 1u << 16;
        std::vector<int> is = {6, 18, 31};
        for (int i : is) req.cells.push_back(AlbedoCell{t.x.coordinate[size_t(i)], 0.0, m.params});
        const WalkResult res = walk_albedo(testing::engine(), req);  // the routing by the registry's trait
        for (size_t k = 0; k < is.size(); ++k) {
            const WalkAlbedo& v = res.values[k];
            const double R = t.values[size_t(r_ch)][size_t(j * w + is[k])];
            const double err = t.error[size_t(j * w + is[k])];
            INFO("roughness " << r << " mu " << req.cells[k].mu << ": walk R " << v.energy.value << " +- "
                              << v.energy.error << ", table " << R << " +- " << err);
            CHECK(std::fabs(v.energy.value - R) <= v.energy.error + err);
            CHECK(v.energy.error < 0.05 * R + 1e-3);  // the comparison has teeth
            CHECK(v.energy.value + v.transmitted.value + v.cutoff.value == Approx(1.0).margin(1e-6));
            CHECK(v.total.value + v.cutoff.value == Approx(1.0).margin(1e-6));
            CHECK(v.single.value <= v.energy.value);
        }
    }
}

TEST_CASE("sheen-volume: check passes the furnace (R + T <= 1) and reciprocity of band fluxes", "[sheen-volume]") {
    const ModelConfig m = resolve_model_simulated("sheen-volume:roughness=0.6");
    CheckOptions o;
    o.directions = 6;
    o.samples = 1u << 14;
    o.reciprocity_tolerance = 1e-3;
    const CheckReport r = run_check(testing::engine(), m, resolve_fresnel("none"), o);
    INFO(check_report_text(r));
    CHECK(r.passed());
    CHECK(r.reciprocity_noise);
    CHECK(r.pairs == 24);
    CHECK(r.max_albedo <= 1.0 + r.max_albedo_error);
    CHECK(r.max_albedo > 0.99);  // R + T: what the bounce limit cut off is all that is missing
    CHECK(r.reciprocity_sigmas < kReciprocitySigmas);
    CHECK(r.max_rel < 0.2);  // the band fluxes are known well enough for the comparison to bite
    CHECK(check_report_text(r).find("band fluxes") != std::string::npos);
}

TEST_CASE("sheen-volume: the lobe's histogram integrates to R, its first order in closed form", "[sheen-volume]") {
    // f cos theta_o summed over a fine grid of outgoing directions (the lobe's own estimate,
    // histogram plus closed-form first order) against the albedo R of the same walks' cell.
    const ModelConfig m = resolve_model_simulated("sheen-volume:roughness=0.5");
    const double mu = 0.6;
    const Vec3 wi = {std::sqrt(1 - mu * mu), 0.0, mu};
    std::vector<Vec3> wos, wis;
    const int nt = 64, np = 64;
    for (int a = 0; a < nt; ++a)
        for (int b = 0; b < np; ++b) {
            const double th = (a + 0.5) / nt * M_PI / 2, ph = (b + 0.5) / np * 2 * M_PI;
            wos.push_back({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
            wis.push_back(wi);
        }
    std::vector<double> err;
    const std::vector<double> f = sheen_layer_lobe(testing::engine(), m, Precision::Float, wos, wis, 1u << 18, &err);
    // the grid's points in one histogram bin share its error: linear within a bin, in quadrature across
    const int bt = SheenLobeBins::theta(), bp = SheenLobeBins::phi();
    std::vector<double> bin_err(size_t(bt * bp), 0.0);
    double sum = 0.0;
    for (size_t k = 0; k < f.size(); ++k) {
        const double th = std::acos(wos[k][2]), ph = std::fabs(std::atan2(wos[k][1], wos[k][0]));
        const double d_omega = std::sin(th) * (M_PI / 2 / nt) * (2 * M_PI / np);
        REQUIRE(std::isfinite(f[k]));
        CHECK(f[k] >= 0.0);
        sum += f[k] * wos[k][2] * d_omega;
        const int row = std::min(int(th / (M_PI / 2) * bt), bt - 1), col = std::min(int(ph / M_PI * bp), bp - 1);
        bin_err[size_t(row * bp + col)] += err[k] * wos[k][2] * d_omega;
    }
    double sum_err = 0.0;
    for (double e : bin_err) sum_err += e * e;
    sum_err = std::sqrt(sum_err);
    AlbedoRequest req;
    req.model = m.id;
    req.samples = 1u << 18;
    req.cells.push_back(AlbedoCell{mu, 0.0, m.params});
    const WalkAlbedo v = walk_albedo(testing::engine(), req).values[0];
    INFO("integral of the lobe " << sum << " +- " << sum_err << ", R " << v.energy.value << " +- " << v.energy.error);
    // the midpoint grid's error on the closed-form first order is below 1e-3 at 64 x 64
    CHECK(std::fabs(sum - v.energy.value) <= sum_err + v.energy.error + 2e-3);
    CHECK(v.energy.value > 0.05);
}

TEST_CASE("sheen-volume: lut albedo sweeps roughness, lobe overlays sheen-ltc", "[sheen-volume][cli]") {
    const std::string dir = "/tmp/brdfbake-sheen-volume-" + std::to_string(::getpid());
    std::system(("mkdir -p " + dir).c_str());
    const auto lut = testing::run_cli("lut albedo --model sheen-volume --alpha-map roughness --size 4x3 --samples 16384 -o " +
                                      dir + "/a.csv");
    INFO(lut.out << lut.err);
    REQUIRE(lut.status == 0);
    const Table t = read_table(dir + "/a.csv");
    CHECK(t.width() == 4);
    for (double v : t.values[0]) {
        CHECK(std::isfinite(v));
        CHECK(v >= 0.0);
        CHECK(v <= 1.0);
    }
    const auto lobe = testing::run_cli("lobe --model sheen-volume:roughness=0.5 --model sheen-ltc:roughness=0.5 --theta-i 45 "
                                       "--resolution 37 -o " + dir + "/l.svg --data " + dir + "/l.csv");
    INFO(lobe.out << lobe.err);
    CHECK(lobe.status == 0);
    const std::string csv = testing::slurp(dir + "/l.csv");
    CHECK(csv.find("f_error") != std::string::npos);
    CHECK(csv.find("sheen-ltc") != std::string::npos);
    CHECK(csv.find("nan") == std::string::npos);
    std::system(("rm -rf " + dir).c_str());
}

// The masking-only Smith form (shadowing=masking: G2 = G1(wo), the masking term of Heitz 2014
// alone) and Blender Cycles' generalized-Schlick estimator (lut gen-schlick --estimator cycles):
// the spec key, the sample weights against the textbook form in long double, the albedo on every
// path against independent Boost.Math quadrature (benchmarks/reference), the estimator's tables at
// Cycles' grid points, and bad input.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "brdfbake/brdf/beckmann.h"
#include "brdfbake/brdf/ggx.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "models/params.h"
#include "reference/gen_schlick_reference.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

bb_vec3 v3(ref::Dir d) { return bb_v3(double(d.x), double(d.y), double(d.z)); }

/// The masking-only lobe's albedo at F = 1 (Heitz 2014's masking term, no shadowing), from the
/// reference D and G1 of either distribution: integral of G1(wo) D / (4 mu_o wi.z) wi.z dwi.
double masking_albedo(bool beckmann, double mu, double alpha) {
    return ref::albedo_halfvector(
        [&](ref::Dir wo, ref::Dir wi) -> ref::ld {
            const ref::Dir wh = ref::normalize(ref::Dir{wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
            const ref::ld g1 = beckmann ? ref::beckmann_g1(wo, alpha, alpha) : ref::ggx_g1(wo, alpha, alpha);
            const ref::ld d = beckmann ? ref::beckmann_d(wh, alpha, alpha) : ref::ggx_d(wh, alpha, alpha);
            return g1 * d / (4 * wo.z * wi.z);
        },
        mu, 0, 1e-9, ref::no_breaks);
}

}  // namespace

TEST_CASE("shadowing=masking: the spec key and its refusals", "[masking][quick]") {
    const ModelConfig g = resolve_model("ggx:alpha=0.25,shadowing=masking");
    CHECK(g.params[BB_GGX_SHADOWING] == BB_SHADOWING_MASKING);
    CHECK(g.canonical == "ggx:alpha=0.25,shadowing=masking");
    const ModelConfig b = resolve_model("beckmann:roughness=0.5,shadowing=masking");
    CHECK(b.params[BB_BECKMANN_SHADOWING] == BB_SHADOWING_MASKING);
    CHECK(resolve_model("ggx:alpha=0.25").params[BB_GGX_SHADOWING] == BB_SHADOWING_CORRELATED);
    CHECK(resolve_model("ggx:alpha=0.25,shadowing=separable").params[BB_GGX_SHADOWING] == BB_SHADOWING_SEPARABLE);
    // Cycles' transmission shadowing is a height-correlated form
    CHECK_THROWS_WITH(resolve_model("ggx:alpha=0.25,shadowing=masking,transmission_shadowing=cycles"),
                      Catch::Contains("needs shadowing=correlated, not shadowing=masking"));
    CHECK_THROWS(resolve_model("ggx:alpha=0.25,shadowing=mask"));
}

TEST_CASE("shadowing=masking: G2 = G1(wo), the sample weight F(wo.wh), on every form of the sampler",
          "[masking][quick]") {
    // bb_ggx_eval / bb_beckmann_eval against D G1(wo) F / (4 mu_o mu_i) from the reference D and
    // Lambda in long double; the importance sample's weight and the vector kernel's closed-form disk
    // weight are then F(wo.wh) (G2 / G1(wo) = 1) where wi is above the horizon, else 0.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    bb_params cond{};
    cond.v[BB_FRESNEL_ETA] = 0.2;
    cond.v[BB_FRESNEL_K] = 3.0;
    int compared = 0;
    for (const double ax : {1e-3, 0.3, 1.0})
        for (const double ay : {ax, 0.7})
            for (const double mu : {1e-3, 0.4, 1.0})
                for (const int fkind : {BB_FRESNEL_NONE, BB_FRESNEL_CONDUCTOR}) {
                    bb_params p{};
                    p.v[BB_SMITH_ALPHA_X] = ax;
                    p.v[BB_SMITH_ALPHA_Y] = ay;
                    p.v[BB_SMITH_SHADOWING] = BB_SHADOWING_MASKING;
                    const ref::Dir wo_ref = ref::dir_mu(mu, 0.3);
                    const bb_vec3 wo = v3(wo_ref);
                    const bb_ggx_disk_cell cell = bb_ggx_disk_cell_make(p, wo, 0);
                    for (int k = 0; k < 64; ++k) {
                        const double u1 = u(rng), u2 = u(rng);
                        // evaluation, both distributions, at a direction above the horizon
                        const ref::Dir wi_ref = ref::dir_mu(0.02 + 0.98 * u1, 6.2 * u2);
                        const ref::Dir wh = ref::normalize(ref::Dir{wo_ref.x + wi_ref.x, wo_ref.y + wi_ref.y, wo_ref.z + wi_ref.z});
                        const double f = bb_fresnel_eval(fkind, cond, double(ref::dot(wo_ref, wh)));
                        const double ggx = double(ref::ggx_d(wh, ax, ay) * ref::ggx_g1(wo_ref, ax, ay)) * f /
                                           (4 * double(wo_ref.z * wi_ref.z));
                        const double beck = double(ref::beckmann_d(wh, ax, ay) * ref::beckmann_g1(wo_ref, ax, ay)) * f /
                                            (4 * double(wo_ref.z * wi_ref.z));
                        INFO("ax " << ax << " ay " << ay << " mu " << mu << " F " << fkind);
                        CHECK(bb_ggx_eval(p, fkind, cond, wo, v3(wi_ref)) == Approx(ggx).epsilon(1e-9).margin(1e-12));
                        CHECK(bb_beckmann_eval(p, fkind, cond, wo, v3(wi_ref)) == Approx(beck).epsilon(1e-9).margin(1e-12));
                        // the samplers
                        const bb_vec2 d = bb_disk_polar(u1, u2);
                        const bb_vec3 m = bb_ggx_sample_vndf_disk(wo, ax, ay, d);
                        const ref::Dir mr = ref::normalize(ref::Dir{m.x, m.y, m.z});
                        const ref::Dir wi = ref::reflect(wo_ref, mr);
                        if (std::fabs(double(wi.z)) < 1e-9) continue;  // the horizon: either side
                        const double expect = wi.z > 0 ? bb_fresnel_eval(fkind, cond, double(ref::dot(wo_ref, mr))) : 0.0;
                        const double w = bb_ggx_disk_weight(cell, fkind, cond, d, std::sqrt(1.0 - d.x * d.x), 0);
                        CHECK(w == Approx(expect).epsilon(1e-11).margin(1e-13));
                        CHECK(bb_ggx_sample(p, fkind, cond, wo, u1, u2).weight == Approx(expect).epsilon(1e-11).margin(1e-13));
                        if (ax == ay) {
                            const bb_ggx_disk_cell iso = bb_ggx_disk_cell_make(p, wo, 1);
                            const double wi_iso = bb_ggx_disk_weight(iso, BB_FRESNEL_NONE, cond, d, std::sqrt(1.0 - d.x * d.x), 1);
                            CHECK((wi_iso == 0.0 || wi_iso == Approx(1.0).epsilon(1e-12)));
                        }
                        const bb_sample sb = bb_beckmann_sample(p, fkind, cond, wo, u1, u2);
                        const ref::Dir mb = ref::normalize(ref::Dir{wo_ref.x + sb.wi.x, wo_ref.y + sb.wi.y, wo_ref.z + sb.wi.z});
                        CHECK(sb.weight == Approx(sb.wi.z > 0 ? bb_fresnel_eval(fkind, cond, double(ref::dot(wo_ref, mb))) : 0.0)
                                               .epsilon(1e-9)
                                               .margin(1e-12));
                        ++compared;
                    }
                }
    CHECK(compared > 2000);
}

TEST_CASE("shadowing=masking: albedo on every method against independent quadrature", "[masking][device]") {
    // The albedo kind at F = 1 for ggx and beckmann with shadowing=masking: double to 1e-6 (auto
    // method), float by importance sampling (the vector kernel for ggx), and quadrature. It is at
    // least the height-correlated lobe's albedo (it ignores shadowing), within the error channels.
    for (const char* name : {"ggx", "beckmann"}) {
        const bool beckmann = std::string(name) == "beckmann";
        LutRequest r;
        r.kind = "albedo";
        r.model = std::string(name) + ":shadowing=masking";
        r.width = 4;
        r.height = 3;
        r.precision = Precision::Double;
        r.tolerance.tolerance = 1e-6;
        const Table t = compute_lut(testing::engine(), r);
        LutRequest rf = r;
        rf.precision = Precision::Float;
        rf.tolerance.tolerance = 0.0;
        rf.samples = 1u << 16;
        const Table tf = compute_lut(testing::engine(), rf);
        LutRequest rq = r;
        rq.method = Method::Quadrature;
        rq.tolerance.tolerance = 0.0;
        const Table tq = compute_lut(testing::engine(), rq);
        LutRequest rc = r;
        rc.model = std::string(name) + ":shadowing=correlated";
        const Table tc = compute_lut(testing::engine(), rc);
        for (size_t j = 0; j < 3; ++j)
            for (size_t i = 0; i < 4; ++i) {
                const size_t c = j * 4 + i;
                const double mu = t.x.parameter[i], alpha = t.y.parameter[j];
                const double want = masking_albedo(beckmann, mu, alpha);
                INFO(name << " mu " << mu << " alpha " << alpha << ": double " << t.values[0][c] << " +- " << t.error[c]
                          << ", float " << tf.values[0][c] << " +- " << tf.error[c] << ", quadrature " << tq.values[0][c]
                          << " +- " << tq.error[c] << ", reference " << want << ", correlated " << tc.values[0][c]);
                CHECK(std::fabs(t.values[0][c] - want) <= 1e-5);
                CHECK(std::fabs(tf.values[0][c] - want) <= tf.error[c]);
                CHECK(std::fabs(tq.values[0][c] - want) <= tq.error[c] + 1e-7);
                CHECK(t.values[0][c] + t.error[c] >= tc.values[0][c] - tc.error[c]);
                CHECK(t.values[0][c] <= 1.0 + t.error[c]);
            }
    }
}

TEST_CASE("gen-schlick --estimator cycles: Cycles' estimator at its grid points", "[masking][genschlick][device]") {
    // The cycles preset with --estimator cycles on a 4 x 4 x 4 edge grid (texels i/3 = 5i/15: points
    // of Cycles' 16-texel axes), in double to 1e-6: within 1e-5 of ref::ggx_cycles_vndf_s (the
    // mean of w over the visible normals, a reflection below the horizon counting 0), and its
    // gen-schlick-ior variant; the float kernel within its error estimate.
    for (bool ior : {false, true}) {
        LutRequest r;
        r.kind = ior ? "gen-schlick-ior" : "gen-schlick";
        r.estimator = "cycles";
        lut_preset("cycles").apply(r);
        CHECK(r.model == "ggx:shadowing=masking");
        r.width = r.height = r.depth = 4;
        r.precision = Precision::Double;
        r.tolerance.tolerance = 1e-6;
        const Table t = compute_lut(testing::engine(), r);
        REQUIRE(t.x.size == 4);
        CHECK(t.attributes.at("estimator").rfind("cycles", 0) == 0);
        CHECK(t.quantity.find("masking-only") != std::string::npos);
        LutRequest rf = r;
        rf.precision = Precision::Float;
        rf.tolerance.tolerance = 0.0;
        rf.samples = 1u << 16;
        const Table tf = compute_lut(testing::engine(), rf);
        // z = 1/3 (exponent 10, eta 1.25) over mu and roughness; z = 0.99 (exponent 5/99, eta 99.5),
        // whose w is steep at wo.wh -> 1 (slow for the reference), at two points
        const int points[][3] = {{1, 0, 1}, {1, 0, 3}, {1, 2, 1}, {1, 2, 3}, {1, 3, 1}, {1, 3, 3}, {3, 2, 1}, {3, 3, 3}};
        for (const auto& kji : points) {
            const int k = kji[0], j = kji[1], i = kji[2];  // z, mu (0: the floor 1e-4, 2/3, 1), roughness
            const size_t c = (size_t(k) * 4 + size_t(j)) * 4 + size_t(i);
            const double alpha = t.x.parameter[size_t(i)], mu = t.y.parameter[size_t(j)];
            const double p = t.z.parameter[size_t(k)];
            const double tol = k == 3 ? 1e-7 : 1e-8;  // absolute error density: about 5 tol
            const double want = ior ? ref::ggx_cycles_vndf_s_ior(mu, alpha, p, tol) : ref::ggx_cycles_vndf_s(mu, alpha, p, tol);
            INFO(r.kind << " mu " << mu << " alpha " << alpha << (ior ? " eta " : " exponent ") << p << ": double "
                        << t.values[0][c] << " +- " << t.error[c] << ", float " << tf.values[0][c] << " +- "
                        << tf.error[c] << ", reference " << want);
            CHECK(std::fabs(t.values[0][c] - want) <= 1e-5);
            CHECK(t.error[c] <= 1e-6);
            CHECK(std::fabs(tf.values[0][c] - want) <= tf.error[c] + 5 * tol);
        }
        if (!ior) {
            // roughness 1, mu 1, z 0.99 (exponent 5/99): Cycles' estimator gives about 0.445, the
            // exact ratio E_w / E 0.874 (measured with Cycles' estimator and brdfbake's ratio).
            const size_t c = (size_t(3) * 4 + 3) * 4 + 3;
            CHECK(t.values[0][c] == Approx(0.445).margin(5e-3));
        }
    }
}

TEST_CASE("the estimator of a request is checked by the library too, not only the command line", "[masking][quick]") {
    LutRequest r;
    r.kind = "albedo";
    r.model = "ggx";
    r.estimator = "cycles";
    CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("for the gen-schlick, gen-schlick-ior and sheen-ltc tables"));
    r.kind = "gen-schlick";
    r.estimator = "exact";
    CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("ratio or cycles"));
}

TEST_CASE("gen-schlick --estimator: the command line, its header and bad input", "[masking][genschlick][cli]") {
    const std::string out = "/tmp/brdfbake-masking-" + std::to_string(::getpid()) + ".h";
    const testing::CliResult run = testing::run_cli("lut gen-schlick --preset cycles --estimator cycles --size 2x2x2 "
                                                    "--samples 256 --no-preview -o " + out);
    INFO(run.err);
    REQUIRE(run.status == 0);
    std::ifstream in(out);
    std::stringstream text;
    text << in.rdbuf();
    CHECK(text.str().find("shadowing=masking") != std::string::npos);
    CHECK(text.str().find("masking-only") != std::string::npos);
    std::remove(out.c_str());
    for (const char* args :
         {"gen-schlick --model ggx --estimator cycles --size 4x4x4",                  // not the masking-only lobe
          "gen-schlick --preset cycles --model ggx --estimator cycles --size 4x4x4",  // ... over the preset's
          "gen-schlick --model ggx --estimator exact --size 4x4x4",                   // no such estimator
          "albedo --model ggx:shadowing=masking --estimator cycles --size 4x4",       // not a gen-schlick table
          "gen-schlick-ior --model ggx:shadowing=mask --size 4x4x4",                  // no such form
          "albedo --model ggx:shadowing=masking,transmission_shadowing=cycles --size 4x4",
          "dielectric --model ggx:shadowing=masking --size 4x4x2",                     // T needs shadowing
          "dielectric-eavg --model ggx:shadowing=masking --size 4x1x2"}) {
        testing::check_refused(std::string("lut ") + args + " -o ",
                               "/tmp/brdfbake-masking-bad-" + std::to_string(::getpid()) + ".exr");
    }
}

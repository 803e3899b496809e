// The rough dielectric's transmission shadowing key (transmission_shadowing=beta|cycles) and the
// dielectric-eavg table kind (issue 18).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "brdfbake/albedo.h"
#include "brdfbake/lut.h"
#include "brdfbake/table.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/spec.h"
#include "models/params.h"
#include "plot/plot.h"
#include "image_readers.h"
#include "reference/reference.h"
#include "scene/scene.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

TEST_CASE("ggx transmission_shadowing: spec, canonical spelling and refusals", "[dielectric][cycles][quick]") {
    CHECK(resolve_model("ggx:alpha=0.5").params[BB_GGX_SHADOWING] == BB_SHADOWING_CORRELATED);
    CHECK(resolve_model("ggx:alpha=0.5").params[BB_GGX_TRANSMISSION_SHADOWING] == BB_TRANSMISSION_SHADOWING_BETA);
    CHECK(resolve_model("ggx:alpha=0.5,transmission_shadowing=beta").canonical == "ggx:alpha=0.5,shadowing=correlated");
    const ModelConfig c = resolve_model("ggx:alpha=0.5,transmission_shadowing=cycles");
    CHECK(c.params[BB_GGX_SHADOWING] == BB_SHADOWING_CORRELATED);
    CHECK(c.params[BB_GGX_TRANSMISSION_SHADOWING] == BB_TRANSMISSION_SHADOWING_CYCLES);
    CHECK(c.canonical == "ggx:alpha=0.5,shadowing=correlated,transmission_shadowing=cycles");
    CHECK(resolve_model(c.canonical).params == c.params);
    // the reflection of a ggx lobe is height-correlated either way
    const bb_vec3 wo = bb_dir_from_mu_phi(0.3, 0.0), wi = bb_dir_from_mu_phi(0.7, 2.0);
    const bb_params none = {{0}};
    CHECK(bb_model_eval(c.id, to_bb_params(c.params), BB_FRESNEL_NONE, none, wo, wi) ==
          bb_model_eval(c.id, to_bb_params(resolve_model("ggx:alpha=0.5").params), BB_FRESNEL_NONE, none, wo, wi));
    for (const char* spec : {"ggx:shadowing=separable,transmission_shadowing=cycles", "ggx:transmission_shadowing=heitz",
                             "ggx:transmission_shadowing="}) {
        INFO(spec);
        testing::check_usage_error(testing::run_cli(std::string("lut dielectric --model '") + spec +
                                                    "' --size 2x2x1 -o /tmp/brdfbake-cycles-never.exr"));
    }
}

TEST_CASE("compute_dielectric refuses masking-only shadowing", "[dielectric][masking][device]") {
    // the transmitted lobe has no masking-only form (brdf/rough_dielectric.h)
    DielectricRequest req;
    req.cells = {{0.5, 0.3, 1.5}};
    req.shadowing = Shadowing::Masking;
    CHECK_THROWS_WITH(compute_dielectric(testing::engine(), req), Catch::Contains("no masking-only form"));
}

TEST_CASE("rough dielectric with Cycles' transmission shadowing against independent quadrature",
          "[dielectric][cycles][device]") {
    // R is the same under both forms; T follows 1/(1 + L_o + L_t), and differs from the Beta form
    // by more than the errors where the roughness is high and the light grazing.
    const std::vector<DielectricCell> cells = {{0.5, 0.3, 1.5}, {0.9, 0.6, 1 / 1.5}, {0.1, 1.0, 1.5}, {0.3, 0.8, 1.33}};
    DielectricRequest req;
    req.cells = cells;
    req.samples = 1 << 18;
    req.transmission_shadowing = TransmissionShadowing::Cycles;
    const DielectricResult cyc = compute_dielectric(testing::engine(), req);
    req.transmission_shadowing = TransmissionShadowing::Beta;
    const DielectricResult beta = compute_dielectric(testing::engine(), req);
    for (size_t k = 0; k < cells.size(); ++k) {
        double r, t;
        ref::rough_dielectric_rt(cells[k].mu, cells[k].alpha, cells[k].eta, ref::DielectricShadowing::Cycles, r, t);
        INFO("mu " << cells[k].mu << " alpha " << cells[k].alpha << " eta " << cells[k].eta << ": R "
                   << cyc.reflected[k].value << " vs " << r << ", T " << cyc.transmitted[k].value << " +- "
                   << cyc.transmitted[k].error << " vs " << t << " (Beta form " << beta.transmitted[k].value << ")");
        CHECK(std::fabs(cyc.reflected[k].value - r) <= cyc.reflected[k].error);
        CHECK(std::fabs(cyc.transmitted[k].value - t) <= cyc.transmitted[k].error);
        CHECK(cyc.reflected[k].value == Approx(beta.reflected[k].value).margin(1e-12));
        if (cells[k].alpha >= 0.8)
            CHECK(std::fabs(cyc.transmitted[k].value - beta.transmitted[k].value) >
                  10 * (cyc.transmitted[k].error + beta.transmitted[k].error));
    }
}

namespace {

LutRequest one_interface(const std::string& kind, const std::string& model, int width, double alpha, double eta) {
    LutRequest r;
    r.kind = kind;
    r.model = model;
    r.width = width;
    r.height = 1;
    r.depth = 1;
    r.alpha_lo = alpha - 0.05;  // one texel centred on alpha
    r.alpha_hi = alpha + 0.05;
    r.eta_lo = eta - 0.05;
    r.eta_hi = eta + 0.05;
    r.samples = 1u << 16;
    return r;
}

}  // namespace

TEST_CASE("dielectric-eavg equals 2 int (R + T) mu dmu of the dielectric table's own values", "[dielectric-eavg][device]") {
    // The dielectric table over mu (linear texel centres, one alpha, one eta) integrated by the
    // midpoint rule at 128 texels; the rule's own error is bounded by its change from 64 texels,
    // the table's sampling error by its error channel weighted as the rule weights it (R + T: twice
    // the channel). Both interfaces' sides and both transmission shadowing forms.
    for (const char* model : {"ggx", "ggx:transmission_shadowing=cycles"})
        for (const auto& ae : {std::pair<double, double>{0.5, 1.5}, {0.1, 1.33}}) {
            const Table eavg =
                compute_lut(testing::engine(), one_interface("dielectric-eavg", model, 1, ae.first, ae.second));
            REQUIRE(eavg.channels == std::vector<std::string>{"Eavg", "Eavg_inside"});
            REQUIRE(eavg.x.parameter.size() == 1);
            CHECK(eavg.x.parameter[0] == Approx(ae.first));
            CHECK(eavg.z.parameter[0] == Approx(ae.second));
            double m[2][2] = {}, err[2] = {};  // [side][64 or 128 texels]
            for (int w : {64, 128}) {
                const Table d = compute_lut(testing::engine(), one_interface("dielectric", model, w, ae.first, ae.second));
                for (int side = 0; side < 2; ++side)
                    for (int i = 0; i < w; ++i) {
                        const double mu = d.x.parameter[size_t(i)];
                        const double rt = d.values[size_t(2 * side)][size_t(i)] + d.values[size_t(2 * side + 1)][size_t(i)];
                        m[side][w == 128] += 2 * rt * mu / w;
                        if (w == 128) err[side] += 2 * 2 * d.error[size_t(i)] * mu / w;
                    }
            }
            for (int side = 0; side < 2; ++side) {
                const double got = eavg.values[size_t(side)][0], rule = std::fabs(m[side][1] - m[side][0]);
                INFO(model << " alpha " << ae.first << " eta " << ae.second << (side ? " inside" : " outside") << ": Eavg "
                           << got << " +- " << eavg.error[0] << ", midpoint rule " << m[side][1] << " +- " << err[side]
                           << " (rule " << rule << ")");
                CHECK(std::fabs(got - m[side][1]) <= eavg.error[0] + err[side] + rule);
                CHECK(eavg.error[0] + err[side] + rule < 0.01);  // the comparison has teeth
            }
        }
}

TEST_CASE("dielectric-eavg: bad requests give one line and exit status 2", "[dielectric-eavg][cli]") {
    for (const char* args : {"--model beckmann --size 4x1x2", "--model ggx --size 4x1x2 --method qmc",
                             "--model ggx --size 4x1x2 --eta-range 0.5,2", "--model ggx --fresnel schlick:f0=0.04 --size 4x1x2",
                             "--model ggx:transmission_shadowing=snell --size 4x1x2"}) {
        INFO(args);
        testing::check_usage_error(
            testing::run_cli(std::string("lut dielectric-eavg ") + args + " -o /tmp/brdfbake-deavg-never.exr"));
    }
}

TEST_CASE("glTF: a transmissive material also plans dielectric-eavg, an opaque dielectric does not",
          "[dielectric-eavg][scene][quick]") {
    const std::string path = "/tmp/brdfbake-deavg-" + std::to_string(::getpid()) + ".gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "materials": [
  {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.4},
   "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.7}}},
  {"name": "plastic", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.6}}]})";
    const Plan plan = make_plan(load_gltf_scene(path));
    std::remove(path.c_str());
    const PlannedTable* e = nullptr;
    for (const auto& t : plan.tables)
        if (t.request.kind == "dielectric-eavg") e = &t;
    REQUIRE(e);
    CHECK(e->materials == std::vector<std::string>{"glass"});
    CHECK(e->alpha.lo == Approx(0.16));
    CHECK(e->eta->lo == Approx(1.7));
    CHECK(e->request.height == 1);
}

TEST_CASE("dielectric-eavg takes the grid conventions: edge texels hold the closed forms, eta maps", "[lut][device]") {
    LutRequest r = testing::lut_request("dielectric-eavg", "ggx", 3, 1, 2);
    r.samples = 1024;
    r.texels = Texels::Edge;  // alpha 0, 0.5, 1 and eta 1, 3
    const Table t = compute_lut(testing::engine(), r);
    REQUIRE(t.x.parameter.front() == 0.0);
    REQUIRE(t.z.parameter.front() == 1.0);
    // alpha = 0 (a smooth interface: R + T = 1 at every mu) and eta = 1 (no interface: T = 1)
    // average to exactly 1 on both sides; a rough interface at eta = 3 loses energy.
    for (size_t k = 0; k < 3; ++k) {
        CHECK(t.values[0][k] == 1.0);
        CHECK(t.values[1][k] == 1.0);
    }
    CHECK(t.values[0][3] == 1.0);
    CHECK(t.values[0][5] < 0.9);
    // The F0 coordinate of the eta axis, as every kind with one takes it.
    r.texels = Texels::Centre;
    r.eta_map = "f0";
    r.eta_lo = 1.2;
    r.eta_hi = 50.0;
    const Table f = compute_lut(testing::engine(), r);
    CHECK(f.z.name == "f0");
    const double f0_lo = std::pow(0.2 / 2.2, 2), f0_hi = std::pow(49.0 / 51.0, 2);
    CHECK(f.z.lo == Approx(f0_lo).epsilon(1e-12));
    CHECK(f.z.hi == Approx(f0_hi).epsilon(1e-12));
}

TEST_CASE("dielectric-eavg to a tolerance: auto (quadrature) meets it and agrees with importance sampling",
          "[dielectric-eavg][tolerance][device]") {
    LutRequest lr = testing::lut_request("dielectric-eavg", "ggx", 3, 1, 2);
    lr.eta_lo = 1.2;
    lr.eta_hi = 2.0;
    lr.alpha_lo = 0.05;
    lr.tolerance.tolerance = 1e-4;
    lr.tolerance.auto_method = true;
    lr.tolerance.max_samples = std::uint64_t(1) << 22;
    const Table q = compute_lut(testing::engine(), lr);
    LutRequest sampled = lr;
    sampled.tolerance = ToleranceRequest{};
    sampled.samples = 1 << 16;
    const Table s = compute_lut(testing::engine(), sampled);
    REQUIRE(q.error.size() == s.error.size());
    for (size_t k = 0; k < q.error.size(); ++k) {
        CHECK(q.error[k] <= 1e-4);
        for (int c = 0; c < 2; ++c) {
            INFO("texel " << k << " " << q.channels[c] << ": " << q.values[c][k] << " +- " << q.error[k] << " vs "
                          << s.values[c][k] << " +- " << s.error[k]);
            CHECK(std::fabs(q.values[c][k] - s.values[c][k]) <= q.error[k] + s.error[k]);
            CHECK(q.values[c][k] <= 1.0 + q.error[k]);  // energy conservation
        }
    }
}

TEST_CASE("the preview of a 1D table with an eta axis is one heatmap per channel over roughness and eta",
          "[dielectric-eavg][pictures][quick]") {
    // dielectric-eavg's layout: x = roughness, y of size 1, z = 6 slices of Cycles' z. Drawn as 6
    // single-row heatmaps per channel (12 panels) it would be 6 small panels wide; the preview is
    // the 2 channels side by side, each over (roughness, z).
    Table t;
    t.kind = "dielectric-eavg";
    t.x = make_axis("roughness", "alpha = r^2 (r = sqrt(alpha))", 0.0, 1.0, 8, Texels::Edge);
    t.x.parameter_name = "alpha";
    for (double r : t.x.coordinate) t.x.parameter.push_back(r * r);
    t.y = make_axis("-", "-", 0.0, 1.0, 1);
    t.y.parameter = {0.5};
    t.z = make_axis("cycles_z", "eta = (1 + w^2) / (1 - w^2)", 0.0, 0.9, 6, Texels::Edge);
    t.z.parameter_name = "eta";
    for (double w : t.z.coordinate) t.z.parameter.push_back((1 + w * w) / (1 - w * w));
    t.channels = {"Eavg", "Eavg_inside"};
    t.values.assign(2, {});
    for (int z = 0; z < 6; ++z)
        for (int x = 0; x < 8; ++x) {
            t.values[0].push_back(1.0 - 0.05 * x);
            t.values[1].push_back(1.0 - 0.05 * x - 0.02 * z);
            t.error.push_back(1e-6);
        }
    const std::string path = "/tmp/brdfbake-deavg-preview-" + std::to_string(::getpid()) + ".png";
    write_table_preview(t, path);
    const testing::Png png = testing::read_png8(path);
    const size_t colours = testing::png_colours(path);
    std::remove(path.c_str());
    CHECK(colours > 16);  // heatmaps of values that vary over roughness and eta, not blank panels
    // Two panels of the 2D layout (760 x 640 each) in one row, not 6 columns of small multiples.
    CHECK(png.width < 2 * 760 + 400);
    CHECK(png.height < 640 + 300);
    CHECK(png.width > png.height);
}

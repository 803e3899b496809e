// Lookup tables: axes, values against independent references, consistency between kinds, and
// the files (EXR round trip through the OpenEXR library, CSV, C header).
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <sstream>
#include <thread>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/ggx.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"
#include "integrate/refine.h"
#include "reference/reference.h"
#include "ggx_albedo_reference.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

LutRequest request(const std::string& kind, int w, int h, std::uint64_t samples = 1 << 16) {
    LutRequest r = testing::lut_request(kind, "ggx", w, h);
    r.samples = samples;
    return r;
}

double ref_albedo(double alpha, double mu, double tol = 1e-9) {
    return ref::albedo_halfvector([&](ref::Dir wo, ref::Dir wi) { return ref::ggx_f(wo, wi, alpha, alpha, true); },
                                  mu, 0.0, tol);
}

std::string tmp_path(const std::string& name) { return "/tmp/brdfbake-lut-" + std::to_string(::getpid()) + "-" + name; }

}  // namespace

TEST_CASE("the table-kind registry: every kind once, found by name and id, unknown names listed", "[lut][quick]") {
    const std::vector<std::string> expected = {"albedo", "eavg", "dfg", "dielectric", "conductor", "dfg-ms",
                                               "sheen-albedo", "dielectric-eavg", "gen-schlick", "gen-schlick-ior",
                                               "dfg-f82", "sheen-viewer", "ltc", "sheen-ltc", "thin-film"};
    REQUIRE(table_kinds().size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        const TableKind* k = table_kinds()[i];
        INFO(expected[i]);
        CHECK(k->name == expected[i]);
        CHECK(find_table_kind(expected[i]) == k);
        CHECK(&table_kind(k->id) == k);
        CHECK(!k->description.empty());
        CHECK(k->compute);
        CHECK(k->fresnel);
        CHECK(k->value_channels);
        CHECK(k->integrations);
        CHECK(k->kernel_programs);
        if (k->eta_axis || k->needs_conductor_fresnel) CHECK(!k->lobe_requirement.empty());
    }
    CHECK(find_table_kind("sheen") == nullptr);
    CHECK_THROWS_WITH(table_kind("sheen"),
                      "unknown table kind 'sheen'; known: albedo, eavg, dfg, dielectric, conductor, dfg-ms, "
                      "sheen-albedo, dielectric-eavg, gen-schlick, gen-schlick-ior, dfg-f82, sheen-viewer, ltc, sheen-ltc, thin-film");
}

TEST_CASE("refine driver: rounds over the cells above the tolerance only, best or latest estimate kept", "[lut][quick]") {
    // A made-up convergence: cell c has error 8^-round / (c + 1) in its first channel and half that
    // in its second, except cell 0, whose second round is worse than its first.
    const std::vector<RefineStep> steps = {{Method::Quadrature, 100}, {Method::Importance, 400}, {Method::Importance, 1600}};
    auto run = [&](bool keep_best, std::vector<std::vector<size_t>>& seen) {
        RefineOptions o;
        o.tolerance = 0.01;
        o.keep_best = keep_best;
        int round = 0;
        return refine_to_tolerance(4, steps, o, [&](const RefineStep& step, const std::vector<size_t>& cells) {
            seen.push_back(cells);
            RefineRound r;
            for (size_t c : cells) {
                AlbedoValue v;
                v.value = double(round * 10 + int(c));
                v.error = std::pow(8.0, -round) / double(c + 1);
                if (c == 0 && round == 1) v.error = 2.0;  // worse than round 0
                v.samples = step.samples;
                v.method = step.method;
                AlbedoValue t = v;
                t.error = v.error / 2;  // a second channel: the cell's error is the larger
                r.values.push_back({v, t});
            }
            ++round;
            return r;
        });
    };
    std::vector<std::vector<size_t>> seen_best, seen_latest;
    const RefineOutcome best = run(true, seen_best), latest = run(false, seen_latest);
    // Round 0: errors 1, 1/2, 1/3, 1/4 -> all go on; round 1: 2, 1/16, 1/24, 1/32 -> all go on;
    // round 2: 1/64 = 0.0156, 1/128, 1/192, 1/256 -> cells 1, 2, 3 meet 0.01.
    REQUIRE(seen_best.size() == 3);
    CHECK(seen_best[0] == std::vector<size_t>{0, 1, 2, 3});
    CHECK(seen_best[2] == std::vector<size_t>{0, 1, 2, 3});
    CHECK(best.rounds == 3);
    CHECK(best.missed == std::vector<size_t>{0});
    CHECK(best.met_by.at("importance (1600 points)") == 3);
    CHECK(best.spent[0] == 2100);
    CHECK(best.total_samples == 4 * 2100);
    CHECK(best.last_step_samples == 1600);
    // Cell 0 keeps its best estimate (round 2: error 1/64 < 1 of round 0 < 2 of round 1).
    CHECK(best.values[0][0].value == 20.0);
    CHECK(best.values[0].size() == 2);
    CHECK(latest.values[0][0].value == 20.0);
    CHECK(seen_latest == seen_best);
}

TEST_CASE("refine driver: a cell stops at the first round that meets the tolerance, keep_best keeps the smaller error",
          "[lut][quick]") {
    const std::vector<RefineStep> steps = {{Method::Importance, 16}, {Method::Importance, 64}, {Method::Importance, 256}};
    for (bool keep_best : {true, false}) {
        RefineOptions o;
        o.tolerance = 0.1;
        o.keep_best = keep_best;
        int round = 0;
        std::vector<size_t> sizes;
        // Cell 0 meets the tolerance at once; cell 1 gets worse in round 1 and never meets it.
        const RefineOutcome r = refine_to_tolerance(2, steps, o, [&](const RefineStep& step, const std::vector<size_t>& cells) {
            sizes.push_back(cells.size());
            RefineRound out;
            for (size_t c : cells) {
                AlbedoValue v;
                v.value = round;
                v.error = c == 0 ? 0.05 : (round == 1 ? 0.9 : 0.5);
                v.samples = step.samples;
                out.values.push_back({v});
            }
            ++round;
            return out;
        });
        INFO("keep_best " << keep_best);
        CHECK(sizes == std::vector<size_t>{2, 1, 1});
        CHECK(r.missed == std::vector<size_t>{1});
        CHECK(r.values[0][0].value == 0.0);
        CHECK(r.spent[0] == 16);
        CHECK(r.spent[1] == 16 + 64 + 256);
        // Rounds 0 and 2 both have error 0.5: keep_best keeps the first; latest takes round 2.
        CHECK(r.values[1][0].value == (keep_best ? 0.0 : 2.0));
        CHECK(r.met_by.at("importance (16 points)") == 1);
    }
}

TEST_CASE("each kind's computed table has the axes and channels the README documents", "[lut][device]") {
    // The README's table of kinds (section "`lut`"): channels, first axis, 1D or 2D, and whether the
    // kind has an eta (or cycles_z) axis. A kind of the registry missing here fails: document it.
    struct Documented {
        std::vector<std::string> channels;
        const char* x;
        bool one_dimensional, eta_axis;
    };
    const std::map<std::string, Documented> readme = {
        {"albedo", {{"E"}, "mu", false, false}},
        {"eavg", {{"Eavg"}, "alpha", true, false}},
        {"dfg", {{"A", "B"}, "mu", false, false}},
        {"dfg-ms", {{"B", "E"}, "mu", false, false}},
        {"dielectric", {{"R", "T", "R_inside", "T_inside"}, "mu", false, true}},
        {"conductor", {{"R", "G", "B"}, "mu", false, false}},  // metal:X without --wavelength
        {"dielectric-eavg", {{"Eavg", "Eavg_inside"}, "alpha", true, true}},
        {"sheen-albedo", {{"E"}, "mu", false, false}},
        {"gen-schlick", {{"s"}, "mu", false, true}},
        {"gen-schlick-ior", {{"s"}, "mu", false, true}},
        {"dfg-f82", {{"A", "B", "C"}, "mu", false, false}},
        {"sheen-viewer", {{"E"}, "mu", false, false}},
        {"ltc", {{"m00", "m02", "m11", "m20", "m22", "magnitude", "fresnel", "distance", "distance_error"}, "mu", false, false}},
        {"sheen-ltc", {{"a", "b", "R", "distance", "distance_error"}, "mu", false, false}},
        {"thin-film", {{"R", "G", "B"}, "mu", false, true}},  // a film without --wavelength: colour per slice
    };
    for (const TableKind* k : table_kinds()) {
        INFO(k->name);
        REQUIRE(readme.count(k->name) == 1);
        const Documented& doc = readme.at(k->name);
        LutRequest r = request(k->name, 3, doc.one_dimensional ? 1 : 2, 1024);
        r.depth = 2;
        if (!k->example_fresnel.empty()) r.fresnel = k->example_fresnel;
        if (k->required_model == "sheen") r.model = "sheen";  // the kinds of the sheen model only
        const Table t = compute_lut(testing::engine(), r);
        CHECK(t.kind == k->name);
        CHECK(t.channels == doc.channels);
        CHECK(t.values.size() == doc.channels.size());
        CHECK(t.height() == (doc.one_dimensional ? 1 : 2));
        CHECK(t.x.name == doc.x);
        CHECK(t.depth() == (doc.eta_axis ? 2 : 1));
        CHECK(t.error.size() == size_t(t.width() * t.height() * t.depth()));
    }
}

TEST_CASE("axes sit at texel centres and map as documented", "[lut][quick]") {
    const Axis a = make_axis("mu", "mu = u", 0.0, 1.0, 4);
    REQUIRE(a.coordinate.size() == 4);
    CHECK(a.coordinate[0] == Approx(0.125));
    CHECK(a.coordinate[3] == Approx(0.875));
    const Axis b = make_axis("alpha", "alpha = v", 0.2, 0.6, 2);
    CHECK(b.coordinate[0] == Approx(0.3));
    CHECK(b.coordinate[1] == Approx(0.5));
}

TEST_CASE("albedo table texels match independent quadrature, and the error channel bounds the error",
          "[lut][device]") {
    LutRequest r = request("albedo", 8, 8, 1 << 18);
    r.mu_map = "sqrt";
    r.alpha_map = "roughness";
    const Table t = compute_lut(testing::engine(), r);
    REQUIRE(t.channels == std::vector<std::string>{"E"});
    // Texel centres through the documented mappings: mu = u^2, alpha = r^2.
    CHECK(t.x.parameter[0] == Approx(std::pow(0.5 / 8, 2)));
    CHECK(t.y.parameter[7] == Approx(std::pow(7.5 / 8, 2)));
    for (int j : {1, 4, 7})
        for (int i : {0, 3, 7}) {
            const double expect = ref_albedo(t.y.parameter[j], t.x.parameter[i]);
            const size_t k = size_t(j) * 8 + i;
            INFO("alpha " << t.y.parameter[j] << " mu " << t.x.parameter[i] << " got " << t.values[0][k] << " +- "
                          << t.error[k] << " expected " << expect);
            CHECK(std::fabs(t.values[0][k] - expect) <= t.error[k]);
            CHECK(std::fabs(t.values[0][k] - expect) <= 1e-4);
        }
}

TEST_CASE("eavg agrees with integrating the reference albedo over mu", "[lut][device]") {
    LutRequest r = request("eavg", 4, 1, 1 << 16);
    r.alpha_lo = 0.2;
    r.alpha_hi = 1.0;
    const Table t = compute_lut(testing::engine(), r);
    for (int i : {0, 3}) {
        const double alpha = t.x.parameter[i];
        // E(mu) mu is smooth: one 61-point Gauss-Kronrod panel (Boost) is accurate to ~1e-8.
        double err = 0;
        const double expect = 2 * boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
                                      [&](double mu) { return ref_albedo(alpha, mu, 1e-8) * mu; }, 0.0, 1.0, 0, 0.0, &err);
        INFO("alpha " << alpha << " got " << t.values[0][i] << " +- " << t.error[i] << " expected " << expect);
        CHECK(std::fabs(t.values[0][i] - expect) <= t.error[i]);
    }
}

TEST_CASE("eavg meets the tolerance it records where E(mu) bends sharply (small alpha)", "[lut][device]") {
    // Before, the mu rule's |G32 - G16| was never refined: --tolerance 1e-7 recorded 1e-7 and
    // delivered 3.07e-6 at alpha = 0.00625.
    LutRequest r = request("eavg", 4, 1, 1 << 16);
    r.alpha_lo = 0.0;
    r.alpha_hi = 0.05;
    r.precision = Precision::Double;
    r.tolerance.tolerance = 1e-7;
    const Table t = compute_lut(testing::engine(), r);
    for (int i = 0; i < 4; ++i) CHECK(t.error[size_t(i)] <= 1e-7);
    for (int i : {0, 3}) {
        const double alpha = t.x.parameter[size_t(i)];
        // Composite Gauss-Legendre (Boost) over mu on panels that shrink geometrically toward the
        // grazing layer, of the fast GGX reference; the 20-node rule checks the 30-node one.
        const double edges[] = {0.0, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0};
        auto eavg = [&](auto rule) {
            double sum = 0;
            for (size_t k = 0; k + 1 < std::size(edges); ++k)
                sum += rule.integrate([&](double mu) { return testing::ggx_albedo_reference<30>(alpha, mu, 1e-10) * mu; },
                                      edges[k], edges[k + 1]);
            return 2 * sum;
        };
        const double expect = eavg(boost::math::quadrature::gauss<double, 30>());
        REQUIRE(std::fabs(expect - eavg(boost::math::quadrature::gauss<double, 20>())) <= 1e-9);
        INFO("alpha " << alpha << " got " << t.values[0][size_t(i)] << " +- " << t.error[size_t(i)] << " expected "
                      << expect);
        CHECK(std::fabs(t.values[0][size_t(i)] - expect) <= t.error[size_t(i)]);
    }
}

TEST_CASE("dfg terms with Schlick F reproduce the directly integrated Fresnel albedo", "[lut][device]") {
    const Table t = compute_lut(testing::engine(), request("dfg", 4, 3));
    REQUIRE(t.channels == std::vector<std::string>{"A", "B"});
    const double f0 = 0.04;
    const ModelConfig m = resolve_model("ggx:alpha=0.5");
    for (int j = 0; j < 3; ++j) {
        AlbedoRequest req;
        req.model = m.id;
        req.fresnel = resolve_fresnel("schlick:f0=0.04");
        ParamBlock p = m.params;
        p[BB_GGX_ALPHA_X] = p[BB_GGX_ALPHA_Y] = t.y.parameter[j];
        req.cells = cells_for(t.x.parameter, 0.0, p);
        req.samples = 1 << 16;
        const AlbedoResult direct = compute_albedo(testing::engine(), req);
        for (int i = 0; i < 4; ++i) {
            const size_t k = size_t(j) * 4 + i;
            const double split = f0 * t.values[0][k] + t.values[1][k];
            INFO("texel " << i << "," << j);
            CHECK(std::fabs(split - direct.values[i].value) <= t.error[k] + direct.values[i].error);
            CHECK(t.values[0][k] >= 0.0);
            CHECK(t.values[1][k] >= 0.0);
        }
    }
    // The multiple-scattering layout holds B and E = A + B.
    const Table ms = compute_lut(testing::engine(), request("dfg-ms", 4, 3));
    REQUIRE(ms.channels == std::vector<std::string>{"B", "E"});
    for (size_t k = 0; k < 12; ++k) CHECK(ms.values[1][k] == Approx(t.values[0][k] + t.values[1][k]).margin(1e-6));
}

TEST_CASE("EXR files round-trip through the OpenEXR library with their description", "[lut][device]") {
    const Table t = compute_lut(testing::engine(), request("albedo", 6, 5, 1 << 12));
    for (bool half : {false, true}) {
        const std::string path = tmp_path(half ? "half.exr" : "float.exr");
        write_table(t, path, half);
        Imf::InputFile file(path.c_str());
        const Imf::Header& h = file.header();
        const Imath::Box2i dw = h.dataWindow();
        REQUIRE(dw.max.x - dw.min.x + 1 == 6);
        REQUIRE(dw.max.y - dw.min.y + 1 == 5);
        REQUIRE(h.channels().findChannel("E") != nullptr);
        REQUIRE(h.channels().findChannel("error") != nullptr);
        CHECK(h.channels().findChannel("E")->type == (half ? Imf::HALF : Imf::FLOAT));
        auto attr = [&](const char* name) {
            const auto* a = h.findTypedAttribute<Imf::StringAttribute>((std::string("brdfbake:") + name).c_str());
            REQUIRE(a != nullptr);
            return a->value();
        };
        CHECK(attr("kind") == "albedo");
        CHECK(attr("model") == "ggx:shadowing=correlated");
        CHECK(attr("x_axis") == "mu");
        CHECK(attr("y_axis") == "alpha");
        CHECK(attr("x_size") == "6");
        CHECK(attr("samples") == "4096");
        CHECK(attr("precision") == "float");
        CHECK(!attr("texel_convention").empty());
        CHECK(std::stod(attr("max_error")) == Approx(t.max_error()).epsilon(1e-6));
        std::vector<float> e(30), err(30);
        Imf::FrameBuffer fb;
        fb.insert("E", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(e.data()), sizeof(float), 6 * sizeof(float)));
        fb.insert("error", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(err.data()), sizeof(float), 6 * sizeof(float)));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        const double tol = half ? 1e-3 : 1e-7;  // half has an 11-bit significand
        for (size_t k = 0; k < 30; ++k) {
            CHECK(e[k] == Approx(t.values[0][k]).epsilon(tol));
            CHECK(err[k] == Approx(t.error[k]).epsilon(tol));
        }
        std::remove(path.c_str());
    }
}

TEST_CASE("CSV and C header tables carry every texel", "[lut][device]") {
    const Table t = compute_lut(testing::engine(), request("albedo", 3, 2, 1 << 10));
    const std::string csv = table_csv(t);
    CHECK(csv.find("mu,alpha,E,error\n") != std::string::npos);
    const std::string body = csv.substr(csv.find("mu,alpha,E,error\n") + 17);
    CHECK(testing::count_lines(body) == 6);
    const std::string h = table_header(t, "brdfbake_test");
    CHECK(h.find("static const float brdfbake_test_E[6]") != std::string::npos);
    CHECK(h.find("static const float brdfbake_test_error[6]") != std::string::npos);
}

TEST_CASE("non-finite tables are refused, not written", "[lut][quick]") {
    Table t;
    t.kind = "albedo";
    t.x = make_axis("mu", "mu = u", 0, 1, 2);
    t.x.parameter = {0.25, 0.75};
    t.y = make_axis("alpha", "alpha = v", 0, 1, 1);
    t.y.parameter = {0.5};
    t.channels = {"E"};
    t.values = {{0.5, std::nan("")}};
    t.error = {0.0, 0.0};
    const std::string path = tmp_path("nan.exr");
    CHECK_THROWS_WITH(write_table(t, path), Catch::Contains("non-finite"));
    CHECK(::access(path.c_str(), F_OK) != 0);
}

TEST_CASE("lut command: bad input exits 2 and writes nothing", "[lut][cli]") {
    const std::string path = tmp_path("bad.exr");
    const char* cases[] = {
        "lut albedo --model ggx:alpha=0.5 -o ",   // alpha is swept, not given
        "lut frobnicate --model ggx -o ",         // unknown kind
        "lut albedo --model lambert -o ",         // nothing to sweep
        "lut albedo --model ggx --size 0x4 -o ",  // empty table
        "lut albedo --model ggx --size 4xq -o ",  // not a size
        "lut dfg --model ggx --fresnel schlick:f0=0.04 -o ",
        "lut albedo --model ggx --alpha-range 1,0.5 -o ",
    };
    for (const char* c : cases) {
        INFO(c);
        const auto r = testing::run_cli(std::string(c) + path);
        CHECK(r.status == 2);
        CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(::access(path.c_str(), F_OK) != 0);
    }
    const auto r = testing::run_cli("lut albedo --model ggx -o " + tmp_path("table.txt"));
    CHECK(r.status == 2);
    CHECK(r.err.find(".exr, .csv, .h, .hpp, .png, .npy") != std::string::npos);
}

// ------------------------------------------------------------------------------------------------
// Issue 6, done-when: `brdfbake lut albedo --model ggx --size 32x32 -o ggx_E.exr` writes a table
// whose every texel is within 1e-4 of independent high-precision values and whose error channel
// bounds the actual error. The whole command runs through the executable; the file is read back
// with the OpenEXR library; all 1024 texels are compared.

using testing::ggx_albedo_reference;
using testing::parallel_for;

TEST_CASE("issue 6: every texel of `lut albedo --model ggx --size 32x32` is within 1e-4 of quadrature and "
          "within its error channel",
          "[lut][cli][device]") {
    const auto t_start = std::chrono::steady_clock::now();
    char dir_template[] = "/tmp/brdfbake-issue6-XXXXXX";
    REQUIRE(::mkdtemp(dir_template) != nullptr);
    const std::string dir = dir_template;
    const std::string path = dir + "/ggx_E.exr";

    // The command of the issue, through the executable.
    const auto run = testing::run_cli("lut albedo --model ggx --size 32x32 -o " + path);
    INFO("stderr: " << run.err);
    REQUIRE(run.status == 0);
    const double t_cli = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

    constexpr int n = 32;
    std::vector<float> e(n * n), err(n * n);
    std::string method;
    {
        Imf::InputFile file(path.c_str());
        const Imf::Header& h = file.header();
        const Imath::Box2i dw = h.dataWindow();
        REQUIRE(dw.max.x - dw.min.x + 1 == n);
        REQUIRE(dw.max.y - dw.min.y + 1 == n);
        REQUIRE(h.channels().findChannel("E") != nullptr);
        REQUIRE(h.channels().findChannel("error") != nullptr);
        REQUIRE(h.channels().findChannel("E")->type == Imf::FLOAT);
        auto attr = [&](const char* name) -> std::string {
            const auto* a = h.findTypedAttribute<Imf::StringAttribute>((std::string("brdfbake:") + name).c_str());
            return a ? a->value() : std::string("(missing)");
        };
        // What the header says is what the reference computes: x = mu = u, y = alpha = v, both over
        // [0, 1] at texel centres, height-correlated GGX without Fresnel, no texel at the alpha floor.
        CHECK(attr("kind") == "albedo");
        CHECK(attr("model") == "ggx:shadowing=correlated");
        CHECK(attr("fresnel") == "none");
        CHECK(attr("x_axis") == "mu");
        CHECK(attr("x_mapping") == "mu = u");
        CHECK(attr("x_range") == "0 1");
        CHECK(attr("y_axis") == "alpha");
        CHECK(attr("y_mapping") == "alpha = v");
        CHECK(attr("y_range") == "0 1");
        CHECK(attr("x_size") == "32");
        CHECK(attr("y_size") == "32");
        CHECK(attr("alpha_floor") == "(missing)");
        method = attr("method") + ", " + attr("samples") + " samples, " + attr("precision");
        Imf::FrameBuffer fb;
        // Texel (i, j) = (mu index, alpha index) at e[j * n + i], relative to the data window.
        char* base_e = reinterpret_cast<char*>(e.data()) - (size_t(dw.min.y) * n + dw.min.x) * sizeof(float);
        char* base_err = reinterpret_cast<char*>(err.data()) - (size_t(dw.min.y) * n + dw.min.x) * sizeof(float);
        fb.insert("E", Imf::Slice(Imf::FLOAT, base_e, sizeof(float), n * sizeof(float)));
        fb.insert("error", Imf::Slice(Imf::FLOAT, base_err, sizeof(float), n * sizeof(float)));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
    }
    std::filesystem::remove_all(dir);

    // Independent references at the texel centres, (i + 0.5) / 32 on both axes.
    const auto t_ref = std::chrono::steady_clock::now();
    auto mu_of = [](size_t k) { return (double(k % n) + 0.5) / n; };
    auto alpha_of = [](size_t k) { return (double(k / n) + 0.5) / n; };
    std::vector<double> expect(n * n), coarse(n * n);
    parallel_for(n * n, [&](size_t k) {
        expect[k] = ggx_albedo_reference<30>(alpha_of(k), mu_of(k), 1e-9);
        coarse[k] = ggx_albedo_reference<20>(alpha_of(k), mu_of(k), 1e-8);
    });
    // The reference's own accuracy: two settings agree everywhere, and the fast quadrature agrees
    // with the adaptive Gauss-Kronrod one of reference.h at the corners and the centre.
    double ref_spread = 0;
    for (size_t k = 0; k < expect.size(); ++k) ref_spread = std::max(ref_spread, std::fabs(expect[k] - coarse[k]));
    CHECK(ref_spread < 1e-8);
    const size_t spots[] = {0, n - 1, n * (n - 1), n * n - 1, n * (n / 2) + n / 2};
    std::vector<double> spot(std::size(spots));
    parallel_for(spot.size(), [&](size_t s) { spot[s] = ref_albedo(alpha_of(spots[s]), mu_of(spots[s]), 1e-9); });
    for (size_t s = 0; s < spot.size(); ++s) {
        INFO("reference cross-check at mu " << mu_of(spots[s]) << " alpha " << alpha_of(spots[s]));
        CHECK(std::fabs(spot[s] - expect[spots[s]]) < 1e-8);
    }
    const double t_reference = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_ref).count();

    // Every texel: |E - ref| <= 1e-4 and |E - ref| <= error.
    size_t over_1e4 = 0, over_estimate = 0, worst_abs = 0, worst_ratio = 0;
    auto diff = [&](size_t k) { return std::fabs(double(e[k]) - expect[k]); };
    auto ratio = [&](size_t k) { return err[k] > 0 ? diff(k) / double(err[k]) : diff(k) > 0 ? INFINITY : 0.0; };
    for (size_t k = 0; k < expect.size(); ++k) {
        over_1e4 += !(diff(k) <= 1e-4);
        over_estimate += !(diff(k) <= double(err[k]));
        if (!(diff(k) <= diff(worst_abs))) worst_abs = k;
        if (!(ratio(k) <= ratio(worst_ratio))) worst_ratio = k;
    }
    auto texel = [&](size_t k) {
        std::ostringstream s;
        s << "texel (" << k % n << ", " << k / n << ") mu " << mu_of(k) << " alpha " << alpha_of(k) << ": E "
          << std::setprecision(9) << e[k] << " reference " << expect[k] << std::scientific << std::setprecision(2)
          << " |diff| " << diff(k) << " error channel " << err[k] << std::defaultfloat << std::setprecision(3)
          << " ratio " << ratio(k);
        return s.str();
    };
    const double t_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    std::ostringstream summary;
    summary << std::setprecision(3) << "issue 6 table (" << method << "):\n  worst |E - ref| " << diff(worst_abs)
            << " at " << texel(worst_abs) << "\n  worst |E - ref| / error " << ratio(worst_ratio) << " at "
            << texel(worst_ratio) << "\n  reference self-consistency " << ref_spread << "; time: command " << t_cli
            << " s, references " << t_reference << " s, total " << t_total << " s\n";
    std::cout << summary.str();
    INFO(summary.str());
    INFO(over_1e4 << " texels off by more than 1e-4, " << over_estimate << " outside their error channel");
    CHECK(over_1e4 == 0);
    CHECK(over_estimate == 0);
}

// ------------------------------------------------------------------------------------------------
// Issue 17: grid conventions (texels at centres or edges, ranges and floors, alpha = 0 as the
// mirror limit, axis order and flips, eta mappings) for every kind, and the CSV axis columns.

TEST_CASE("edge texels sit on the range's ends, i/(N - 1) between, one edge texel is refused", "[lut][quick]") {
    const Axis a = make_axis("roughness", "alpha = r^2", 0.0, 1.0, 32, Texels::Edge);
    CHECK(a.coordinate.front() == 0.0);
    CHECK(a.coordinate.back() == 1.0);
    for (int i = 0; i < 32; ++i) CHECK(a.coordinate[size_t(i)] == Approx(i / 31.0).margin(1e-15));
    const Axis b = make_axis("mu", "mu = u", 0.25, 0.75, 3, Texels::Edge);
    CHECK(b.coordinate == std::vector<double>{0.25, 0.5, 0.75});
    CHECK_THROWS_WITH(make_axis("mu", "mu = u", 0.0, 1.0, 1, Texels::Edge), Catch::Contains("at least 2 texels"));
    CHECK(parse_texels("centre") == Texels::Centre);
    CHECK(parse_texels("edge") == Texels::Edge);
    CHECK_THROWS_WITH(parse_texels("middle"), Catch::Contains("--texels must be centre or edge"));
}

TEST_CASE("arrange_axes: a permutation and flips move every value with its texel", "[lut][quick]") {
    Table t;
    t.kind = "dielectric";
    t.x = make_axis("mu", "mu = u", 0, 1, 3);
    t.y = make_axis("alpha", "alpha = v", 0, 1, 2);
    t.z = make_axis("eta", "eta = w", 1, 2, 4);
    for (Axis* a : {&t.x, &t.y, &t.z}) a->parameter = a->coordinate;
    t.channels = {"R"};
    t.values.assign(1, {});
    // The value of texel (i, j, l) encodes its indices.
    for (int l = 0; l < 4; ++l)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 3; ++i) {
                t.values[0].push_back(100 * l + 10 * j + i);
                t.error.push_back(0.001 * (100 * l + 10 * j + i));
            }
    Table u = t;
    arrange_axes(u, {"eta", "mu", "alpha"}, {"mu"});
    REQUIRE(u.x.name == "eta");
    REQUIRE(u.y.name == "mu");
    REQUIRE(u.z.name == "alpha");
    CHECK(u.width() == 4);
    CHECK(u.height() == 3);
    CHECK(u.depth() == 2);
    CHECK(u.y.lo == 1.0);  // flipped: texel 0 holds the upper end
    CHECK(u.y.hi == 0.0);
    CHECK(u.y.coordinate.front() == t.x.coordinate.back());
    for (int j = 0; j < 2; ++j)          // new z = alpha
        for (int i = 0; i < 3; ++i)      // new y = flipped mu
            for (int l = 0; l < 4; ++l) {  // new x = eta
                const size_t k = (size_t(j) * 3 + i) * 4 + l;
                CHECK(u.values[0][k] == 100 * l + 10 * j + (2 - i));
                CHECK(u.error[k] == Approx(0.001 * (100 * l + 10 * j + (2 - i))));
            }
    Table same = t;
    arrange_axes(same, {}, {});
    CHECK(same.values == t.values);
    CHECK_THROWS_WITH(arrange_axes(same, {"mu", "alpha"}, {}), Catch::Contains("has 3 axes"));
    CHECK_THROWS_WITH(arrange_axes(same, {}, {"roughness"}), Catch::Contains("no axis 'roughness'"));
    CHECK_THROWS_WITH(arrange_axes(same, {"mu", "mu", "eta"}, {}), Catch::Contains("named twice"));
}

TEST_CASE("CSV: the column named after an axis holds its coordinate, the derived parameter its own column",
          "[lut][quick]") {
    Table t;
    t.kind = "albedo";
    t.x = make_axis("mu", "mu = u", 0, 1, 2);
    t.x.parameter_name = "mu";
    t.x.parameter = t.x.coordinate;
    t.y = make_axis("roughness", "alpha = r^2", 0, 1, 2);
    t.y.parameter_name = "alpha";
    for (double r : t.y.coordinate) t.y.parameter.push_back(r * r);
    t.channels = {"E"};
    t.values = {{0.9, 0.8, 0.7, 0.6}};
    t.error = {1e-4, 1e-4, 1e-4, 1e-4};
    const std::string csv = table_csv(t);
    const std::string body = csv.substr(csv.find("mu,roughness,alpha,E,error\n"));
    // Coordinates in the shortest text that reads back as them; a float table's values and errors to 9 digits.
    CHECK(body == "mu,roughness,alpha,E,error\n"
                  "0.25,0.25,0.0625,0.9,0.0001\n"
                  "0.75,0.25,0.0625,0.8,0.0001\n"
                  "0.25,0.75,0.5625,0.7,0.0001\n"
                  "0.75,0.75,0.5625,0.6,0.0001\n");
}

TEST_CASE("issue 17: `lut albedo --model ggx --size 2x2 --alpha-map roughness -o t.csv` writes roughness 0.25, "
          "0.75 under roughness and alpha 0.0625, 0.5625 under alpha",
          "[lut][cli][device]") {
    const std::string path = tmp_path("issue17.csv");
    const auto run = testing::run_cli("lut albedo --model ggx --size 2x2 --alpha-map roughness --samples 1024 --no-preview -o " + path);
    INFO(run.err);
    REQUIRE(run.status == 0);
    const std::string csv = testing::slurp(path);
    std::remove(path.c_str());
    const size_t head = csv.find("mu,roughness,alpha,E,error\n");
    REQUIRE(head != std::string::npos);
    std::istringstream rows(csv.substr(head + 27));
    const double want_r[] = {0.25, 0.25, 0.75, 0.75}, want_a[] = {0.0625, 0.0625, 0.5625, 0.5625};
    for (int k = 0; k < 4; ++k) {
        std::string line;
        REQUIRE(std::getline(rows, line));
        double mu, rough, alpha;
        char c;
        std::istringstream l(line);
        l >> mu >> c >> rough >> c >> alpha;
        CHECK(rough == want_r[k]);
        CHECK(alpha == want_a[k]);
    }
}

TEST_CASE("every kind takes the grid conventions: edge texels, a flipped and reordered roughness axis",
          "[lut][device]") {
    for (const TableKind* k : table_kinds()) {
        LutRequest r = request(k->name, 3, k->one_dimensional ? 1 : 2, 1024);
        r.depth = 2;
        if (!k->example_fresnel.empty()) r.fresnel = k->example_fresnel;
        if (k->required_model == "sheen") r.model = "sheen";  // the kinds of the sheen model only
        r.texels = Texels::Edge;
        r.alpha_map = "roughness";
        r.alpha_lo = 0.2;
        r.alpha_hi = 0.8;
        r.mu_lo = 0.5;
        r.flip = {"roughness"};
        // Each kind names its own axes (mu, roughness, then its z axis: the generalized-Schlick
        // kinds' is cycles_z); roughness first reorders them.
        if (!k->one_dimensional) {
            r.axes = table_axis_names(*k, r);
            REQUIRE(r.axes.size() >= 2);
            std::swap(r.axes[0], r.axes[1]);
        }
        INFO(k->name);
        const Table t = compute_lut(testing::engine(), r);
        const Axis& rough = t.x;
        REQUIRE(rough.name == "roughness");
        CHECK(rough.texels == Texels::Edge);
        CHECK(rough.coordinate.front() == 0.8);  // flipped: texel 0 at the upper end
        CHECK(rough.coordinate.back() == 0.2);
        CHECK(rough.parameter.front() == Approx(0.64));
        if (!k->one_dimensional) {
            CHECK(t.y.name == "mu");
            CHECK(t.y.coordinate.front() == 0.5);
            CHECK(t.y.coordinate.back() == 1.0);
            CHECK(t.attributes.at("axis_order").rfind("roughness, mu", 0) == 0);
        }
    }
}

TEST_CASE("alpha = 0 is the mirror limit: F(mu) for the albedo, the split-sum terms and the smooth dielectric",
          "[lut][device]") {
    LutRequest r = request("albedo", 3, 3, 1024);
    r.texels = Texels::Edge;
    r.fresnel = "schlick:f0=0.04";
    r.mu_lo = 0.1;
    const Table e = compute_lut(testing::engine(), r);
    REQUIRE(e.y.parameter.front() == 0.0);
    CHECK(e.attributes.count("alpha_zero") == 1);
    CHECK(e.attributes.count("alpha_floor") == 0);
    for (int i = 0; i < 3; ++i) {
        const double mu = e.x.parameter[size_t(i)];
        CHECK(e.values[0][size_t(i)] == Approx(0.04 + 0.96 * std::pow(1 - mu, 5)).margin(1e-15));
    }
    const Table s = compute_lut(testing::engine(), [] {
        LutRequest q = request("dfg", 3, 2, 1024);
        q.texels = Texels::Edge;
        q.mu_lo = 0.2;
        return q;
    }());
    for (int i = 0; i < 3; ++i) {
        const double mu = s.x.parameter[size_t(i)], b = std::pow(1 - mu, 5);
        CHECK(s.values[0][size_t(i)] == Approx(1 - b).margin(1e-15));
        CHECK(s.values[1][size_t(i)] == Approx(b).margin(1e-15));
    }
    LutRequest d = request("dielectric", 2, 2, 1024);
    d.texels = Texels::Edge;
    d.mu_lo = 0.3;
    d.depth = 2;
    d.eta_lo = 1.0;  // eta = 1: no interface
    d.eta_hi = 1.5;
    const Table g = compute_lut(testing::engine(), d);
    CHECK(g.attributes.count("eta_one") == 1);
    for (int l = 0; l < 2; ++l)
        for (int i = 0; i < 2; ++i) {
            const size_t k = size_t(l) * 4 + size_t(i);  // alpha index 0
            const double mu = g.x.parameter[size_t(i)], eta = g.z.parameter[size_t(l)];
            const double f = eta == 1.0 ? 0.0 : ref::fresnel_dielectric(mu, eta);
            const double f_inside = eta == 1.0 ? 0.0 : ref::fresnel_dielectric(mu, 1 / eta);
            CHECK(g.values[0][k] == Approx(f).margin(1e-12));
            CHECK(g.values[1][k] == Approx(1 - f).margin(1e-12));
            CHECK(g.values[2][k] == Approx(f_inside).margin(1e-12));
            CHECK(g.values[3][k] == Approx(1 - f_inside).margin(1e-12));
        }
}

TEST_CASE("eta mappings: F0 and Cycles' z coordinates map back to eta, up to 100 and below 1", "[lut][device]") {
    for (const char* map : {"f0", "cycles", "linear"}) {
        LutRequest r = request("dielectric", 2, 2, 256);
        r.eta_map = map;
        r.depth = 3;
        r.texels = Texels::Edge;
        r.alpha_lo = 0.3;
        r.eta_lo = std::string(map) == "linear" ? 0.5 : 1.2;
        r.eta_hi = 100.0;
        INFO(map);
        const Table t = compute_lut(testing::engine(), r);
        CHECK(t.z.parameter.front() == r.eta_lo);
        CHECK(t.z.parameter.back() == 100.0);
        for (size_t l = 0; l < 3; ++l) {
            const double w = t.z.coordinate[l], eta = t.z.parameter[l];
            const double f0 = ((eta - 1) / (eta + 1)) * ((eta - 1) / (eta + 1));
            if (std::string(map) == "f0") CHECK(w == Approx(f0).epsilon(1e-12));
            if (std::string(map) == "cycles") CHECK(w == Approx(std::pow(f0, 0.25)).epsilon(1e-12));
            if (std::string(map) == "linear") CHECK(w == eta);
        }
        CHECK(t.z.name == (std::string(map) == "f0" ? "f0" : std::string(map) == "cycles" ? "cycles_z" : "eta"));
    }
}

TEST_CASE("issue 17: bad grid options exit 2 with one line and write nothing", "[lut][cli]") {
    const std::string path = tmp_path("bad17.exr");
    const char* cases[] = {
        "lut albedo --model ggx --texels edge --size 1x4 -o ",      // one edge texel
        "lut eavg --model ggx --texels edge --size 1 -o ",          // one edge texel, 1D
        "lut albedo --model ggx --texels middle -o ",               // unknown convention
        "lut albedo --model ggx --mu-range 0.8,0.2 -o ",            // inverted
        "lut albedo --model ggx --mu-range 0,1.5 -o ",              // beyond 1
        "lut albedo --model ggx --mu-floor 0 -o ",                  // no floor
        "lut albedo --model ggx --alpha-range 0.5,0.5 -o ",         // empty
        "lut dielectric --model ggx --eta-range 0,2 -o ",           // eta <= 0
        "lut dielectric --model ggx --eta-range -1,2 -o ",          // eta <= 0
        "lut dielectric --model ggx --eta-range 2,1.5 -o ",         // inverted
        "lut dielectric --model ggx --eta-range 1.5,200 -o ",       // beyond 100
        "lut dielectric --model ggx --eta-map f0 --eta-range 0.5,2 -o ",  // f0 covers eta >= 1 only
        "lut dielectric --model ggx --eta-map z -o ",               // unknown mapping
        "lut albedo --model ggx --axes mu,eta -o ",                 // no eta axis
        "lut albedo --model ggx --axes mu -o ",                     // not every axis
        "lut albedo --model ggx --axes mu,mu -o ",                  // twice
        "lut albedo --model ggx --flip roughness -o ",              // the axis is alpha here
        "lut albedo --model ggx --preset nope -o ",                 // unknown preset
    };
    for (const char* c : cases) testing::check_refused(c, path);
}

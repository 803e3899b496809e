// Lookup tables: axes, values against independent references, consistency between kinds, and
// the files (EXR round trip through the OpenEXR library, CSV, C header).
#include <catch2/catch.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <unistd.h>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/ggx.h"
#include "brdfbake/lut.h"
#include "reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

LutRequest request(const std::string& kind, int w, int h, std::uint64_t samples = 1 << 16) {
    LutRequest r;
    r.kind = kind;
    r.model = "ggx";
    r.width = w;
    r.height = h;
    r.samples = samples;
    return r;
}

double ref_albedo(double alpha, double mu, double tol = 1e-9) {
    return ref::albedo_halfvector([&](ref::Dir wo, ref::Dir wi) { return ref::ggx_f(wo, wi, alpha, alpha, true); },
                                  mu, 0.0, tol);
}

std::string tmp_path(const std::string& name) { return "/tmp/brdfbake-lut-" + std::to_string(::getpid()) + "-" + name; }

}  // namespace

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
    CHECK(r.err.find(".exr, .csv or .h") != std::string::npos);
}

// The presets: each preset's file, read the way its engine reads it, against values derived from
// the engine's documented convention (the source files cited in host/tables/presets.cpp and the
// README) and independent Boost.Math quadrature (benchmarks/reference) — never against a copy of
// an engine's table.
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "brdfbake/lut.h"
#include "ggx_albedo_reference.h"
#include "reference/reference.h"
#include "image_readers.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

using testing::exr_channel;

namespace {

struct TempDir {
    std::string path;
    TempDir() {
        char t[] = "/tmp/brdfbake-presets-XXXXXX";
        REQUIRE(::mkdtemp(t) != nullptr);
        path = t;
    }
    ~TempDir() { std::filesystem::remove_all(path); }
};

/// A float channel of an EXR (row-major over the data window).
/// The RGBA pixels as a generic reader (and an engine's texture upload) sees them.
std::vector<Imf::Rgba> exr_rgba(const std::string& path, int& w, int& h) {
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i dw = file.dataWindow();
    w = dw.max.x - dw.min.x + 1;
    h = dw.max.y - dw.min.y + 1;
    std::vector<Imf::Rgba> px(size_t(w) * h);
    file.setFrameBuffer(px.data() - dw.min.x - size_t(dw.min.y) * w, 1, size_t(w));
    file.readPixels(dw.min.y, dw.max.y);
    return px;
}

/// 16-bit RGB(A) samples of a PNG, as libpng reads them, scaled to [0, 1].
std::vector<double> png_rgb(const std::string& path, int& w, int& h, int& channels) {
    const testing::Png p = testing::read_png(path);
    w = p.width;
    h = p.height;
    channels = p.channels;
    std::vector<double> v;
    for (unsigned s : p.samples) v.push_back(s / 65535.0);
    return v;
}

/// The split-sum terms of height-correlated GGX at (alpha, mu) from the references: E = A + B
/// (F = 1) by the fast half-vector quadrature, B = integral of f (1 - wo.wh)^5 cos by
/// ref::albedo_halfvector.
struct SplitSum {
    double a, b;
};
SplitSum split_sum_reference(double alpha, double mu) {
    const double e = testing::ggx_albedo_reference<30>(alpha, mu, 1e-9);
    const double b = ref::albedo_halfvector(
        [&](ref::Dir wo, ref::Dir wi) {
            const ref::Dir h = ref::normalize(ref::Dir{wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
            const ref::ld c = 1 - ref::dot(wo, h);
            return ref::ggx_f(wo, wi, alpha, alpha, true) * c * c * c * c * c;
        },
        mu, 0.0, 1e-8);
    return {e - b, b};
}

struct Probe {
    int x, y;
};

/// Runs `brdfbake ARGS -o DIR/NAME --no-preview`, which must succeed, and reads `channel` of
/// the EXR it wrote, which must be width x height texels.
std::vector<float> written_channel(const TempDir& dir, const std::string& args, const std::string& name,
                                   const char* channel, int width, int height) {
    const std::string path = dir.path + "/" + name;
    const auto run = testing::run_cli(args + " -o " + path + " --no-preview");
    INFO(run.err);
    REQUIRE(run.status == 0);
    int w = 0, h = 0;
    std::vector<float> v = exr_channel(path, channel, w, h);
    REQUIRE(w == width);
    REQUIRE(h == height);
    return v;
}

}  // namespace

TEST_CASE("preset cycles: every texel of ggx_E within its certified 5e-7 of Cycles' convention (edges, x = "
          "roughness, mu floored at 1e-4, alpha = r^2, E = 1 at r = 0), and within its error channel",
          "[presets][device]") {
    TempDir dir;
    const int w = 32, h = 32;
    const std::vector<float> e = written_channel(dir, "lut --preset cycles", "ggx_E.exr", "E", w, h);
    int ew = 0, eh = 0;
    const std::vector<float> err = exr_channel(dir.path + "/ggx_E.exr", "error", ew, eh);
    REQUIRE(err.size() == e.size());
    // Cycles (intern/cycles/app/cycles_precompute.cpp): texel (x, y) at rough = x/31, mu = y/31,
    // each clamped to [1e-4, 1]; alpha = rough^2. Rough 1e-4 is alpha 1e-8: the mirror, E = 1.
    std::vector<double> expect(size_t(w) * h);
    testing::parallel_for(expect.size(), [&](size_t k) {
        const int x = int(k % 32), y = int(k / 32);
        const double rough = x / 31.0, mu = std::max(y / 31.0, 1e-4);
        expect[k] = x == 0 ? 1.0 : testing::ggx_albedo_reference<20>(rough * rough, mu, 1e-9);
    });
    double worst = 0;
    size_t at = 0;
    for (size_t k = 0; k < expect.size(); ++k)
        if (std::fabs(e[k] - expect[k]) > worst) {
            worst = std::fabs(e[k] - expect[k]);
            at = k;
        }
    std::cout << "preset cycles ggx_E: worst |E - reference| " << worst << " at rough " << (at % 32) / 31.0 << ", mu "
              << (at / 32) / 31.0 << "\n";
    INFO("worst " << worst << " at texel (" << at % 32 << ", " << at / 32 << ")");
    CHECK(worst <= 5e-7);  // README: certified to 5e-7 (measured: 2.9e-7)
    // The error channel: every texel certified to 5e-7, and honest: each value within 3x its own
    // estimate of the reference (issue 37's criterion), plus the float file's rounding (half an
    // ulp below 1: 2^-25) and the reference's 1e-9. Measured: 1.5x beyond the rounding at worst
    // (texel (7, 21): 2.9e-7 off, estimate 1.7e-7).
    double worst_ratio = 0;
    for (size_t k = 0; k < e.size(); ++k) {
        INFO("texel (" << k % 32 << ", " << k / 32 << "): " << e[k] << " +- " << err[k] << " vs " << expect[k]);
        CHECK(err[k] <= 5e-7);
        const double off = std::fabs(e[k] - expect[k]);
        CHECK(off <= 3 * err[k] + std::ldexp(1.0, -25) + 1e-9);
        const double beyond_rounding = off - std::ldexp(1.0, -25) - 1e-9;
        if (beyond_rounding > 0) worst_ratio = std::max(worst_ratio, beyond_rounding / err[k]);
    }
    std::cout << "preset cycles ggx_E: worst (|E - reference| - rounding) / error estimate " << worst_ratio << "\n";
    // Cycles' own first column is computed at alpha = 1e-8, not 0. There the albedo is within
    // 2 Lambda(mu) of the mirror's 1: as alpha -> 0 the reflected direction is the mirror one, where
    // G2 / G1 = (1 + Lambda_o) / (1 + 2 Lambda_o) >= 1 - Lambda_o, and the visible normals sum to 1
    // (Heitz 2014, eq. 99 and the normalisation of D_wo). Lambda at the floor mu = 1e-4 (its
    // largest) from reference.h:
    const double lambda = double(ref::ggx_lambda(ref::Dir{std::sqrt(1 - 1e-8), 0, 1e-4}, 1e-8, 1e-8));
    INFO("Lambda(mu = 1e-4, alpha = 1e-8) = " << lambda);
    CHECK(2 * lambda < 1e-7);
}

TEST_CASE("preset cycles: ggx_Eavg within 2e-6 of 2 integral of E(mu) mu dmu at roughness i/31", "[presets][device]") {
    TempDir dir;
    const std::vector<float> eavg = written_channel(dir, "lut eavg --preset cycles", "ggx_Eavg.exr", "Eavg", 32, 1);
    std::vector<double> expect(32);
    testing::parallel_for(32, [&](size_t x) {
        const double alpha = (x / 31.0) * (x / 31.0);
        // Cycles: ggx_Eavg = mean over uniform mu of 2 mu E(mu). Adaptive Gauss-Kronrod (Boost).
        expect[x] = x == 0 ? 1.0
                           : 2 * boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
                                     [&](double mu) { return testing::ggx_albedo_reference<20>(alpha, mu, 1e-10) * mu; },
                                     0.0, 1.0, 8, 1e-10);
    });
    double worst = 0;
    for (size_t x = 0; x < 32; ++x) {
        INFO("roughness " << x / 31.0 << ": " << eavg[x] << " reference " << expect[x]);
        CHECK(std::fabs(eavg[x] - expect[x]) <= 2e-6);
        worst = std::max(worst, std::fabs(eavg[x] - expect[x]));
    }
    std::cout << "preset cycles ggx_Eavg: worst |Eavg - reference| " << worst << "\n";
}

TEST_CASE("presets three, gltf, unreal, filament: the texels an engine's shader reads hold its split-sum terms",
          "[presets][device]") {
    TempDir dir;
    struct Case {
        const char* preset;
        const char* extension;
        int w, h;             // of the file: x then y
        bool roughness_first; // the file's x is the roughness axis: --size is given as mu x roughness
        // The engine's read: which (roughness, mu) texel (x, y) holds, and which split-sum value
        // channel c of the file holds (A, B or E = A + B).
        double (*roughness)(int x, int y, int w, int h);
        double (*mu)(int x, int y, int w, int h);
        double (*channel)(const SplitSum& s, int c);
    };
    const Case cases[] = {
        // three.js DFGLUTData: texture(dfgLUT, vec2(roughness, dotNV)).rg = (A, B), centres.
        {"three", "exr", 8, 6, true, [](int x, int, int w, int) { return (x + 0.5) / w; },
         [](int, int y, int, int h) { return (y + 0.5) / h; }, [](const SplitSum& s, int c) { return c ? s.b : s.a; }},
        // glTF Sample Viewer: texture(u_GGXLUT, vec2(NdotV, roughness)).rg = (A, B).
        {"gltf", "png", 8, 6, false, [](int, int y, int, int h) { return (y + 0.5) / h; },
         [](int x, int, int w, int) { return (x + 0.5) / w; }, [](const SplitSum& s, int c) { return c ? s.b : s.a; }},
        // Unreal EnvBRDF: PreIntegratedGF at float2(NoV, Roughness), .x = A, .y = B.
        {"unreal", "png", 8, 4, false, [](int, int y, int, int h) { return (y + 0.5) / h; },
         [](int x, int, int w, int) { return (x + 0.5) / w; }, [](const SplitSum& s, int c) { return c ? s.b : s.a; }},
        // Filament DFG (multiscatter), in dfg.inc's GL order (cmgen.cpp iblLutDfg writes row y from
        // image row size - 1 - y): x = NoV, row 0 the smoothest, R = B, G = E; the centre of row y
        // is roughness (y + 0.5)/h.
        {"filament", "exr", 8, 6, false, [](int, int y, int, int h) { return (y + 0.5) / h; },
         [](int x, int, int w, int) { return (x + 0.5) / w; },
         [](const SplitSum& s, int c) { return c ? s.a + s.b : s.b; }},
    };
    for (const Case& c : cases) {
        INFO("preset " << c.preset);
        const std::string path = dir.path + "/" + c.preset + "." + c.extension;
        // --size is mu x roughness whatever the axis order (the kind's own axes).
        const std::string size = c.roughness_first ? std::to_string(c.h) + "x" + std::to_string(c.w)
                                                   : std::to_string(c.w) + "x" + std::to_string(c.h);
        const auto run = testing::run_cli(std::string("lut --preset ") + c.preset + " --size " + size +
                                          " --samples 262144 -o " + path + " --no-preview");
        INFO(run.err);
        REQUIRE(run.status == 0);
        int w = 0, h = 0, channels = 0;
        std::vector<double> rg;  // R, G per texel as the engine's upload sees them
        double precision;        // half a unit in the last place of the format, relative (half) or absolute (PNG)
        bool relative;
        if (std::string(c.extension) == "png") {
            const std::vector<double> v = png_rgb(path, w, h, channels);
            REQUIRE(channels == 3);
            for (size_t k = 0; k < v.size() / 3; ++k) {
                rg.push_back(v[3 * k]);
                rg.push_back(v[3 * k + 1]);
                CHECK(v[3 * k + 2] == 0.0);  // B = 0 in a two-channel table
            }
            precision = 0.5 / 65535;
            relative = false;
        } else {
            const std::vector<Imf::Rgba> px = exr_rgba(path, w, h);
            for (const Imf::Rgba& p : px) {
                rg.push_back(float(p.r));
                rg.push_back(float(p.g));
            }
            precision = std::ldexp(1.0, -11);
            relative = true;
        }
        REQUIRE(w == c.w);
        REQUIRE(h == c.h);
        // Texels away from the mirror corner (roughness index >= 1) and the grazing column.
        const Probe probes[] = {{1, 1}, {c.w - 1, 1}, {1, c.h - 1}, {c.w - 1, c.h - 1}, {c.w / 2, c.h / 2}};
        for (const Probe& p : probes) {
            const double rough = c.roughness(p.x, p.y, w, h), mu = c.mu(p.x, p.y, w, h);
            const SplitSum s = split_sum_reference(rough * rough, mu);
            for (int ch = 0; ch < 2; ++ch) {
                const double got = rg[2 * (size_t(p.y) * w + p.x) + ch], want = c.channel(s, ch);
                // The format's rounding plus the sampling noise of 2^18 samples (the error
                // channel of such a table is below 2e-4 on these texels).
                const double tol = (relative ? precision * std::fabs(want) : precision) + 3e-4;
                INFO("texel (" << p.x << ", " << p.y << ") roughness " << rough << " mu " << mu << " channel " << ch
                               << ": " << got << " expected " << want);
                CHECK(std::fabs(got - want) <= tol);
            }
        }
    }
}

TEST_CASE("presets: unknown names and kinds without a layout exit 2 with one line", "[presets][cli]") {
    const std::string path = "/tmp/brdfbake-presets-bad-" + std::to_string(::getpid()) + ".exr";
    for (const char* args : {"lut --preset frostbite -o ", "lut sheen-albedo --preset cycles -o ",
                             "lut albedo --preset gltf -o ", "lut -o "})
        testing::check_refused(args, path);
    CHECK(lut_presets().size() >= 5);
    CHECK_THROWS_WITH(lut_preset("nope"), Catch::Contains("known: gltf, filament, three, cycles, unreal"));
}

TEST_CASE("apply_preset: the preset's layout for the kind, each option given replacing its field", "[presets]") {
    // README "Drop-in tables": Cycles' ggx_Eavg is 32 texels at the edges of roughness [0, 1], double
    // precision to 5e-7; options given beside the preset override only their own fields.
    LutSettings given;
    given.preset = "cycles";
    given.kind = "eavg";
    given.size = std::vector<int>{8};
    const LutSetup eavg = apply_preset(given);
    CHECK(eavg.request.kind == "eavg");
    CHECK(eavg.request.width == 8);
    CHECK(eavg.request.height == 1);
    CHECK(eavg.request.texels == Texels::Edge);
    CHECK(eavg.request.alpha_map == "roughness");
    CHECK(eavg.request.precision == Precision::Double);
    CHECK(eavg.request.tolerance.tolerance == 5e-7);
    CHECK_FALSE(eavg.half);
    // The method options count as one: a sample count given drops the preset's tolerance.
    given.samples = 4096;
    const LutSetup fixed = apply_preset(given);
    CHECK(fixed.request.tolerance.tolerance == 0.0);
    CHECK(fixed.request.samples == 4096);
    CHECK(fixed.request.precision == Precision::Double);
    // Cycles' own estimator takes the masking-only lobe, as its precompute does.
    LutSettings estimator;
    estimator.preset = "cycles";
    estimator.kind = "gen-schlick";
    estimator.estimator = "cycles";
    CHECK(apply_preset(estimator).request.model == "ggx:shadowing=masking");
    estimator.estimator = "ratio";
    CHECK(apply_preset(estimator).request.model == "ggx:shadowing=correlated");
    // A half-float engine texture, unless --half says otherwise; the preset's first kind by default.
    LutSettings filament;
    filament.preset = "filament";
    CHECK(apply_preset(filament).half);
    CHECK(apply_preset(filament).request.kind == "dfg-ms");
    filament.half = false;
    CHECK_FALSE(apply_preset(filament).half);
    // Without a preset: LutRequest's defaults, kDefaultLutTexels on every axis of the kind.
    LutSettings plain;
    plain.kind = "dielectric";
    plain.model = "ggx";
    const LutRequest glass = apply_preset(plain).request;
    CHECK((glass.width == kDefaultLutTexels && glass.height == kDefaultLutTexels && glass.depth == kDefaultLutTexels));
    plain.kind = "eavg";
    CHECK(apply_preset(plain).request.height == 1);
    // The command line's messages.
    plain.preset = "gltf";
    CHECK_THROWS_WITH(apply_preset(plain), "preset 'gltf' has a layout for dfg, sheen-viewer tables, not eavg");
    LutSettings bare;
    bare.kind = "albedo";
    CHECK_THROWS_WITH(apply_preset(bare), "--model is required (or give --preset)");
    bare.model = "ggx";
    bare.estimator = "cycles";
    CHECK_THROWS_WITH(apply_preset(bare), "--estimator is for the gen-schlick, gen-schlick-ior and sheen-ltc tables, not albedo");
}

TEST_CASE("preset cycles gen-schlick-ior: the z = 0 slice (eta = 1, no interface) holds s = 0 in closed form",
          "[presets][gen-schlick]") {
    // At eta = 1 the dielectric Fresnel is 0 at every angle and F0 = ((eta - 1)/(eta + 1))^2 = 0,
    // so w = clamp((F - F0)/(1 - F0), 0, 1) = 0 and s = E_w / E = 0 (Cycles' table holds 0
    // there); both estimators. z = 1 (computed at 0.99, eta 99.5) reflects.
    TempDir dir;
    for (const char* estimator : {"ratio", "cycles"}) {
        INFO("--estimator " << estimator);
        const std::vector<float> s =
            written_channel(dir, std::string("lut gen-schlick-ior --preset cycles --estimator ") + estimator +
                                     " --size 3x3x2 --samples 4096",
                            std::string("ior-") + estimator + ".exr", "s", 3, 6);
        for (int i = 0; i < 9; ++i) CHECK(s[i] == 0.0f);        // z = 0: rows 0-2
        CHECK(*std::max_element(s.begin() + 9, s.end()) > 0.1f);  // z = 1: rows 3-5 (s = 0 only at mu = 1)
    }
}

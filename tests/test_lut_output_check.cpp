// `lut -o FILE` refuses a format that cannot hold the table before the compute: the table's shape
// (lut_table_shape: kind, channels, axes, model, no values) is what every format's check reads
// (check_table_format), and the same checks run again in write_table. The truth here is the
// writer itself: for every table kind (and the ltc packings, the dielectric walk, colour
// channels, arranged axes) and every format, the check before the compute refuses exactly where
// writing the computed table refuses, with the same line.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"
#include "checks.h"
#include "models/merl_file.h"
#include "support.h"

using namespace brdfbake;

namespace {

std::string scratch(const std::string& name) {
    return "/tmp/brdfbake-outcheck-" + std::to_string(::getpid()) + "-" + name;
}

/// The refusal's text, or "" where `f` throws nothing.
template <typename F>
std::string refusal(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// The extensions check_table_path lists in its refusal (".exr, .csv, ... or .cs (Unity HDRP)").
std::vector<std::string> known_extensions() {
    const std::string text = refusal([] { check_table_path("/tmp/x.unknown-format"); });
    std::vector<std::string> out;
    const std::regex ext(R"(\.([a-z]+)\b)");
    // The list without its notes in parentheses ("(three.js)" names no format of its own).
    const std::string list = std::regex_replace(text.substr(text.find(": use ") + 6), std::regex(R"(\([^)]*\))"), "");
    for (auto it = std::sregex_iterator(list.begin(), list.end(), ext); it != std::sregex_iterator(); ++it)
        out.push_back((*it)[1]);
    return out;
}

void check_same_axis(const Axis& shape, const Axis& table, bool own_range) {
    CHECK(shape.name == table.name);
    CHECK(shape.size == table.size);
    if (table.size > 1) CHECK(shape.texels == table.texels);
    if (!own_range && table.size > 1) {
        CHECK(shape.lo == table.lo);
        CHECK(shape.hi == table.hi);
    }
}

/// The requests compared: every kind at 3 x 2 (x 2), then what changes a kind's channels or axes.
std::vector<LutRequest> requests() {
    std::vector<LutRequest> out;
    for (const TableKind* k : table_kinds()) {
        LutRequest r = testing::lut_request(k->name, "ggx", 3, k->one_dimensional ? 1 : 2);
        r.depth = 2;
        r.samples = 1024;
        if (!k->example_fresnel.empty()) r.fresnel = k->example_fresnel;
        if (!k->required_model.empty()) r.model = k->required_model;
        out.push_back(r);
    }
    // The ltc packings on the engines' grid (x = roughness, y = sqrt(1 - mu), edge texels).
    for (const char* packing : {"three", "eevee", "unity-hdrp", "unity-hdrp-2021"}) {
        LutRequest r = testing::lut_request("ltc", "ggx", 3, 3);
        r.samples = 1024;
        r.packing = packing;
        r.mu_map = "sqrt-one-minus";
        r.alpha_map = "roughness";
        r.texels = Texels::Edge;
        out.push_back(r);
    }
    LutRequest walk = testing::lut_request("albedo", "ggx:scattering=multiple,eta=1.5", 2, 2);  // R, T, R_below, T_below
    walk.samples = 1024;
    out.push_back(walk);
    LutRequest colour = testing::lut_request("thin-film", "ggx", 2, 2);  // R, G, B without --wavelength
    colour.depth = 2;
    colour.samples = 1024;
    if (!table_kind("thin-film").example_fresnel.empty()) colour.fresnel = table_kind("thin-film").example_fresnel;
    out.push_back(colour);
    // A measured model per colour (E_r, E_g, E_b: three channels, which three.js refuses) and its Eavg.
    static const std::string merl = [] {
        const std::string path = scratch("lambert.binary");
        write_merl_file(path, [](const std::array<double, 3>&, const std::array<double, 3>&) {
            return std::array<double, 3>{0.2 / M_PI, 0.3 / M_PI, 0.4 / M_PI};
        });
        return path;
    }();
    for (const char* kind : {"albedo", "eavg"}) {
        LutRequest m = testing::lut_request(kind, "merl:file=" + merl + ",channel=rgb", 3, kind[0] == 'a' ? 2 : 1);
        m.samples = 1024;
        out.push_back(m);
    }
    LutRequest arranged = testing::lut_request("dielectric", "ggx", 3, 2);  // a 3D table turned to 2D slices of alpha
    arranged.depth = 2;
    arranged.samples = 1024;
    arranged.axes = {"eta", "mu", "alpha"};
    arranged.flip = {"mu"};
    out.push_back(arranged);
    return out;
}

}  // namespace

TEST_CASE("lut's output check before the compute: the shape is the computed table's, and every format refuses it "
          "exactly where writing the table refuses, with the same line",
          "[lut][formats][device]") {
    const std::vector<std::string> formats = known_extensions();
    REQUIRE(formats.size() == 12);  // .exr .csv .h .hpp .png .npy .js .inc .tables .cc .c .cs
    std::set<std::string> refused_somewhere;
    int refusals = 0;
    for (const LutRequest& r : requests()) {
        INFO(r.kind << " " << r.model << " packing '" << r.packing << "'");
        validate_lut(r);
        const Table shape = lut_table_shape(r);
        const Table t = compute_lut(testing::engine(), r);
        CHECK(shape.kind == t.kind);
        CHECK(shape.channels == t.channels);
        CHECK(shape.attributes.at("model") == t.attributes.at("model"));
        CHECK(shape.values.empty());
        const TableKind& kind = table_kind(r.kind);
        check_same_axis(shape.x, t.x, false);
        check_same_axis(shape.y, t.y, false);
        check_same_axis(shape.z, t.z, !kind.own_z_axis.empty());
        for (const std::string& ext : formats) {
            INFO("." << ext);
            const std::string path = scratch("table." + ext);
            const std::string before = refusal([&] { check_table_format(shape, path); });
            const std::string after = refusal([&] { write_table(t, path); });
            CHECK(before == after);
            if (!after.empty()) {
                ++refusals;
                refused_somewhere.insert(ext);
                CHECK(!std::filesystem::exists(path));
            }
            std::filesystem::remove(path);
            std::filesystem::remove(path + ".json");
        }
    }
    // The comparison is not empty: the formats that hold only some tables refuse some here.
    CHECK(refusals > 0);
    std::filesystem::remove(scratch("lambert.binary"));
    for (const char* ext : {"png", "js", "inc", "cc", "c", "cs"}) CHECK(refused_somewhere.count(ext) == 1);
}

TEST_CASE("lut -o refuses a format by the table's channels before the compute: one line, exit 2, under a second, "
          "nothing written",
          "[lut][formats][cli]") {
    struct Case {
        std::string args, file, says;
    };
    const std::vector<Case> cases = {
        // Before lut_table_shape the whole 64 x 64 fit came first: 11.6 s of CPU (amd-epyc-2c, load 8).
        {"lut ltc --preset three", "ltc.js", "a three.js half-float DataTexture has 1, 2 or 4 channels"},
        {"lut dfg-f82 --model ggx", "f82.js", "a three.js half-float DataTexture has 1, 2 or 4 channels"},
        {"lut dfg --model ggx --size 256", "dfg.cc", "an EEVEE .cc file holds Blender EEVEE's ltc_mat_ggx and ltc_mag_ggx"},
        {"lut ltc --model ggx", "ltc.png", "a PNG holds at most four channels"},
        {"lut sheen-ltc --model sheen", "sheen.inc", "Filament's dfg.inc holds 2 half floats per texel"},
    };
    for (const Case& c : cases) {
        INFO(c.args << " -o " << c.file);
        const std::string path = scratch(c.file);
        const auto t0 = std::chrono::steady_clock::now();
        const testing::CliResult res = testing::run_cli(c.args + " -o " + path);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        CHECK(res.status == 2);
        CHECK(testing::count_lines(res.err) == 1);
        CHECK(res.err.rfind("brdfbake: error: " + c.says, 0) == 0);
        CHECK(seconds < 1.0);
        CHECK(!std::filesystem::exists(path));
        CHECK(!std::filesystem::exists(path.substr(0, path.find_last_of('.')) + ".png"));  // no preview either
    }
}

TEST_CASE("lut ltc refuses a Lambert base (diffuse=KD) in one line before the compute, diffuse=0 is the lobe alone",
          "[lut][ltc][cli]") {
    const std::string path = scratch("diffuse.exr");
    const auto t0 = std::chrono::steady_clock::now();
    const testing::CliResult res = testing::run_cli("lut ltc --model ggx:diffuse=0.3 -o " + path);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(res.status == 2);
    CHECK(testing::count_lines(res.err) == 1);
    CHECK(res.err.rfind("brdfbake: error: the ltc table fits one lobe; 'ggx:shadowing=correlated,diffuse=0.3' adds a "
                        "Lambert base kd/pi",
                        0) == 0);
    CHECK(seconds < 1.0);
    CHECK(!std::filesystem::exists(path));
    for (const char* model : {"beckmann:diffuse=1", "ggx:diffuse=0.05"}) {
        LutRequest r = testing::lut_request("ltc", model, 4, 4);
        CHECK_THROWS_WITH(validate_lut(r), Catch::Contains("adds a Lambert base kd/pi, whose LTC is exact (M = I"));
    }
    CHECK_NOTHROW(validate_lut(testing::lut_request("ltc", "ggx:diffuse=0", 4, 4)));
    CHECK_NOTHROW(validate_lut(testing::lut_request("albedo", "ggx:diffuse=0.3", 4, 4)));  // other kinds take it
}

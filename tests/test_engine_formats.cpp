// The engines' own files, read the way the engines read them: three.js's DFGLUTData.js imported
// by node (with stand-ins for three.js's DataTexture and constants) and its half floats decoded
// in JavaScript; Filament's dfg.inc and Cycles' shader.tables compiled by g++ where the engines
// include them; 16-bit PNG tables read back by read_table and `brdfbake show`, and walked chunk
// by chunk for colour-space chunks that make a browser convert the samples.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;
using testing::run_cli;
using testing::run_shell;
using testing::slurp;

namespace {

std::string scratch(const std::string& name) {
    const std::string dir = "/tmp/brdfbake-engine-formats-" + std::to_string(::getpid());
    std::system(("mkdir -p " + dir).c_str());
    return dir + "/" + name;
}

void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// IEEE 754 binary16 to double, written from the standard (not through Imath).
double from_half(unsigned h) {
    const int sign = h >> 15 ? -1 : 1, exponent = int(h >> 10) & 31, mantissa = int(h & 1023);
    if (exponent == 0) return sign * std::ldexp(mantissa, -24);
    if (exponent == 31) return mantissa ? NAN : sign * INFINITY;
    return sign * std::ldexp(1024 + mantissa, exponent - 25);
}

/// Half a unit in the last place of binary16 at v: the most rounding to half moves v.
double half_rounding(double v) { return std::ldexp(1.0, std::ilogb(std::max(std::fabs(v), 6.2e-5)) - 11); }

/// A 2-channel table over roughness (x) and mu (y), texel centres, whose values name their texel:
/// A = roughness / 2 + 0.25, B = mu^2 / 3 (not a binary fraction: half floats round it).
Table coordinate_table(int w, int h) {
    Table t;
    t.kind = "dfg";
    t.quantity = "test values naming their texel";
    t.x = testing::identity_axis("roughness", "alpha = r^2", 0, 1, w);
    t.y = testing::identity_axis("mu", "mu = u", 0, 1, h);
    t.channels = {"A", "B"};
    t.values.assign(2, std::vector<double>(size_t(w) * h));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            t.values[0][size_t(j) * w + i] = t.x.coordinate[size_t(i)] / 2 + 0.25;
            t.values[1][size_t(j) * w + i] = t.y.coordinate[size_t(j)] * t.y.coordinate[size_t(j)] / 3;
        }
    t.error.assign(size_t(w) * h, 1e-6);
    t.attributes["precision"] = "float";
    return t;
}

/// Imports DFGLUTData.js from a three.js source tree's place (src/renderers/shaders) whose
/// textures/DataTexture.js and constants.js are stand-ins, and returns what getDFGLUT() built,
/// its half floats decoded in JavaScript.
nlohmann::json import_with_node(const std::string& module) {
    const std::string root = scratch("three");
    REQUIRE(run_shell("mkdir -p " + root + "/src/renderers/shaders " + root + "/src/textures").status == 0);
    put(root + "/package.json", "{\"type\": \"module\"}\n");
    put(root + "/src/textures/DataTexture.js",
        "export class DataTexture { constructor(data, width, height, format, type) {"
        " this.image = { data, width, height }; this.format = format; this.type = type; } }\n");
    put(root + "/src/constants.js",
        "export const RedFormat = 'RedFormat', RGFormat = 'RGFormat', RGBAFormat = 'RGBAFormat', "
        "HalfFloatType = 'HalfFloatType', LinearFilter = 'LinearFilter', ClampToEdgeWrapping = 'ClampToEdgeWrapping';\n");
    REQUIRE(run_shell("cp " + module + " " + root + "/src/renderers/shaders/DFGLUTData.js").status == 0);
    put(root + "/read.mjs",
        "import { getDFGLUT } from './src/renderers/shaders/DFGLUTData.js';\n"
        "const lut = getDFGLUT();\n"
        "const half = (h) => { const s = h >> 15 ? -1 : 1, e = (h >> 10) & 31, m = h & 1023;\n"
        "  return e === 0 ? s * m * 2 ** -24 : e === 31 ? (m ? NaN : s * Infinity) : s * (1 + m / 1024) * 2 ** (e - 15); };\n"
        "console.log(JSON.stringify({ width: lut.image.width, height: lut.image.height, format: lut.format,\n"
        "  type: lut.type, isUint16: lut.image.data instanceof Uint16Array, same: getDFGLUT() === lut,\n"
        "  mag: lut.magFilter, wrapS: lut.wrapS, values: Array.from(lut.image.data, half) }));\n");
    const auto r = run_shell("node " + root + "/read.mjs");
    INFO(r.err);
    REQUIRE(r.status == 0);
    return nlohmann::json::parse(r.out);
}

/// The 0xHHHH numbers of a file outside its // comments.
std::vector<unsigned> hex_numbers(const std::string& text) {
    std::vector<unsigned> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("//", 0) == 0) continue;
        static const std::regex hex("0x([0-9a-f]{4}),");
        for (std::sregex_iterator it(line.begin(), line.end(), hex), end; it != end; ++it)
            out.push_back(unsigned(std::stoul((*it)[1].str(), nullptr, 16)));
    }
    return out;
}

/// The PNG chunk types of a file, walked from its signature (length, type, data, CRC).
std::vector<std::string> png_chunks(const std::string& bytes) {
    std::vector<std::string> types;
    size_t p = 8;
    while (p + 8 <= bytes.size()) {
        const uint32_t length = uint32_t(uint8_t(bytes[p])) << 24 | uint32_t(uint8_t(bytes[p + 1])) << 16 |
                                uint32_t(uint8_t(bytes[p + 2])) << 8 | uint8_t(bytes[p + 3]);
        types.push_back(bytes.substr(p + 4, 4));
        p += 12 + length;
    }
    return types;
}

}  // namespace

TEST_CASE("DFGLUTData.js: node imports it as three.js does, half floats within rounding, x = roughness, y = NoV, "
          "row 0 at NoV 0",
          "[formats][engine][quick]") {
    const Table t = coordinate_table(16, 16);
    const std::string path = scratch("DFGLUTData.js");
    write_table(t, path);
    const nlohmann::json lut = import_with_node(path);
    CHECK(lut["width"] == 16);
    CHECK(lut["height"] == 16);
    CHECK(lut["format"] == "RGFormat");
    CHECK(lut["type"] == "HalfFloatType");
    CHECK(lut["isUint16"] == true);
    CHECK(lut["same"] == true);
    CHECK(lut["mag"] == "LinearFilter");
    CHECK(lut["wrapS"] == "ClampToEdgeWrapping");
    const auto& v = lut["values"];
    REQUIRE(v.size() == 512);
    // three.js samples texture2D(dfgLUT, vec2(roughness, dotNV)): texel (i, j) at
    // DATA[(j * 16 + i) * 2], roughness (i + 0.5)/16, NoV (j + 0.5)/16.
    double worst = 0;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            const double r = (i + 0.5) / 16, mu = (j + 0.5) / 16;
            const double a = v[size_t(j * 16 + i) * 2], b = v[size_t(j * 16 + i) * 2 + 1];
            CHECK(std::fabs(a - (r / 2 + 0.25)) <= half_rounding(r / 2 + 0.25));
            CHECK(std::fabs(b - mu * mu / 3) <= half_rounding(mu * mu / 3));
            worst = std::max(worst, std::fabs(b - t.values[1][size_t(j) * 16 + i]));
        }
    CHECK(worst > 0);  // half floats: some rounding shows, so the values were not passed as text

    SECTION("a table flipped along y is written in texture order") {
        Table f = t;
        arrange_axes(f, {}, {"mu"});
        write_table(f, path);
        const nlohmann::json again = import_with_node(path);
        CHECK(again["values"] == v);
    }
    SECTION("three channels or a 3D table are refused, nothing written") {
        Table three = t;
        three.channels.push_back("C");
        three.values.push_back(three.values[0]);
        const std::string other = scratch("three.js");
        CHECK_THROWS_WITH(write_table(three, other), Catch::Contains("1, 2 or 4 channels"));
        CHECK(slurp(other).empty());
    }
}

TEST_CASE("dfg.inc compiles where Filament includes it (const uint16_t DFG_LUT[] = {...}) cmgen's layout, "
          "GL order from a table stored roughest first",
          "[formats][engine][quick]") {
    // Filament's preset layout: x = NoV, y = perceptual roughness from the roughest (flipped).
    Table t = coordinate_table(4, 8);  // x = roughness (4), y = mu (8), then swapped
    arrange_axes(t, {"mu", "roughness"}, {"roughness"});
    REQUIRE(t.x.name == "mu");
    REQUIRE(t.y.lo == 1.0);
    const std::string dir = scratch("filament");
    REQUIRE(run_shell("mkdir -p " + dir).status == 0);
    write_table(t, dir + "/dfg.inc");
    put(dir + "/DFG.cpp",
        "#include <cstdint>\nconst uint16_t DFG_LUT[] = {\n#include \"dfg.inc\"\n};\n"
        "static_assert(sizeof(DFG_LUT) == 8 * 4 * 2 * sizeof(uint16_t), \"DFG_LUT_SIZE doesn't match\");\n");
    const auto r = run_shell("g++ -std=c++17 -Wall -Werror -fsyntax-only " + dir + "/DFG.cpp");
    INFO(r.err);
    CHECK(r.status == 0);
    const std::string text = slurp(dir + "/dfg.inc");
    const std::vector<unsigned> h = hex_numbers(text);
    REQUIRE(h.size() == 64);
    // Row j of the file at roughness (j + 0.5)/4 (t = 0 first), x = NoV; 4 texels per line.
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 8; ++i) {
            const double r = (j + 0.5) / 4, mu = (i + 0.5) / 8;
            CHECK(std::fabs(from_half(h[size_t(j * 8 + i) * 2]) - (r / 2 + 0.25)) <= half_rounding(r / 2 + 0.25));
            CHECK(std::fabs(from_half(h[size_t(j * 8 + i) * 2 + 1]) - mu * mu / 3) <= half_rounding(mu * mu / 3));
        }
    CHECK(std::regex_search(text, std::regex("\n    (0x[0-9a-f]{4}, ){8}\n")));
}

TEST_CASE("shader.tables syntax compiles where Cycles includes it (CCL_NAMESPACE_BEGIN inside), values to a float",
          "[formats][engine][quick]") {
    Table t = coordinate_table(4, 3);
    t.z = make_axis("cycles_z", "eta = (1 + z^2)/(1 - z^2)", 0, 1, 2, Texels::Edge);
    t.z.parameter = t.z.coordinate;
    for (auto& v : t.values) {
        const std::vector<double> slice = v;
        v.insert(v.end(), slice.begin(), slice.end());
        v.back() = 1.0;  // a whole number must still be a floating literal
    }
    t.error.resize(t.values[0].size(), 1e-6);
    const std::string dir = scratch("cycles");
    REQUIRE(run_shell("mkdir -p " + dir + "/scene").status == 0);
    write_table(t, dir + "/scene/ggx_test.tables");
    put(dir + "/shader.cpp",
        "#define CCL_NAMESPACE_BEGIN namespace ccl {\n#define CCL_NAMESPACE_END }\n"
        "#include \"scene/ggx_test.tables\"\n"
        "static_assert(sizeof(ccl::table_ggx_test_A) == 24 * sizeof(float), \"size\");\n"
        "static_assert(sizeof(ccl::table_ggx_test_B) == 24 * sizeof(float), \"size\");\n"
        "float first() { return ccl::table_ggx_test_A[0] + ccl::table_ggx_test_B[23]; }\n");
    const auto r = run_shell("g++ -std=c++17 -Wall -Wno-unused-variable -Werror -fsyntax-only -I" + dir + " " + dir +
                             "/shader.cpp");
    INFO(r.err);
    CHECK(r.status == 0);
    const std::string text = slurp(dir + "/scene/ggx_test.tables");
    const auto open = text.find("table_ggx_test_B[24] = {");
    REQUIRE(open != std::string::npos);
    std::istringstream in(text.substr(text.find('{', open) + 1, text.find("};", open) - text.find('{', open) - 1));
    std::vector<float> b;
    for (std::string item; std::getline(in, item, ',');) b.push_back(std::strtof(item.c_str(), nullptr));
    REQUIRE(b.size() == 24);
    for (size_t k = 0; k < 24; ++k) CHECK(b[k] == float(t.values[1][k]));
    CHECK(text.find(" 1.0f\n};") != std::string::npos);
}

TEST_CASE("PNG tables: no colour-space chunk, and read_table and `brdfbake show` read them back exactly",
          "[formats][engine][quick]") {
    Table t = coordinate_table(16, 8);
    t.values[1][5] = 211.0 / 65535;  // the texels a browser's gamma conversion changed
    t.values[1][6] = 5.0 / 65535;
    const std::string path = scratch("t.png");
    write_table(t, path);
    const std::vector<std::string> chunks = png_chunks(slurp(path));
    REQUIRE(chunks.size() >= 3);
    CHECK(chunks.front() == "IHDR");
    CHECK(chunks.back() == "IEND");
    for (const char* converting : {"gAMA", "sRGB", "iCCP", "cHRM"})
        CHECK(std::find(chunks.begin(), chunks.end(), converting) == chunks.end());

    const Table back = read_table(path);
    CHECK(back.kind == t.kind);
    CHECK(back.channels == t.channels);
    CHECK(back.x.name == "roughness");
    CHECK(back.y.size == 8);
    REQUIRE(back.values.size() == 2);
    for (size_t c = 0; c < 2; ++c)
        for (size_t k = 0; k < t.values[c].size(); ++k)
            CHECK(back.values[c][k] == std::round(t.values[c][k] * 65535) / 65535);
    CHECK(back.values[1][5] * 65535 == 211);
    CHECK(back.values[1][6] * 65535 == 5);
    CHECK(back.error[0] == Approx(1e-6 + 0.5 / 65535));

    // Through the command: shown, and converted back to a PNG holding the same samples.
    const std::string again = scratch("again.png");
    const auto r = run_cli("show " + path + " --format json -o " + again);
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(r.out.find("roughness") != std::string::npos);
    const Table twice = read_table(again);
    CHECK(twice.values == back.values);
}

TEST_CASE("the presets' engine files hold the mirror limit where the engines sample smooth texels: three.js's at "
          "x = roughness 1/32, Filament's dfg.inc in its first row",
          "[formats][engine][presets]") {
    // A near-mirror lobe (alpha = r^2 <= 1e-3) reflects about the normal: (1 - wo.wh)^5 = (1 - mu)^5, so
    // the split-sum B = (1 - mu)^5 and A = 1 - (1 - mu)^5 (E = A + B = 1), to about alpha away from grazing.
    const std::string three = scratch("preset/DFGLUTData.js");
    REQUIRE(run_shell("mkdir -p " + scratch("preset")).status == 0);
    auto r = run_cli("lut --preset three --no-preview -o " + three);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const nlohmann::json lut = import_with_node(three);
    REQUIRE(lut["width"] == 16);
    REQUIRE(lut["format"] == "RGFormat");
    for (int j = 2; j < 16; ++j) {
        const double mu = (j + 0.5) / 16, b = std::pow(1 - mu, 5);
        INFO("NoV row " << j);
        CHECK(double(lut["values"][size_t(j * 16) * 2]) == Approx(1 - b).margin(3e-3));
        CHECK(double(lut["values"][size_t(j * 16) * 2 + 1]) == Approx(b).margin(3e-3));
    }

    const std::string inc = scratch("preset/dfg.inc");
    r = run_cli("lut --preset filament --size 16x16 --no-preview -o " + inc);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const std::vector<unsigned> h = hex_numbers(slurp(inc));
    REQUIRE(h.size() == 16 * 16 * 2);
    for (int i = 2; i < 16; ++i) {  // row 0: perceptual roughness 1/32, x = NoV
        const double mu = (i + 0.5) / 16, b = std::pow(1 - mu, 5);
        INFO("NoV column " << i);
        CHECK(from_half(h[size_t(i) * 2]) == Approx(b).margin(3e-3));  // Filament's R: the f90 term
        CHECK(from_half(h[size_t(i) * 2 + 1]) == Approx(1).margin(3e-3));  // G: E = A + B
    }
}

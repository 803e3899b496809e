// `brdfbake lut ltc --preset eevee`: the C++ source compiled by the system compiler beside the
// declarations Blender's EEVEE gives its LTC arrays, and read back by a program as Blender reads
// them (ltc_mat_ggx[t][a][c], ltc_mag_ggx[t][a][c]; legacy: [4 (a + 64 t) + c]). The declarations
// below are written from Blender's headers as docs/ltc_presets.md quotes them: Blender 4.2 and
// later, source/blender/draw/engines/eevee/eevee_lut.hh (namespace blender::eevee::lut,
// `extern const float ltc_mat_ggx[64][64][4];`, `extern const float ltc_mag_ggx[64][64][2];`);
// legacy EEVEE, Blender 2.80 to 4.1, eevee_lut.h (`extern const float ltc_mat_ggx[64 * 64 * 4];`,
// `extern const float ltc_mag_ggx[64 * 64 * 2];`). What the arrays hold is Blender's data's
// convention: three.js's ltc_1 and (ltc_2.R, ltc_2.G), texel for texel (docs/ltc_presets.md).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "brdfbake/table.h"
#include "checks.h"
#include "scratch.h"
#include "support.h"

using namespace brdfbake;
using testing::run_cli;
using testing::run_shell;

namespace {

using testing::put;
using Scratch = testing::ScratchDir;

/// Blender 4.2's eevee_lut.hh, its two LTC declarations (for an n x n table; Blender's n is 64).
std::string eevee_lut_hh(int n) {
    const std::string s = std::to_string(n);
    return "#pragma once\n\nnamespace blender::eevee::lut {\n\n/* LTC matrix components for isotropic GGX. */\n"
           "extern const float ltc_mat_ggx[" + s + "][" + s + "][4];\n"
           "/* LTC magnitude components for isotropic GGX. */\nextern const float ltc_mag_ggx[" + s + "][" + s +
           "][2];\n\n}  // namespace blender::eevee::lut\n";
}

/// Legacy EEVEE's eevee_lut.h, its two LTC declarations.
std::string eevee_lut_h(int n) {
    const std::string s = std::to_string(n);
    return "#pragma once\n\nextern const float ltc_mat_ggx[" + s + " * " + s + " * 4];\nextern const float ltc_mag_ggx[" +
           s + " * " + s + " * 2];\n";
}

/// A program that prints every texel "t a m0 m1 m2 m3 g0 g1" as Blender indexes the arrays.
std::string print_program(int n, bool legacy) {
    const std::string s = std::to_string(n);
    std::string p = legacy ? "#include <stdio.h>\n#include \"eevee_lut.h\"\n" : "#include <cstdio>\n#include \"eevee_lut.hh\"\n";
    p += "int main(void) {\n";
    if (!legacy) p += "  using namespace blender::eevee::lut;\n";
    p += "  for (int t = 0; t < " + s + "; ++t)\n    for (int a = 0; a < " + s + "; ++a) {\n";
    if (legacy)
        p += "      const float* m = &ltc_mat_ggx[4 * (a + " + s + " * t)];\n"
             "      const float* g = &ltc_mag_ggx[2 * (a + " + s + " * t)];\n";
    else
        p += "      const float* m = ltc_mat_ggx[t][a];\n      const float* g = ltc_mag_ggx[t][a];\n";
    p += "      printf(\"%d %d %.9g %.9g %.9g %.9g %.9g %.9g\\n\", t, a, m[0], m[1], m[2], m[3], g[0], g[1]);\n"
         "    }\n  return 0;\n}\n";
    return p;
}

/// The texels the program printed: texels[t * n + a] = {m0, m1, m2, m3, g0, g1}.
std::vector<std::vector<float>> printed_texels(const std::string& out, int n) {
    std::vector<std::vector<float>> texels(size_t(n) * n);
    std::istringstream in(out);
    int t, a, count = 0;
    while (in >> t >> a) {
        REQUIRE((t >= 0 && t < n && a >= 0 && a < n));
        std::vector<float>& v = texels[size_t(t) * n + a];
        v.resize(6);
        for (float& x : v) in >> x;
        ++count;
    }
    CHECK(count == n * n);
    return texels;
}

/// Compiles `sources` (in dir) with `compiler` and runs the program: its texels.
std::vector<std::vector<float>> compile_and_print(const std::string& dir, const std::string& compiler,
                                                  const std::string& sources, int n) {
    const auto built = run_shell("cd " + dir + " && " + compiler + " -Wall -Wextra -Werror -o print " + sources);
    INFO(compiler << " " << sources << ": " << built.err);
    REQUIRE(built.status == 0);
    const auto ran = run_shell(dir + "/print");
    REQUIRE(ran.status == 0);
    return printed_texels(ran.out, n);
}

/// A table on EEVEE's grid (n x n, x = roughness, y = sqrt(1 - mu), edge texels) in the eevee
/// packing, each value naming its texel and channel (not a binary fraction: float rounds it).
Table eevee_grid_table(int n) {
    Table t = testing::ltc_engine_grid_table(n, {"ltc_mat_ggx.0", "ltc_mat_ggx.1", "ltc_mat_ggx.2", "ltc_mat_ggx.3",
                                                 "ltc_mag_ggx.0", "ltc_mag_ggx.1", "distance", "distance_error"});
    t.x.parameter = t.x.coordinate;
    t.y.parameter = t.y.coordinate;
    for (size_t c = 0; c < t.channels.size(); ++c)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) t.values[c][size_t(j) * n + i] = (c + 1) * 10.0 + j + i / 3.0 - (c == 1 ? 50 : 0);
    return t;
}

}  // namespace

TEST_CASE("eevee .cc and .c: compiled beside Blender's declarations, each texel as Blender indexes it is the table's float",
          "[formats][engine][ltc][quick]") {
    const int n = 64;
    const Table t = eevee_grid_table(n);
    const Scratch dir("eevee");
    write_table(t, dir / "eevee_ltc.cc");
    write_table(t, dir / "eevee_ltc.c");
    put(dir / "eevee_lut.hh", eevee_lut_hh(n));
    put(dir / "eevee_lut.h", eevee_lut_h(n));
    put(dir / "main.cc", print_program(n, false));
    put(dir / "main.c", print_program(n, true));
    // eevee_lut.cc includes eevee_lut.hh before its definitions: the file must compile after it too.
    put(dir / "beside.cc", "#include \"eevee_lut.hh\"\n#include \"eevee_ltc.cc\"\n");
    put(dir / "beside.c", "#include \"eevee_lut.h\"\n#include \"eevee_ltc.c\"\n");
    struct Build {
        const char* compiler;
        const char* sources;
        bool legacy;
    };
    // Standalone (the file's own linkage), and included after the header; legacy as C (eevee_lut.c,
    // Blender 2.80 to 3.6) and as C++ (eevee_lut.cc, 4.0 and 4.1).
    for (const Build& b : {Build{"g++ -std=c++17", "main.cc eevee_ltc.cc", false},
                           Build{"g++ -std=c++17", "main.cc beside.cc", false},
                           Build{"gcc -std=c99", "main.c eevee_ltc.c", true}, Build{"gcc -std=c99", "main.c beside.c", true},
                           Build{"g++ -std=c++17 -x c++", "main.c eevee_ltc.c", true}}) {
        const auto texels = compile_and_print(dir.path, b.compiler, b.sources, n);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (int c = 0; c < 6; ++c) {
                    INFO(b.compiler << " " << b.sources << ": texel t = " << j << ", a = " << i << ", channel " << c);
                    REQUIRE(texels[size_t(j) * n + i].size() == 6);
                    CHECK(texels[size_t(j) * n + i][size_t(c)] == float(t.values[size_t(c)][size_t(j) * n + i]));
                }
    }
    // Off EEVEE's grid or without its arrays: refused, nothing written.
    Table flipped = t;
    arrange_axes(flipped, {"roughness", "sqrt_one_minus_mu"}, {"roughness"});
    CHECK_THROWS_WITH(write_table(flipped, dir / "flipped.cc"), Catch::Contains("EEVEE's LTC grid"));
    Table plain = t;
    plain.channels[0] = "m00";
    CHECK_THROWS_WITH(write_table(plain, dir / "plain.c"), Catch::Contains("ltc_mat_ggx and ltc_mag_ggx"));
    CHECK_FALSE(std::filesystem::exists(dir / "flipped.cc"));
    CHECK_FALSE(std::filesystem::exists(dir / "plain.c"));
}

TEST_CASE("lut ltc --preset eevee: Blender's arrays hold --preset three's ltc_1 and ltc_2.RG, row t = 0 is (1, 0, 0, m)",
          "[ltc][presets][cli]") {
    // 8 x 8 texels on EEVEE's grid (Blender's 64 x 64 fit takes 17 s of CPU), the declarations'
    // size changed to match.
    const int n = 8;
    const Scratch dir("eevee");
    const auto eevee = run_cli("lut ltc --preset eevee --size " + std::to_string(n) + " -o " + (dir / "eevee_ltc.cc") +
                               " --no-preview");
    INFO(eevee.err);
    REQUIRE(eevee.status == 0);
    const auto three = run_cli("lut ltc --preset three --size " + std::to_string(n) + " -o " + (dir / "three.csv") +
                               " --no-preview");
    INFO(three.err);
    REQUIRE(three.status == 0);
    const Table t3 = read_table_file(dir / "three.csv");
    REQUIRE(t3.channels.size() >= 6);
    REQUIRE(t3.channels[0] == "ltc_1.R");
    REQUIRE(t3.channels[5] == "ltc_2.G");
    put(dir / "eevee_lut.hh", eevee_lut_hh(n));
    put(dir / "main.cc", print_program(n, false));
    const auto texels = compile_and_print(dir.path, "g++ -std=c++17", "main.cc eevee_ltc.cc", n);
    for (int t = 0; t < n; ++t)
        for (int a = 0; a < n; ++a) {
            // ltc_mat_ggx[t][a] = ltc_1.RGBA, ltc_mag_ggx[t][a] = ltc_2.RG of three.js's texel a + n t.
            // ltc_1 is float32 in the table; the magnitudes are doubles, which the CSV prints to 9
            // digits: the float nearest those digits may be the neighbour of the .cc's float(v).
            const size_t k = size_t(t) * n + a;
            for (int c = 0; c < 6; ++c) {
                INFO("texel t = " << t << ", a = " << a << ", channel " << c);
                const float want = float(t3.values[size_t(c)][k]);
                if (c < 4) CHECK(texels[k][size_t(c)] == want);
                else CHECK(std::fabs(texels[k][size_t(c)] - want) <= std::fabs(want) * 1.2e-7);
            }
        }
    // Normal view (t = 0): the lobe is symmetric about the normal, so M = diag(m, m, 1) up to scale
    // and M^-1 / M^-1_11 = (1, 0, 0, m) (Heitz et al. 2016, isotropic case; three.js's and Blender's
    // first row read so). For small alpha the lobe's slopes are twice the GGX half vector's, a
    // GGX slope distribution of width 2 alpha, and the clamped cosine's slopes are GGX's of width
    // 1: m -> 2 alpha (three.js's texels a = 1, 2 hold 2.0 alpha to 0.3%). The fitter's alpha floor
    // (attribute ltc_alpha_floor) puts r = 0 at alpha 1e-4.
    REQUIRE(t3.attributes.at("ltc_alpha_floor").find("alpha = 0.0001 are fitted at 0.0001") != std::string::npos);
    for (int a = 0; a < n; ++a) {
        const std::vector<float>& m = texels[size_t(a)];
        const double r = double(a) / (n - 1), alpha = std::max(r * r, 1e-4);
        INFO("t = 0, a = " << a << ": " << m[0] << " " << m[1] << " " << m[2] << " " << m[3]);
        CHECK(std::fabs(m[0] - 1.0) <= 1e-2);
        CHECK(std::fabs(m[1]) <= 1e-2);
        CHECK(std::fabs(m[2]) <= 1e-2);
        if (alpha <= 0.09) CHECK(m[3] == Approx(2 * alpha).epsilon(2e-2));
        CHECK(m[3] > 0.0);
    }
    // The row's m grows with roughness (the lobe widens), and texels off t = 0 are not diagonal.
    for (int a = 1; a < n; ++a) CHECK(texels[size_t(a)][3] > texels[size_t(a) - 1][3]);
    CHECK(std::fabs(texels[size_t(n) + 1][2]) > 0.05);
}

TEST_CASE("lut -o NAME.cc / NAME.c: a table that is not EEVEE's is refused with one line, nothing written",
          "[ltc][presets][cli]") {
    // Refused when the table is written (after its computation): the progress display held back so
    // that stderr holds the message alone.
    const Scratch dir("eevee");
    for (const auto& [args, out] : {std::pair<std::string, std::string>{"lut albedo --model ggx --size 4", "albedo.cc"},
                                    {"lut ltc --preset three --size 3", "three.c"},
                                    {"lut ltc --preset eevee --size 3 --flip roughness", "flipped.cc"}})
        testing::check_refused_when_written(args, dir / out);
}

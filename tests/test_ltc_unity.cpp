// `brdfbake lut ltc --preset unity-hdrp -o NAME.cs`: the C# file compiled by Mono's mcs (Debian's
// mono-mcs) beside a stub of the rest of HDRP's LTCAreaLight class, and read back by a program as
// HDRP uploads it. Unity's conventions, as docs/ltc_presets.md ("Unity HDRP") quotes them from
// Unity-Technologies/Graphics (Packages/com.unity.render-pipelines.high-definition):
//  - Runtime/Material/LTCAreaLight/Generated/LtcData.BRDF_GGX.cs: namespace
//    UnityEngine.Rendering.HighDefinition, `internal partial class LTCAreaLight`, `internal static
//    ushort[] s_LtcMatrixData_BRDF_GGX = new ushort[64 * 64 * 4]`, accessed at
//    [<roughnessIndex> + 64 * <thetaIndex>] per texel, roughness = (index / 63)^2, cosTheta =
//    1 - (thetaIndex / 63)^2;
//  - Runtime/Material/LTCAreaLight/LTCAreaLight.cs: Texture2DArray(64, 64, ..., R16G16B16A16_SFloat)
//    filled by SetPixelData(s_LtcMatrixData_BRDF_GGX, 0, slice): 4 half floats per texel, texel
//    (x, y) at x + 64 y, row y sampled at v = (y + 0.5) / 64;
//  - Editor/Material/LTCAreaLight/LTCTableGenerator.cs ExportToCSharp: the texel is
//    FloatToHalf(invM.m00, invM.m20, invM.m11, invM.m02) / invM.m22, invM the inverse of M (LTC.cs:
//    Matrix.mRC is row R, column C; M maps the cosine's directions to the lobe's, the view at
//    (sin theta, 0, cos theta)); LTCAreaLight.hlsl SampleLtcMatrix loads RGBA into
//    invM._m00_m02_m11_m20 with invM._m22 = 1, "the transposed M^(-1)";
//  - the generator's cosTheta floor 3.7540224885647058e-4 at the last row.
#include <catch2/catch.hpp>

#include <Imath/half.h>
#include <unistd.h>

#include <cmath>
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

/// The rest of HDRP's LTCAreaLight class that the table meets: k_LtcLUTResolution (n; HDRP's is
/// 64) and a Main that reads the array as HDRP uploads it, printing "y x R G B A" for texel (x, y):
/// since July 2023 SetPixelData lays the ushort array into an RGBA16F texture, texel (x, y) at
/// x + n y (printed: the half floats' bits); from 2021 to then LoadLUT took entries 0, 2, 4, 6 of
/// row x + n y of the double[,] array as Mathf.Min(65504, (float)v) (printed: the floats, with
/// entry 8 and the sum of |entries 1, 3, 5, 7|).
std::string csharp_stub(int n, bool doubles) {
    const std::string s = std::to_string(n);
    std::string p = "using System;\n\nnamespace UnityEngine.Rendering.HighDefinition\n{\n"
                    "    internal partial class LTCAreaLight\n    {\n"
                    "        internal const int k_LtcLUTResolution = " + s + ";\n\n"
                    "        static float Clamp(double v) { return Math.Min(65504.0f, (float)v); }\n\n"
                    "        static int Main()\n        {\n";
    if (doubles)
        p += "            double[,] data = s_LtcMatrixData_BRDF_GGX;\n"
             "            if (data.GetLength(0) != k_LtcLUTResolution * k_LtcLUTResolution || data.GetLength(1) != 9) return 1;\n";
    else
        p += "            ushort[] data = s_LtcMatrixData_BRDF_GGX;\n"
             "            if (data.Length != k_LtcLUTResolution * k_LtcLUTResolution * 4) return 1;\n";
    p += "            for (int y = 0; y < k_LtcLUTResolution; ++y)\n"
         "                for (int x = 0; x < k_LtcLUTResolution; ++x)\n"
         "                {\n"
         "                    int i = x + k_LtcLUTResolution * y;\n";
    if (doubles)
        p += "                    Console.WriteLine(\"{0} {1} {2} {3} {4} {5} {6} {7}\", y, x, Clamp(data[i, 0]).ToString(\"R\"),\n"
             "                                      Clamp(data[i, 2]).ToString(\"R\"), Clamp(data[i, 4]).ToString(\"R\"),\n"
             "                                      Clamp(data[i, 6]).ToString(\"R\"), data[i, 8].ToString(\"R\"),\n"
             "                                      (Math.Abs(data[i, 1]) + Math.Abs(data[i, 3]) + Math.Abs(data[i, 5]) + Math.Abs(data[i, 7])).ToString(\"R\"));\n";
    else
        p += "                    Console.WriteLine(\"{0} {1} {2} {3} {4} {5}\", y, x, data[4 * i], data[4 * i + 1],\n"
             "                                      data[4 * i + 2], data[4 * i + 3]);\n";
    return p + "                }\n            return 0;\n        }\n    }\n}\n";
}

float half_value(unsigned bits) {
    Imath::half h;
    h.setBits(static_cast<unsigned short>(bits));
    return float(h);
}

/// Compiles dir/LtcData.BRDF_GGX.cs beside the stub with mcs (warnings as errors) and runs it with
/// mono: texels[y * n + x] = the four values HDRP uploads for texel (x, y) (the 2021 form: then
/// entry 8 and the sum of the entries that must be 0).
std::vector<std::vector<float>> compile_and_read(const std::string& dir, int n, bool doubles = false) {
    put(dir + "/LTCAreaLightStub.cs", csharp_stub(n, doubles));
    const auto built = run_shell("cd " + dir + " && mcs -warnaserror+ -warn:4 -nologo -out:print.exe "
                                 "LtcData.BRDF_GGX.cs LTCAreaLightStub.cs");
    INFO("mcs (Debian's mono-mcs, scripts/setup.sh): " << built.out << built.err);
    REQUIRE(built.status == 0);
    const auto ran = run_shell("mono " + dir + "/print.exe");
    INFO(ran.err);
    REQUIRE(ran.status == 0);
    std::vector<std::vector<float>> texels(size_t(n) * n);
    std::istringstream in(ran.out);
    int y, x, count = 0;
    while (in >> y >> x) {
        REQUIRE((y >= 0 && y < n && x >= 0 && x < n));
        std::vector<float>& v = texels[size_t(y) * n + x];
        for (int c = 0; c < (doubles ? 6 : 4); ++c) {
            unsigned bits = 0;
            float f = 0;
            if (doubles) in >> f;
            else in >> bits;
            v.push_back(doubles ? f : half_value(bits));
        }
        ++count;
    }
    CHECK(count == n * n);
    return texels;
}

/// A table on HDRP's grid (n x n, x = roughness, y = sqrt(1 - mu), edge texels) in the unity-hdrp
/// packing, R and G naming its row and column (G negative), each value a half float (one
/// subnormal and HDRP's clamp 65504 among them).
Table unity_grid_table(int n) {
    Table t = testing::ltc_engine_grid_table(
        n, {"s_LtcMatrixData_BRDF_GGX.0", "s_LtcMatrixData_BRDF_GGX.1", "s_LtcMatrixData_BRDF_GGX.2",
            "s_LtcMatrixData_BRDF_GGX.3", "magnitude", "fresnel", "distance", "distance_error"});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {  // R names the row, G the column; each exact in half floats
            const double v[8] = {1.0 + j + (i % 8) / 8.0, -(1.0 + i + (j % 8) / 8.0), 100.0 + i + j / 4.0,
                                 300.0 + j + i / 4.0, 0.5, 0.25, 0.01, 0.001};
            for (size_t c = 0; c < t.channels.size(); ++c) t.values[c][size_t(j) * n + i] = v[c];
        }
    t.values[3][0] = 65504.0;
    t.values[3][1] = std::ldexp(3.0, -24);  // a subnormal half
    return t;
}

}  // namespace

TEST_CASE("unity-hdrp .cs: compiled by mcs beside HDRP's class, each texel as SetPixelData lays it is the table's half",
          "[formats][engine][ltc][quick]") {
    const int n = 64;
    const Table t = unity_grid_table(n);
    const Scratch dir("unity");
    write_table(t, dir / "LtcData.BRDF_GGX.cs");
    const auto texels = compile_and_read(dir.path, n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 4; ++c) {
                INFO("texel t = " << j << ", a = " << i << ", channel " << c);
                REQUIRE(texels[size_t(j) * n + i].size() == 4);
                CHECK(texels[size_t(j) * n + i][size_t(c)] == t.values[size_t(c)][size_t(j) * n + i]);
            }
    // Off HDRP's grid, without its array, or values that are not half floats: refused, nothing written.
    Table flipped = t;
    arrange_axes(flipped, {"roughness", "sqrt_one_minus_mu"}, {"roughness"});
    CHECK_THROWS_WITH(write_table(flipped, dir / "flipped.cs"), Catch::Contains("HDRP's LTC grid"));
    Table plain = t;
    plain.channels[0] = "m00";
    CHECK_THROWS_WITH(write_table(plain, dir / "plain.cs"), Catch::Contains("s_LtcMatrixData_BRDF_GGX"));
    Table wide = t;
    wide.values[2][5] = 1.0 + std::ldexp(1.0, -12);  // between two half floats
    CHECK_THROWS_WITH(write_table(wide, dir / "wide.cs"), Catch::Contains("not one"));
    wide.values[2][5] = 70000.0;  // beyond the largest half
    CHECK_THROWS_WITH(write_table(wide, dir / "wide.cs"), Catch::Contains("not one"));
    for (const char* name : {"flipped.cs", "plain.cs", "wide.cs"}) CHECK_FALSE(std::filesystem::exists(dir / name));
}

TEST_CASE("lut ltc --preset unity-hdrp(-2021): HDRP's texels are --preset three's M^-1 renormalised, row t = 0 is "
          "(1/m, 0, 1/m, 0)",
          "[ltc][presets][cli]") {
    // 8 x 8 texels on HDRP's grid (the 64 x 64 fit takes 16 s of CPU); three's last row computed at
    // HDRP's cosTheta floor so that every texel has the same (roughness, view). The 2021 form holds
    // the same numbers (those of the half floats the GPU gets) as doubles, all nine entries.
    const bool doubles = GENERATE(false, true);
    const std::string preset = doubles ? "unity-hdrp-2021" : "unity-hdrp";
    INFO("--preset " << preset);
    const int n = 8;
    const Scratch dir("unity");
    const auto unity = run_cli("lut ltc --preset " + preset + " --size " + std::to_string(n) + " -o " +
                               (dir / "LtcData.BRDF_GGX.cs") + " --no-preview");
    INFO(unity.err);
    REQUIRE(unity.status == 0);
    const auto three = run_cli("lut ltc --preset three --mu-floor 3.7540224885647058e-4 --size " + std::to_string(n) +
                               " -o " + (dir / "three.csv") + " --no-preview");
    INFO(three.err);
    REQUIRE(three.status == 0);
    const Table t3 = read_table_file(dir / "three.csv");
    REQUIRE(t3.channels.size() >= 4);
    REQUIRE(t3.channels[0] == "ltc_1.R");
    REQUIRE(t3.channels[3] == "ltc_1.A");
    const auto texels = compile_and_read(dir.path, n, doubles);
    for (int t = 0; t < n; ++t)
        for (int a = 0; a < n; ++a) {
            // three.js's ltc_1 = (Minv00, Minv20, Minv02, Minv22) / Minv11 (docs/ltc_presets.md), so
            // HDRP's (Minv00, Minv20, Minv11, Minv02) / Minv22 = (R, G, 1, B) / A. HDRP's generator
            // rounds to half floats and its loader clamped to 65504: the texel is that within the
            // half's rounding (2^-11 relative, 2^-25 absolute below its normal range) plus ltc_1's
            // float32 rounding.
            const size_t k = size_t(t) * n + a;
            const double r = t3.values[0][k], g = t3.values[1][k], b = t3.values[2][k], al = t3.values[3][k];
            const double want[4] = {r / al, g / al, 1.0 / al, b / al};
            for (int c = 0; c < 4; ++c) {
                INFO("texel t = " << t << ", a = " << a << ", channel " << c << ": three's ltc_1 " << r << " " << g
                                  << " " << b << " " << al);
                const double w = std::clamp(want[c], -65504.0, 65504.0);
                CHECK(std::fabs(texels[k][size_t(c)] - w) <= std::fabs(w) * (std::ldexp(1.0, -11) + 1e-6) + 3e-8);
            }
            // The shader's invM (_m22 = 1) is M^-1 transposed, up to a positive scale: the stored
            // M^-1_22 of three (A) and its M^-1_11 (1) have the sign of HDRP's B and 1.
            CHECK(texels[k][2] > 0.0f);
            if (doubles) {  // entry 8 (M^-1_22 / M^-1_22) is 1, entries 1, 3, 5, 7 are 0 (isotropic: no y coupling)
                CHECK(texels[k][4] == 1.0f);
                CHECK(texels[k][5] == 0.0f);
            }
        }
    // Normal view (t = 0): M = diag(m, m, 1) up to scale (the lobe is symmetric about the normal),
    // so M^-1 / M^-1_22 = diag(1/m, 1/m, 1): R = B, G = A = 0 as in HDRP's own first row; for small
    // alpha m -> 2 alpha (test_ltc_eevee.cpp: the lobe's slopes are twice the half vector's).
    for (int a = 0; a < n; ++a) {
        const std::vector<float>& u = texels[size_t(a)];
        const double rr = double(a) / (n - 1), alpha = std::max(rr * rr, 1e-4);
        INFO("t = 0, a = " << a << ": " << u[0] << " " << u[1] << " " << u[2] << " " << u[3]);
        CHECK(std::fabs(u[0] - u[2]) <= std::fabs(u[2]) * std::ldexp(1.0, -10));
        CHECK(u[1] == 0.0f);
        CHECK(u[3] == 0.0f);
        if (alpha <= 0.09) CHECK(1.0 / u[0] == Approx(2 * alpha).epsilon(2e-2));
    }
}

TEST_CASE("lut -o NAME.cs: a table that is not HDRP's is refused with one line, nothing written", "[ltc][presets][cli]") {
    const Scratch dir("unity");
    for (const auto& [args, out] : {std::pair<std::string, std::string>{"lut albedo --model ggx --size 4", "albedo.cs"},
                                    {"lut ltc --preset three --size 3", "three.cs"},
                                    {"lut ltc --preset unity-hdrp --size 3 --flip roughness", "flipped.cs"},
                                    // HDRP's BRDF_GGX.cs: GGX with height-correlated G2, F = 1
                                    {"lut ltc --preset unity-hdrp --size 3 --model beckmann", "beckmann.cs"},
                                    {"lut ltc --preset unity-hdrp --size 3 --model ggx:shadowing=separable",
                                     "separable.cs"}})
        testing::check_refused_when_written(args, dir / out);
}

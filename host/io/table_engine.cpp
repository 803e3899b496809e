// The engines' own table files, written directly so that nothing needs converting:
//  - three.js's src/renderers/shaders/DFGLUTData.js: an ES module whose Uint16Array DATA holds
//    half floats, texel (x, y) at (y * width + x) * channels, uploaded by getDFGLUT() as a
//    DataTexture (RGFormat, HalfFloatType, linear filtering, clamped; flipY false, so row 0 is
//    texture coordinate t = 0) and sampled at vec2(roughness, dotNV);
//  - Filament's dfg.inc: the body of `const uint16_t DFG_LUT[] = { #include "dfg.inc" };`
//    (filament/src/details/DFG.cpp), as cmgen --ibl-dfg=dfg.inc writes it
//    (tools/cmgen/src/cmgen.cpp, iblLutDfg): "0x%04x, " per half float, 2 (or 3, with the cloth
//    DFG) per texel, 4 texels per line, rows in GL order (row 0 at t = 0, perceptual roughness 0);
//  - Cycles' intern/cycles/scene/shader.tables: `static const float table_NAME[N] = { ... };`
//    between CCL_NAMESPACE_BEGIN and CCL_NAMESPACE_END, one table row per line, a blank line
//    between z-slices, stored index (z * height + y) * width + x;
//  - Blender EEVEE's LTC arrays ltc_mat_ggx and ltc_mag_ggx as eevee_lut.cc defines them: Blender
//    4.2 and later (source/blender/draw/engines/eevee/eevee_lut.hh: namespace blender::eevee::lut,
//    `extern const float ltc_mat_ggx[64][64][4];`, `extern const float ltc_mag_ggx[64][64][2];`) or
//    legacy EEVEE, Blender 2.80 to 4.1 (eevee_lut.h: `extern const float ltc_mat_ggx[64 * 64 * 4];`,
//    `ltc_mag_ggx[64 * 64 * 2]`), index [t][a] = 4 (a + 64 t): row t at sqrt(1 - cos theta) = t/63,
//    column a at roughness a/63 (docs/ltc_presets.md, "Blender EEVEE").
#include <Imath/half.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/table.h"
#include "brdfbake/version.h"

namespace brdfbake {
namespace {

/// The stored texel that a texture's texel (i, j) holds, texture row 0 at the sampling
/// coordinate's low end: a flipped axis (lo > hi, texel 0 at the range's upper end) is written
/// backwards, as cmgen writes its image rows (roughest first) bottom-up.
size_t texture_texel(const Table& t, int i, int j) {
    const int x = t.x.lo > t.x.hi ? t.width() - 1 - i : i;
    const int y = t.y.lo > t.y.hi ? t.height() - 1 - j : j;
    return size_t(y) * size_t(t.width()) + size_t(x);
}

/// The IEEE 754 binary16 bits of v, rounded to nearest even (Imath::half).
uint16_t half_bits(double v) { return Imath::half(float(v)).bits(); }

std::string hex16(uint16_t bits) {
    char b[8];
    std::snprintf(b, sizeof b, "0x%04x", unsigned(bits));
    return b;
}

/// The description as comment lines "PREFIX key: text" (no line break inside a line, no "*/").
std::string description_comment(const Table& t, const char* prefix) {
    std::string out;
    for (const auto& kv : table_description(t)) {
        std::string text = comment_line_text(kv.second);
        for (size_t p = text.find("*/"); p != std::string::npos; p = text.find("*/", p)) text.replace(p, 2, "* /");
        out += std::string(prefix) + kv.first + ": " + text + "\n";
    }
    return out;
}

void require_2d(const Table& t, const std::string& format) {
    if (t.depth() > 1)
        throw Error("a " + format + " holds a 2D texture; the " + t.kind + " table has " + std::to_string(t.depth()) +
                    " z-slices: write .exr, .npy, .h or .tables");
}

std::string channel_list(const Table& t) {
    std::string s;
    for (const auto& c : t.channels) s += (s.empty() ? "" : ", ") + c;
    return s;
}

}  // namespace

void check_threejs_table(const Table& t) {
    require_2d(t, "three.js DataTexture module");
    const size_t n = t.channels.size();
    if (n != 1 && n != 2 && n != 4)
        throw Error("a three.js half-float DataTexture has 1, 2 or 4 channels (three.js has no RGB format); the " +
                    t.kind + " table has " + std::to_string(n) + ": write .exr or .npy");
}

std::string table_threejs_module(const Table& t) {
    check_threejs_table(t);
    const size_t n = t.channels.size();
    const char* format = n == 1 ? "RedFormat" : n == 2 ? "RGFormat" : "RGBAFormat";
    std::ostringstream o;
    o << "/**\n * Precomputed " << t.kind << " table written by brdfbake " << BRDFBAKE_VERSION
      << " in the form of three.js's src/renderers/shaders/DFGLUTData.js\n * Resolution: " << t.width() << "x"
      << t.height() << "\n * Format: " << (n == 1 ? "R16F" : n == 2 ? "RG16F" : "RGBA16F") << " (" << n
      << " half floats per texel: " << channel_list(t) << "), texel (x, y) at DATA[(y * " << t.width()
      << " + x) * " << n << "], row 0 at texture coordinate 0\n"
      << description_comment(t, " * ") << " */\n\n";
    o << "import { DataTexture } from '../../textures/DataTexture.js';\n";
    o << "import { " << format << ", HalfFloatType, LinearFilter, ClampToEdgeWrapping } from '../../constants.js';\n\n";
    o << "const DATA = new Uint16Array( [";
    for (int j = 0; j < t.height(); ++j) {
        o << "\n\t";
        for (int i = 0; i < t.width(); ++i)
            for (size_t c = 0; c < n; ++c) {
                const bool last = j + 1 == t.height() && i + 1 == t.width() && c + 1 == n;
                o << hex16(half_bits(t.values[c][texture_texel(t, i, j)])) << (last ? "" : (i + 1 == t.width() && c + 1 == n) ? "," : ", ");
            }
    }
    o << "\n] );\n\nlet lut = null;\n\nexport function getDFGLUT() {\n\n\tif ( lut === null ) {\n\n";
    o << "\t\tlut = new DataTexture( DATA, " << t.width() << ", " << t.height() << ", " << format << ", HalfFloatType );\n";
    o << "\t\tlut.name = 'DFG_LUT';\n\t\tlut.minFilter = LinearFilter;\n\t\tlut.magFilter = LinearFilter;\n";
    o << "\t\tlut.wrapS = ClampToEdgeWrapping;\n\t\tlut.wrapT = ClampToEdgeWrapping;\n";
    o << "\t\tlut.generateMipmaps = false;\n\t\tlut.needsUpdate = true;\n\n\t}\n\n\treturn lut;\n\n}\n";
    return o.str();
}

void check_filament_table(const Table& t) {
    require_2d(t, "Filament dfg.inc");
    const size_t n = t.channels.size();
    if (n != 2 && n != 3)
        throw Error("Filament's dfg.inc holds 2 half floats per texel (3 with the cloth DFG); the " + t.kind +
                    " table has " + std::to_string(n) + " channels: write .exr or .npy");
}

std::string table_filament_include(const Table& t) {
    check_filament_table(t);
    const size_t n = t.channels.size();
    std::ostringstream o;
    o << "// generated by brdfbake " << BRDFBAKE_VERSION << " in the form of cmgen --ibl-dfg=dfg.inc\n";
    o << "// DFG LUT stored as an " << (n == 2 ? "RG16F" : "RGB16F") << " texture (" << channel_list(t)
      << "), in GL order: row 0 at texture coordinate 0\n";
    o << description_comment(t, "// ");
    for (int j = 0; j < t.height(); ++j)
        for (int i = 0; i < t.width(); ++i) {
            if (i % 4 == 0) o << "\n    ";
            for (size_t c = 0; c < n; ++c) o << hex16(half_bits(t.values[c][texture_texel(t, i, j)])) << ", ";
        }
    o << "\n";
    return o.str();
}

namespace {

/// Blender EEVEE's LTC arrays: their names (the eevee packing's channels are NAME.0, NAME.1, ...),
/// texel sizes and eevee_lut.hh's comments.
struct EeveeArray {
    const char* name;
    int channels;
    const char* comment;
};
const EeveeArray kEeveeArrays[] = {{"ltc_mat_ggx", 4, "LTC matrix components for isotropic GGX."},
                                   {"ltc_mag_ggx", 2, "LTC magnitude components for isotropic GGX."}};

/// "lo to hi, edge texels" of an axis, for the messages.
std::string number_range(const Axis& a) {
    return round_trip_text(a.lo) + " to " + round_trip_text(a.hi) + ", " + texels_name(a.texels) + " texels";
}

/// Throws unless t has the channels `names` (else: "an FORMAT holds WHAT (lut ltc --preset
/// PRESET)") and lies on the LTC grid of ENGINE (three.js's, which EEVEE and HDRP share): x =
/// roughness and y = sqrt(1 - mu), each over [0, 1] at edge texels (uv * 63/64 + 0.5/64), unflipped.
void require_ltc_grid_table(const Table& t, const std::string& format, const std::vector<std::string>& names,
                            const std::string& what, const std::string& preset, const std::string& engine) {
    for (const std::string& name : names)
        if (std::find(t.channels.begin(), t.channels.end(), name) == t.channels.end())
            throw Error("an " + format + " holds " + what + " (lut ltc --preset " + preset + "); the " + t.kind +
                        " table has channels " + channel_list(t) + ": write .exr or .csv");
    require_2d(t, format);
    auto on_grid = [](const Axis& a, const char* name) {
        return a.name == name && a.lo == 0.0 && a.hi == 1.0 && a.texels == Texels::Edge;
    };
    if (!on_grid(t.x, "roughness") || !on_grid(t.y, "sqrt_one_minus_mu"))
        throw Error("an " + format + " holds " + engine + "'s LTC grid, x = roughness and y = sqrt_one_minus_mu, each "
                    "0 to 1 at edge texels (lut ltc --preset " + preset + "); this table's x is " + t.x.name + " (" +
                    number_range(t.x) + "), y " + t.y.name + " (" + number_range(t.y) + "): write .exr or .csv");
}

/// Throws unless t is an EEVEE LTC table (the eevee packing's channels, EEVEE's grid).
void require_eevee_table(const Table& t, const std::string& format) {
    std::vector<std::string> names;
    for (const EeveeArray& a : kEeveeArrays)
        for (int k = 0; k < a.channels; ++k) names.push_back(a.name + ("." + std::to_string(k)));
    require_ltc_grid_table(t, format, names, "Blender EEVEE's ltc_mat_ggx and ltc_mag_ggx", "eevee", "EEVEE");
}

/// The value channel `name` of t (present: require_eevee_table).
const std::vector<double>& channel_values(const Table& t, const std::string& name) {
    return t.values[size_t(std::find(t.channels.begin(), t.channels.end(), name) - t.channels.begin())];
}

/// One EEVEE array's initialiser: per texel its channels, either nested {{...}, ...} rows of
/// {c0, c1, ...} texels (current EEVEE) or flat (legacy), `f` literals.
std::string eevee_initialiser(const Table& t, const EeveeArray& a, bool flat) {
    std::vector<const std::vector<double>*> ch;
    for (int k = 0; k < a.channels; ++k) ch.push_back(&channel_values(t, a.name + ("." + std::to_string(k))));
    const size_t per_line = size_t(8 / a.channels);  // 8 numbers a line
    std::ostringstream o;
    o << "{";
    for (int j = 0; j < t.height(); ++j) {
        if (!flat) o << (j ? "," : "") << "\n    {";
        for (int i = 0; i < t.width(); ++i) {
            const size_t texel = size_t(j) * size_t(t.width()) + size_t(i);
            const bool first = flat ? texel == 0 : i == 0;
            o << (first ? "" : ",") << ((flat ? texel : size_t(i)) % per_line == 0 ? (flat ? "\n    " : "\n        ") : " ")
              << (flat ? "" : "{");
            for (int k = 0; k < a.channels; ++k) o << (k ? ", " : "") << c_float_literal((*ch[size_t(k)])[texel], true);
            if (!flat) o << "}";
        }
        if (!flat) o << "}";
    }
    o << "\n}";
    return o.str();
}

}  // namespace

void check_eevee_table(const Table& t, bool legacy) {
    require_eevee_table(t, legacy ? "EEVEE .c file (legacy)" : "EEVEE .cc file");
}

std::string table_eevee_source(const Table& t, bool legacy) {
    check_eevee_table(t, legacy);
    const std::string w = std::to_string(t.width()), h = std::to_string(t.height());
    std::ostringstream o;
    o << "/* Blender EEVEE's LTC tables, written by brdfbake " << BRDFBAKE_VERSION << " for "
      << (legacy ? "legacy EEVEE, Blender 2.80 to 4.1\n * (source/blender/draw/engines/eevee/eevee_lut.c, eevee_lut.cc "
                   "from 4.0; declared in eevee_lut.h)."
                 : "Blender 4.2 and later\n * (source/blender/draw/engines/eevee/eevee_lut.cc, declared in eevee_lut.hh).")
      << "\n * To use them: in eevee_lut." << (legacy ? "c (.cc)" : "cc") << " replace the definitions of ltc_mat_ggx and "
      << "ltc_mag_ggx by the two\n * below, or add this file to the engine's sources and delete those two definitions "
      << "there.\n * ltc_mat_ggx" << (legacy ? "[4 (a + " + w + " t) + c]" : "[t][a][c]")
      << " = M^-1 / M^-1_11 as (00, 20, 02, 22) (three.js's ltc_1), ltc_mag_ggx"
      << (legacy ? "[2 (a + " + w + " t) + c]" : "[t][a][c]") << " =\n * (magnitude, fresnel); column a at roughness a / "
      << t.width() - 1 << ", row t at sqrt(1 - cos theta) = t / " << t.height() - 1 << ".\n";
    if (t.width() != 64 || t.height() != 64)
        o << " * Blender declares 64 x 64 (UTIL_TEX_SIZE / LUT_SIZE): this table is " << w << " x " << h
          << ", which needs those declarations changed.\n";
    o << " * The extern " << (legacy ? "declarations give" : "definitions have")
      << " external linkage in C++ without the header.\n" << description_comment(t, " * ") << " */\n\n";
    if (!legacy) o << "namespace blender::eevee::lut {\n\n";
    for (const EeveeArray& a : kEeveeArrays) {
        const std::string shape = legacy ? "[" + w + " * " + h + " * " + std::to_string(a.channels) + "]"
                                         : "[" + h + "][" + w + "][" + std::to_string(a.channels) + "]";
        o << "/* " << a.comment << " */\n";
        if (legacy) o << "extern const float " << a.name << shape << ";\n";
        o << (legacy ? "" : "extern ") << "const float " << a.name << shape << " = " << eevee_initialiser(t, a, legacy)
          << ";\n\n";
    }
    if (!legacy) o << "}  // namespace blender::eevee::lut\n";
    return o.str();
}

namespace {

/// HDRP's GGX LTC array, whose channels the unity-hdrp packing names NAME.0 ... NAME.3.
const char* const kUnityArray = "s_LtcMatrixData_BRDF_GGX";

/// The binary16 bits of a value the table stores as a half float (the unity-hdrp packing rounds
/// and clamps); throws if it is not one, so that no other table's numbers pass as HDRP's.
uint16_t exact_half_bits(double v, const std::string& channel) {
    const Imath::half h = Imath::half(float(v));
    if (!h.isFinite() || double(float(h)) != v)
        throw Error("the HDRP .cs file holds half floats; channel " + channel + " holds " + round_trip_text(v) +
                    ", which is not one: write it with lut ltc --preset unity-hdrp");
    return h.bits();
}

/// The texel's "// alpha = ..." and the row's "// cos theta = ..." numbers: the axis's parameter.
double axis_parameter(const Axis& a, int i) {
    return a.parameter.size() == size_t(a.size) ? a.parameter[size_t(i)] : a.coordinate[size_t(i)];
}

}  // namespace

namespace {

/// The header comment of an HDRP .cs file: what it replaces, how HDRP reads it, the description.
std::string unity_hdrp_comment(const Table& t, bool doubles) {
    const std::string w = std::to_string(t.width());
    std::ostringstream o;
    o << "// Unity HDRP's GGX LTC table, written by brdfbake " << BRDFBAKE_VERSION << " as HDRP's\n"
      << "// Runtime/Material/LTCAreaLight/Generated/LtcData.BRDF_GGX.cs"
      << (doubles ? " (the double form of HDRP from its 2021 LTC generator, pull\n"
                    "// request Unity-Technologies/Graphics#3957, until pull request #7929 of July 2023; LTCAreaLight.cs's "
                    "LoadLUT\n// uploads entries 0, 2, 4, 6 into slice 0 of _LtcData, R16G16B16A16_SFloat)."
                  : " (the ushort form of HDRP since 2023, pull\n"
                    "// request Unity-Technologies/Graphics#7929; LTCAreaLight.cs uploads it with SetPixelData into slice 0 "
                    "of\n// _LtcData, R16G16B16A16_SFloat).")
      << " To use it: replace that file's text by this file's (keep its .meta;\n// an HDRP package from the package "
         "cache must first be embedded in the project's Packages folder).\n// "
      << kUnityArray
      << (doubles ? "[a + " + w + " * t, r + 3 * c] = M^-1_rc / M^-1_22 (columns first; HDRP reads entries 0, 2, 4, 6 "
                    "into\n// invM._m00_m02_m11_m20 with _m22 = 1, clamped to 65504);"
                  : "[4 * (a + " + w + " * t) + c]: the half-float bits of M^-1 / M^-1_22 as (00, 20, 11, 02)\n"
                    "// for c = R, G, B, A (SampleLtcMatrix loads them into invM._m00_m02_m11_m20, _m22 = 1), clamped "
                    "to 65504;")
      << "\n// column a at perceptual roughness a / " << t.width() - 1 << ", row t at sqrt(1 - cos theta) = t / "
      << t.height() - 1 << ". HDRP takes the magnitude and Fresnel terms\n// from its FGD table: the table's "
      << "magnitude and fresnel channels are not written here.\n";
    if (t.width() != 64 || t.height() != 64)
        o << "// HDRP's texture is 64 x 64 (LTCAreaLight.k_LtcLUTResolution, LTC_LUT_SIZE): this table is " << w << " x "
          << t.height() << ",\n// which needs those changed.\n";
    return o.str() + description_comment(t, "// ");
}

}  // namespace

namespace {

/// Whether t holds the nine entries of the unity-hdrp-2021 packing (else the unity-hdrp packing's four half floats).
bool unity_hdrp_doubles(const Table& t) {
    return std::find(t.channels.begin(), t.channels.end(), kUnityArray + std::string(".8")) != t.channels.end();
}

/// The names of the HDRP array's channels in t's packing.
std::vector<std::string> unity_hdrp_channels(const Table& t) {
    std::vector<std::string> names;
    for (int k = 0; k < (unity_hdrp_doubles(t) ? 9 : 4); ++k) names.push_back(kUnityArray + ("." + std::to_string(k)));
    return names;
}

}  // namespace

void check_unity_hdrp_table(const Table& t) {
    const std::string format = "HDRP .cs file (Unity HDRP)";
    require_ltc_grid_table(t, format, unity_hdrp_channels(t), std::string("Unity HDRP's ") + kUnityArray,
                           unity_hdrp_doubles(t) ? "unity-hdrp-2021" : "unity-hdrp", "HDRP");
    // HDRP's array is the fit of its BRDF_GGX (Runtime/Material/LTCAreaLight/BRDF/BRDF_GGX.cs: GGX
    // D, height-correlated G2 = 1 / (1 + Lambda(V) + Lambda(L)), F = 1): brdfbake's default ggx.
    const auto model = t.attributes.find("model");
    if (model != t.attributes.end() && model->second != "ggx:shadowing=correlated")
        throw Error("an " + format + " holds " + kUnityArray + ", the fit of HDRP's GGX with height-correlated "
                    "shadowing (ggx:shadowing=correlated); this table's model is " + model->second +
                    ": write .exr or .csv");
}

std::string table_unity_hdrp_source(const Table& t) {
    check_unity_hdrp_table(t);
    const bool doubles = unity_hdrp_doubles(t);
    const std::vector<std::string> names = unity_hdrp_channels(t);
    const std::string w = std::to_string(t.width()), h = std::to_string(t.height());
    std::ostringstream o;
    o << unity_hdrp_comment(t, doubles) << "\nnamespace UnityEngine.Rendering.HighDefinition\n{\n"
      << "    internal partial class LTCAreaLight\n    {\n        internal static "
      << (doubles ? "double[,] " : "ushort[] ") << kUnityArray << " = new "
      << (doubles ? "double[" + w + " * " + h + ", 3 * 3]" : "ushort[" + w + " * " + h + " * 4]") << "\n        {";
    std::vector<const std::vector<double>*> ch;
    for (const std::string& name : names) ch.push_back(&channel_values(t, name));
    for (int j = 0; j < t.height(); ++j) {
        o << "\n            // t = " << j << ": cos theta = " << round_trip_text(axis_parameter(t.y, j)) << "\n";
        for (int i = 0; i < t.width(); ++i) {
            const size_t texel = size_t(j) * size_t(t.width()) + size_t(i);
            std::string line = doubles ? "            { " : "            ";
            for (size_t c = 0; c < names.size(); ++c)
                line += (doubles ? round_trip_text((*ch[c])[texel]) : std::to_string(exact_half_bits((*ch[c])[texel], names[c]))) +
                        (doubles && c + 1 == names.size() ? " }," : ", ");
            o << line << std::string(line.size() < 45 ? 45 - line.size() : 1, ' ') << "// a = " << i
              << ": alpha = " << round_trip_text(axis_parameter(t.x, i)) << "\n";
        }
    }
    o << "        };\n    }\n}\n";
    return o.str();
}

std::string table_cycles_tables(const Table& t, const std::string& symbol) {
    std::ostringstream o;
    o << "/* Written by brdfbake " << BRDFBAKE_VERSION
      << " in the syntax of Cycles' intern/cycles/scene/shader.tables: one float array per channel,\n"
      << " * index (z * " << t.height() << " + y) * " << t.width()
      << " + x, a row of x per line, a blank line between z-slices.\n"
      << description_comment(t, " * ") << " */\n\nCCL_NAMESPACE_BEGIN\n";
    const size_t n = size_t(t.width()) * size_t(t.image_height());
    for (size_t c = 0; c < t.channels.size(); ++c) {
        const std::string name = "table_" + symbol + (t.channels.size() > 1 ? "_" + c_identifier(t.channels[c]) : "");
        o << "\nstatic const float " << name << "[" << n << "] = {\n";
        for (size_t k = 0; k < n; ++k) {
            const bool row_start = k % size_t(t.width()) == 0;
            if (row_start && k > 0 && k % (size_t(t.width()) * size_t(t.height())) == 0) o << "\n";
            o << (row_start ? "  " : " ") << c_float_literal(t.values[c][k], true) << (k + 1 < n ? "," : "");
            if ((k + 1) % size_t(t.width()) == 0 || k + 1 == n) o << "\n";
        }
        o << "};\n";
    }
    o << "\nCCL_NAMESPACE_END\n";
    return o.str();
}

}  // namespace brdfbake

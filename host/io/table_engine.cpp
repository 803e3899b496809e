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
//    between z-slices, stored index (z * height + y) * width + x.
#include <Imath/half.h>

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

std::string table_threejs_module(const Table& t) {
    require_2d(t, "three.js DataTexture module");
    const size_t n = t.channels.size();
    const char* format = n == 1 ? "RedFormat" : n == 2 ? "RGFormat" : n == 4 ? "RGBAFormat" : nullptr;
    if (!format)
        throw Error("a three.js half-float DataTexture has 1, 2 or 4 channels (three.js has no RGB format); the " +
                    t.kind + " table has " + std::to_string(n) + ": write .exr or .npy");
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

std::string table_filament_include(const Table& t) {
    require_2d(t, "Filament dfg.inc");
    const size_t n = t.channels.size();
    if (n != 2 && n != 3)
        throw Error("Filament's dfg.inc holds 2 half floats per texel (3 with the cloth DFG); the " + t.kind +
                    " table has " + std::to_string(n) + " channels: write .exr or .npy");
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
            std::string literal = round_trip_text(t.values[c][k], true);
            if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
            const bool row_start = k % size_t(t.width()) == 0;
            if (row_start && k > 0 && k % (size_t(t.width()) * size_t(t.height())) == 0) o << "\n";
            o << (row_start ? "  " : " ") << literal << "f" << (k + 1 < n ? "," : "");
            if ((k + 1) % size_t(t.width()) == 0 || k + 1 == n) o << "\n";
        }
        o << "};\n";
    }
    o << "\nCCL_NAMESPACE_END\n";
    return o.str();
}

}  // namespace brdfbake

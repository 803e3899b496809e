// Lookup tables: axes with their texel convention (centres or edges), value channels, a per-texel
// error channel, the attributes that describe how the table was made, and the writers (OpenEXR,
// CSV, C/C++ header, 16-bit PNG, NumPy .npy, and the engines' own files: three.js's
// DFGLUTData.js, Filament's dfg.inc, Cycles' shader.tables).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace brdfbake {

/// Where the texels of an axis sit on its coordinate range [lo, hi] (lo > hi for a flipped axis).
enum class Texels {
    Centre,  // texel i at t = (i + 0.5) / size: the texel centres of a sampled texture
    Edge,    // texel i at t = i / (size - 1): the first and last texel on the range's ends
};

/// "centre" or "edge"; throws Error otherwise.
Texels parse_texels(const std::string& text);
const char* texels_name(Texels texels);

/// One table axis. Texel i sits at t_i of [0, 1] by the axis's texel convention; the axis
/// coordinate is lo + (hi - lo) t_i, and `mapping` turns the coordinate into the parameter
/// (e.g. alpha = coordinate^2 for the "roughness" mapping of alpha). A flipped axis has lo > hi:
/// its texel 0 holds the range's upper end.
struct Axis {
    std::string name;            // the coordinate's name: "mu", "sqrt_mu", "alpha", "roughness", "eta", "f0", ...
    std::string mapping;         // how coordinate -> parameter, in words: "mu = u", "mu = u^2", "alpha = r^2"
    std::string parameter_name;  // what the mapping yields ("mu", "alpha", "eta"); empty: the coordinate itself
    double lo = 0.0, hi = 1.0;
    int size = 1;
    Texels texels = Texels::Centre;
    std::vector<double> coordinate;  // per texel: lo + (hi - lo) t_i
    std::vector<double> parameter;   // per texel: the mapped parameter value
};

struct Table {
    std::string kind;      // "albedo", "eavg", "dfg", ...
    std::string quantity;  // what a texel holds, in words
    Axis x;                // width
    Axis y;                // height (size 1 for a 1D table)
    Axis z;                // depth (size 1 for a 2D table); 3D tables stack z-slices along y
    std::vector<std::string> channels;
    std::vector<std::vector<double>> values;  // [channel][(z * height + y) * width + x]
    std::vector<double> error;                // same layout: estimated absolute error (max over channels)
    std::map<std::string, std::string> attributes;  // model, fresnel, method, samples, precision, ...

    int width() const { return x.size; }
    int height() const { return y.size; }
    int depth() const { return z.size; }
    /// Rows of the stored image: the z-slices stacked along y.
    int image_height() const { return y.size * z.size; }
    double max_error() const;
};

/// An axis of `size` texels over the coordinate range [lo, hi] with the given texel convention
/// (throws Error for edge texels with size 1: one texel cannot sit on both ends).
Axis make_axis(const std::string& name, const std::string& mapping, double lo, double hi, int size,
               Texels texels = Texels::Centre);

/// Reorders the axes of a table: `order` names the axes (by Axis::name) in their new order x, y[, z]
/// (every axis of size > 1 once; empty: keep), and every axis named in `flip` is reversed (its
/// texel 0 then holds the range's upper end). Values and errors move with their texels. Throws
/// Error for an unknown or repeated name.
void arrange_axes(Table& table, const std::vector<std::string>& order, const std::vector<std::string>& flip);

/// The RGB(A) view of a table's value channels that the image formats share: slot s of
/// R, G, B, A holds value channel view[s], or nothing (-1: written as 0, or A absent). One
/// channel: R = G = B = it; two: R, G and B = 0; three: R, G, B; four: R, G, B, A. More than
/// four value channels have no view (empty).
std::vector<int> rgba_view(const Table& table);
/// "R = A, G = B, B = 0": the view in words, for the files' descriptions.
std::string rgba_view_text(const Table& table);

/// Whether the table was computed in double precision (its "precision" attribute): its text
/// outputs then print 17 significant digits where a float table's print at most 9.
bool is_double_table(const Table& table);
/// A value of the table in the shortest text that reads back as it at the table's precision
/// (round_trip_text in brdfbake/output.h).
std::string table_value_text(const Table& table, double value);

/// Checks that every value and error is finite; throws Error naming the first bad texel.
void check_finite(const Table& table);

/// Throws Error unless `path` ends in a table format write_table knows (.exr, .csv, .h, .hpp,
/// .png, .npy, .js, .inc, .tables, .cc, .c).
void check_table_path(const std::string& path);

/// check_table_path, then what the format of `path` refuses by the table's shape: its channels
/// (three.js: 1, 2 or 4; Filament: 2 or 3; PNG: at most 4; EEVEE and HDRP: their arrays' channels),
/// its z-slices, axes and model (the engines' grids); no value is read, so `shape` may be a table
/// without values (lut_table_shape, brdfbake/lut.h): a refusal before the compute. write_table runs
/// the same checks. Throws Error.
void check_table_format(const Table& shape, const std::string& path);
/// The checks of check_table_format per format (each writer runs its own).
void check_png_table(const Table& shape);
void check_threejs_table(const Table& shape);
void check_filament_table(const Table& shape);
void check_eevee_table(const Table& shape, bool legacy);
void check_unity_hdrp_table(const Table& shape);

/// Writes by the extension of `path`: .exr (float32, or half when `half`), .csv, .h/.hpp, .png
/// (16-bit), .npy (with its sidecar PATH.json), .js (table_threejs_module), .inc
/// (table_filament_include), .tables (table_cycles_tables, arrays named after the file's stem),
/// .cc and .c (table_eevee_source: Blender EEVEE, current and legacy).
/// Every write goes through a temporary file and a rename. Throws Error.
void write_table(const Table& table, const std::string& path, bool half = false);

/// The description every format carries, in a stable order: (key, text) pairs that the EXR
/// header stores as brdfbake:KEY attributes.
std::vector<std::pair<std::string, std::string>> table_description(const Table& table);

void write_exr(const Table& table, const std::string& path, bool half);
/// three.js's DFGLUTData.js form: an ES module of the table's half floats (Uint16Array DATA,
/// texel (x, y) at (y * width + x) * channels) whose getDFGLUT() returns a DataTexture (RedFormat,
/// RGFormat or RGBAFormat for 1, 2 or 4 channels; HalfFloatType; linear; clamped). Rows in
/// texture order: row 0 at the y axis's low end, a flipped axis written backwards (also along x).
/// Throws Error for a 3D table or 3 or more than 4 channels.
std::string table_threejs_module(const Table& table);
/// Filament's dfg.inc form (cmgen --ibl-dfg=dfg.inc): "0x%04x, " half floats, 2 or 3 per texel,
/// 4 texels per line, rows in GL order as table_threejs_module's, the description in // comments.
/// Throws Error for a 3D table or other than 2 or 3 channels.
std::string table_filament_include(const Table& table);
/// Cycles' shader.tables syntax: between CCL_NAMESPACE_BEGIN and CCL_NAMESPACE_END, one
/// `static const float table_SYMBOL[N]` (table_SYMBOL_CHANNEL for a table of several channels) per
/// value channel in the stored order, 9 significant digits, `f` literals; no error array.
std::string table_cycles_tables(const Table& table, const std::string& symbol);
/// Blender EEVEE's LTC arrays ltc_mat_ggx and ltc_mag_ggx from the eevee packing's channels
/// (ltc_mat_ggx.0-3, ltc_mag_ggx.0-1), `f` literals that read back as the table's floats: Blender
/// 4.2 and later (`legacy` false: in namespace blender::eevee::lut, `extern const float
/// ltc_mat_ggx[H][W][4] = {...};`, eevee_lut.hh's declarations) or legacy EEVEE, Blender 2.80 to 4.1
/// (flat `ltc_mat_ggx[W * H * 4]`, eevee_lut.h's). Throws Error for a table off EEVEE's grid (x =
/// roughness, y = sqrt_one_minus_mu, each 0 to 1 at edge texels) or without those channels.
std::string table_eevee_source(const Table& table, bool legacy);
/// Unity HDRP's Generated/LtcData.BRDF_GGX.cs from the unity-hdrp packing's channels
/// (s_LtcMatrixData_BRDF_GGX.0-3, half floats): namespace UnityEngine.Rendering.HighDefinition,
/// `internal partial class LTCAreaLight`, `internal static ushort[] s_LtcMatrixData_BRDF_GGX = new
/// ushort[W * H * 4]` of the values' binary16 bits, texel [4 (a + W t) + c]. Throws Error for a table
/// off HDRP's grid (EEVEE's), without those channels, or whose values are not half floats.
std::string table_unity_hdrp_source(const Table& table);
/// `v` as a C floating literal that reads back as v (as float(v), with the `f` suffix, when
/// `as_float`): round_trip_text with ".0" where it has no point or exponent (1.0f, never 1f, which C
/// rejects).
std::string c_float_literal(double v, bool as_float);
/// `text` fit for one // comment line: no line break inside, no final backslash.
std::string comment_line_text(const std::string& text);
/// `name` with every character a C identifier cannot hold replaced by '_'.
std::string c_identifier(const std::string& name);
std::string table_csv(const Table& table);
std::string table_header(const Table& table, const std::string& symbol);
/// 16-bit PNG: the RGB(A) view (rgba_view), each value v stored as round(v * 65535). Values must
/// lie in [0, 1]; a value outside by no more than its texel's error estimate is clamped, one
/// further out is refused (Error). The description is in tEXt chunks brdfbake:KEY. Throws Error.
void write_png16(const Table& table, const std::string& path);
/// NumPy .npy (format 1.0, '<f8', C order) of shape (x), (y, x) or (z, y, x) plus a last axis of
/// the value channels and the error, and the sidecar PATH.json (axes, channels, description).
void write_npy(const Table& table, const std::string& path);
/// The .npy array's shape: (x), (y, x) or (z, y, x) by the table's dimensions, then the channels
/// (value channels, then the error).
std::vector<size_t> npy_shape(const Table& table);

/// Reads back a table write_table wrote: .exr, .csv, .npy (with its PATH.json sidecar) or .png. Kind,
/// quantity, axes, channels, values, error and attributes come back; values of an EXR are its
/// float32 (or half) samples, of a CSV its printed digits (round_trip_text), of a PNG sample / 65535
/// exactly (its error: the description's max_error plus half a step, 0.5 / 65535, for every texel,
/// as a PNG stores no error channel). An axis's per-texel parameter
/// comes back from the EXR header (brdfbake:x_parameter_values), the .npy sidecar or the CSV's
/// parameter column, and equals the coordinate where the file has none. Throws Error for any
/// other file (only regular files are opened: a FIFO or device is refused before it is read),
/// one that is not a brdfbake table, and one whose parts disagree or hold what no table holds,
/// naming the field: a non-finite range, a size that is not a whole number, a
/// value or error that is NaN or infinite (or a negative error), a .npy whose header shape,
/// sidecar shape, dtype, axes or channels disagree with its description.
/// The kind is not checked here (the io layer knows no kinds): brdfbake::read_table
/// (brdfbake/table_kinds.h) reads through this and refuses a kind brdfbake does not write.
Table read_table_file(const std::string& path);

}  // namespace brdfbake

// Lookup tables: axes with their texel-centre convention, value channels, a per-texel error
// channel, the attributes that describe how the table was made, and the writers (OpenEXR, CSV,
// C/C++ header).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace brdfbake {

/// One table axis. Texel i sits at the texel centre t = (i + 0.5) / size of [0, 1]; the axis
/// coordinate is lo + (hi - lo) t, and `mapping` turns the coordinate into the parameter
/// (e.g. mu = coordinate^2 for the "sqrt" mapping of mu).
struct Axis {
    std::string name;     // "mu", "alpha", "eta"
    std::string mapping;  // how coordinate -> parameter, in words: "mu = u", "mu = u^2", "alpha = r^2"
    double lo = 0.0, hi = 1.0;
    int size = 1;
    std::vector<double> coordinate;  // per texel: lo + (hi - lo)(i + 0.5)/size
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

/// An axis of `size` texels over the coordinate range [lo, hi] with texel centres.
Axis make_axis(const std::string& name, const std::string& mapping, double lo, double hi, int size);

/// Checks that every value and error is finite; throws Error naming the first bad texel.
void check_finite(const Table& table);

/// Throws Error unless `path` ends in a table format write_table knows (.exr, .csv, .h, .hpp).
void check_table_path(const std::string& path);

/// Writes by the extension of `path`: .exr (float32, or half when `half`), .csv, .h/.hpp.
/// Every write goes through a temporary file and a rename. Throws Error.
void write_table(const Table& table, const std::string& path, bool half = false);

void write_exr(const Table& table, const std::string& path, bool half);
std::string table_csv(const Table& table);
std::string table_header(const Table& table, const std::string& symbol);

}  // namespace brdfbake

#include "models/spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>

#include "brdfbake/error.h"
#include "engine/embedded_sources.h"
#include "models/csv_text.h"

namespace brdfbake {

namespace {

/// The rows of an embedded CSV (its "# " lines and header read by CsvText): its columns.
std::vector<std::vector<double>> read_embedded_csv(const std::string& key) {
    const char* text = embedded_source(key);
    if (!text) throw Error("the embedded table '" + key + "' is missing from this build");
    const std::string whole = text;
    CsvText csv(whole);
    std::vector<std::vector<double>> rows;
    for (std::vector<std::string> cells; csv.next_row(cells);) {
        std::vector<double> row;
        for (const std::string& cell : cells) row.push_back(std::strtod(cell.c_str(), nullptr));
        rows.push_back(row);
    }
    return rows;
}

/// D65 (5 nm steps) linearly interpolated at `nm`.
double d65_at(const std::vector<std::vector<double>>& d65, double nm) {
    const double first = d65.front()[0], step = d65[1][0] - d65[0][0];
    const double t = (nm - first) / step;
    const size_t i = std::min(size_t(t), d65.size() - 2);
    const double f = t - double(i);
    return d65[i][1] * (1.0 - f) + d65[i + 1][1] * f;
}

using Matrix = std::array<std::array<double, 3>, 3>;

Matrix inverse(const Matrix& m) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Matrix r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // The cofactor of m[j][i] over det (the adjugate's transpose).
            const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
    return r;
}

/// a * b.
Matrix product(const Matrix& a, const Matrix& b) {
    Matrix r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
    return r;
}

/// XYZ -> RGB of the primaries `prim` (x, y each) and the white point `white_xyz`: the primaries'
/// XYZ (x/y, 1, z/y) as columns, scaled so that they sum to the white point (SMPTE RP 177 /
/// IEC 61966-2-1's construction); the inverse maps XYZ to RGB.
Matrix xyz_to_rgb(const double (&prim)[3][2], const std::array<double, 3>& white_xyz) {
    Matrix p;
    for (int c = 0; c < 3; ++c) {
        const double x = prim[c][0], y = prim[c][1];
        p[0][c] = x / y;
        p[1][c] = 1.0;
        p[2][c] = (1.0 - x - y) / y;
    }
    const Matrix pi = inverse(p);
    std::array<double, 3> s{};
    for (int i = 0; i < 3; ++i) s[i] = pi[i][0] * white_xyz[0] + pi[i][1] * white_xyz[1] + pi[i][2] * white_xyz[2];
    Matrix rgb_to_xyz;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rgb_to_xyz[r][c] = p[r][c] * s[c];
    return inverse(rgb_to_xyz);
}

/// XYZ -> ACEScg: Bradford from `white_xyz` to the ACES white, then AP1 (spectrum.h).
Matrix xyz_to_acescg(const std::array<double, 3>& white_xyz) {
    const Matrix bradford = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    const double wx = 0.32168, wy = 0.33767;
    const std::array<double, 3> aces_white = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
    Matrix scale{};
    for (int i = 0; i < 3; ++i) {
        double from = 0.0, to = 0.0;
        for (int k = 0; k < 3; ++k) {
            from += bradford[i][k] * white_xyz[k];
            to += bradford[i][k] * aces_white[k];
        }
        scale[i][i] = to / from;
    }
    const Matrix adapt = product(inverse(bradford), product(scale, bradford));
    const double ap1[3][2] = {{0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044}};
    return product(xyz_to_rgb(ap1, aces_white), adapt);
}

/// The observer's colour-matching functions by wavelength and D65, parsed once from the embedded
/// CSVs (every colour space and step reads them).
struct ObserverData {
    std::map<int, std::array<double, 3>> xyz_bar;
    std::vector<std::vector<double>> d65;
};

const ObserverData& observer_data() {
    static const ObserverData data = [] {
        ObserverData o;
        for (const auto& r : read_embedded_csv("cie/cie1931_2deg_1nm.csv"))
            o.xyz_bar[int(std::lround(r[0]))] = {r[1], r[2], r[3]};
        o.d65 = read_embedded_csv("cie/cie_d65.csv");
        return o;
    }();
    return data;
}

SpectralWeights make_weights(int step_nm, Matrix (*to_rgb)(const std::array<double, 3>&)) {
    const auto& xyz_bar = observer_data().xyz_bar;
    const auto& d65 = observer_data().d65;
    SpectralWeights w;
    std::vector<std::array<double, 3>> xyz;
    double y_sum = 0.0;
    for (int nm = 380; nm <= 780; nm += step_nm) {
        const double e = d65_at(d65, nm);
        const auto& b = xyz_bar.at(nm);
        xyz.push_back({b[0] * e, b[1] * e, b[2] * e});
        y_sum += b[1] * e;
        w.nm.push_back(nm);
    }
    for (auto& v : xyz)
        for (int c = 0; c < 3; ++c) {
            v[c] /= y_sum;
            w.white_xyz[c] += v[c];
        }
    const Matrix m = to_rgb(w.white_xyz);
    for (const auto& v : xyz) {
        std::array<double, 3> rgb{};
        for (int i = 0; i < 3; ++i) rgb[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
        w.rgb.push_back(rgb);
    }
    return w;
}

}  // namespace

std::array<std::array<double, 3>, 3> xyz_to_linear_srgb(const std::array<double, 3>& white_xyz) {
    const double srgb[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    return xyz_to_rgb(srgb, white_xyz);
}

const SpectralWeights& colour_weights(const std::string& colour_space, int step_nm) {
    using Weights = std::map<std::pair<std::string, int>, SpectralWeights>;
    static const Weights all = [] {
        Weights m;
        for (int s : {1, 2, 4, 5}) {
            m[{"srgb", s}] = make_weights(s, xyz_to_linear_srgb);
            m[{"acescg", s}] = make_weights(s, xyz_to_acescg);
        }
        return m;
    }();
    if (colour_space != "srgb" && colour_space != "acescg")
        throw Error("unknown colour space '" + colour_space + "'; known: srgb, acescg");
    const auto it = all.find({colour_space, step_nm});
    if (it == all.end()) throw Error("spectral weights exist at 1, 2, 4 and 5 nm steps, not " + std::to_string(step_nm));
    return it->second;
}

const std::vector<std::array<double, 4>>& cie_observer() {
    static const std::vector<std::array<double, 4>> rows = [] {
        std::vector<std::array<double, 4>> r;
        for (const auto& kv : observer_data().xyz_bar) r.push_back({double(kv.first), kv.second[0], kv.second[1], kv.second[2]});
        return r;
    }();
    return rows;
}

std::string colour_space_text(const std::string& colour_space) {
    return std::string(colour_space == "acescg" ? "ACEScg (AP1 primaries, ACES white (about D60) by Bradford from D65; "
                                                  "white = 1, 1, 1)"
                                                : "linear sRGB (D65 white = 1, 1, 1)") +
           ", CIE 1931 2-degree observer, illuminant D65, 380-780 nm summed at 1 nm";
}

unsigned char srgb_encode_8bit(double linear) {
    const double v = std::min(1.0, std::max(0.0, std::isfinite(linear) ? linear : 0.0));
    const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(255.0 * encoded));
}

const SpectralWeights& srgb_weights(int step_nm) { return colour_weights("srgb", step_nm); }

}  // namespace brdfbake

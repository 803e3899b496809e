// Colour from spectra: the CIE 1931 2-degree observer under illuminant D65 (data/cie/, embedded),
// as weights that turn a reflectance sampled over the visible spectrum into linear sRGB.
#pragma once

#include <array>
#include <vector>

namespace brdfbake {

/// rgb = sum_i weights[i] * R(nm[i]) is the linear-sRGB colour of a surface of spectral
/// reflectance R lit by D65 and seen by the CIE 1931 2-degree observer, normalised so that a
/// perfect white (R = 1 everywhere) is (1, 1, 1). The weights are the colour-matching functions
/// times D65 (Riemann sums at `step_nm`), the XYZ -> linear-sRGB matrix built from the sRGB
/// primaries (IEC 61966-2-1: r 0.64, 0.33; g 0.30, 0.60; b 0.15, 0.06) and the white point the
/// same sums give (x = 0.3127, y = 0.3290), so white maps to white exactly.
struct SpectralWeights {
    std::vector<double> nm;                  // 380, 380 + step, ..., 780
    std::vector<std::array<double, 3>> rgb;  // per wavelength
    std::array<double, 3> white_xyz{};       // D65's XYZ under the observer, Y = 1
};

/// The weights at 1, 2, 4 or 5 nm steps (throws Error for another step).
const SpectralWeights& srgb_weights(int step_nm);

/// The 3x3 XYZ -> linear-sRGB matrix for the white point `white_xyz` (rows: R, G, B).
std::array<std::array<double, 3>, 3> xyz_to_linear_srgb(const std::array<double, 3>& white_xyz);

}  // namespace brdfbake

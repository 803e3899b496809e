// Colour from spectra: the CIE 1931 2-degree observer under illuminant D65 (data/cie/, embedded),
// as weights that turn a reflectance sampled over the visible spectrum into linear sRGB.
#pragma once

#include <array>
#include <string>
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

/// ACEScg (colour_weights("acescg", step)) follows S-2014-004 "ACEScg - A Working Space for CGI Render and Compositing",
/// sec. 4.3: the AP1 primaries r 0.713, 0.293; g 0.165, 0.830; b 0.128, 0.044 and the ACES white
/// x = 0.32168, y = 0.33767 of TB-2018-001). The colour under D65 is carried to the ACES white by
/// the Bradford transform (Lam 1985; the matrix of ICC.1:2010 Annex E), applied as a von Kries
/// scaling in its cone space from the sums' own D65 white, so that a perfect white is (1, 1, 1) in
/// ACEScg too. The choice: OpenColorIO's ACES configurations convert linear sRGB to ACEScg with
/// Bradford; colour-science's spectral route to ACES2065-1 defaults to CAT02 (the two differ by
/// about 1e-3 on saturated colours).
///
/// The weights of a colour space by name: "srgb" or "acescg" (throws Error for another).
const SpectralWeights& colour_weights(const std::string& colour_space, int step_nm);

/// How colour_weights(colour_space, 1) makes its colour, in words for headers and outputs: the
/// space ("linear sRGB" or "ACEScg ..."), its white, the observer, the illuminant and the sums.
std::string colour_space_text(const std::string& colour_space);

/// The sRGB encoding of a linear-sRGB value (IEC 61966-2-1:1999, sec. 5.2: 12.92 v up to
/// 0.0031308, 1.055 v^(1/2.4) - 0.055 above) as an 8-bit level, round(255 V); values outside
/// [0, 1] (a colour outside sRGB's gamut, or brighter than white) are clipped first.
unsigned char srgb_encode_8bit(double linear);

/// The embedded CIE 1931 2-degree observer (data/cie/cie1931_2deg_1nm.csv): nm, x-bar, y-bar, z-bar.
const std::vector<std::array<double, 4>>& cie_observer();

/// The 3x3 XYZ -> linear-sRGB matrix for the white point `white_xyz` (rows: R, G, B).
std::array<std::array<double, 3>, 3> xyz_to_linear_srgb(const std::array<double, 3>& white_xyz);

}  // namespace brdfbake

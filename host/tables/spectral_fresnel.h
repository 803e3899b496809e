// A Fresnel term that depends on the wavelength (metal:X, nk:FILE, thin-film) as a table's colour
// channels. The albedo is linear in F and F depends on the angle alone, so the spectral integral
// of the albedo per colour channel c is the albedo at the curve
//   F_c(cos) = sum_lambda w_c(lambda) F(lambda, cos)
// (w_c: the colour-matching functions under D65 turned into the colour space's channel,
// models/spectrum.h). Each curve is tabulated on the device (fresnel_rgb_on_device) and
// integrated as a BB_FRESNEL_TABLE term (brdf/fresnel.h): three integrations, not one per
// wavelength. Each channel's error adds to the integration's two bounds, each a largest
// difference over cos in F_c, which bounds the albedo's (|dE| <= max |dF| times the albedo at
// F = 1, <= 1 for the energy-conserving lobes):
//   the curve's: its linear interpolant against F_c at the midpoints between nodes (where a
//                linear interpolant's error peaks, to leading order h^2/8 |F''|);
//   the spectrum's: the 1 nm sum against the 2 nm one (as `fresnel --rgb` reports it).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/engine.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"

namespace brdfbake {
namespace tables {

/// Nodes of each channel's curve over cos in [0, 1] (uniform).
constexpr int kSpectralCurveNodes = 1025;

/// Whether a request's channels are the colour of its Fresnel term: a term that depends on the
/// wavelength, no --wavelength, and not --rgb-wavelengths.
bool spectral_colour(const LutRequest& r);
/// Whether a request asks for the old three channels at 650, 550 and 450 nm (--rgb-wavelengths).
bool rgb_wavelengths(const LutRequest& r);

/// The three channels' curves of a spectral Fresnel term.
struct SpectralCurves {
    std::array<FresnelConfig, 3> channel;      // BB_FRESNEL_TABLE, with their curves
    std::array<double, 3> curve_error{};       // max over the midpoints of |interpolant - F_c|
    std::array<double, 3> spectral_error{};    // max over cos of |1 nm sum - 2 nm sum|
    std::string colour;                        // how the channels were made, for the table's header
};

/// The curves of `fresnel_spec` in the colour space `colour` ("srgb" or "acescg").
SpectralCurves spectral_curves(Engine& engine, const std::string& fresnel_spec, const std::string& colour,
                               Precision precision);

/// The channel names of a colour request: R, G, B.
const std::vector<std::string>& colour_channel_names();

/// The cells integrated once per channel of `curves`: values[channel][cell], and per cell the
/// largest channel's error, each channel's being its integration's plus its curve's and its
/// spectrum's. With a tolerance, the integration gets what those two leave of it (Error when they
/// take more than three quarters). Returns the last integration (its method and samples).
AlbedoResult integrate_colour(Engine& engine, const LutRequest& r, const ModelConfig& m, const SpectralCurves& curves,
                              const std::vector<AlbedoCell>& cells, std::vector<std::vector<double>>& values,
                              std::vector<double>& error);

}  // namespace tables
}  // namespace brdfbake

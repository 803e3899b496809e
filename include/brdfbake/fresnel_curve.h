// A Fresnel term evaluated on the device (kernels/fresnel.cl) at a list of cosines: the
// reflectance F and its two polarisations, the values `brdfbake fresnel` prints and plots.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace brdfbake {

struct FresnelCurves {
    std::vector<double> f, rs, rp;  // per cosine: unpolarised, s- and p-polarised reflectance
};

/// F, Rs and Rp of `fresnel` at each cos(theta) in [0, 1], computed by the Fresnel kernel in
/// `precision`. Throws Error for a cosine outside [0, 1] or a non-finite value from the kernel.
FresnelCurves fresnel_on_device(Engine& engine, const FresnelConfig& fresnel, Precision precision,
                                const std::vector<double>& cosines);

/// The colour of a Fresnel term's reflectance at each cos(theta): F over the visible spectrum
/// (380 to 780 nm at 1 nm, the spec resolved at each, one kernel launch for them all) weighed
/// by the CIE 1931 2-degree observer under D65 into linear sRGB (white = (1, 1, 1); see
/// models/spectrum.h). `error` is |sum at 1 nm - sum at 2 nm| per channel: the CIE defines
/// colorimetry by the 1 nm sum, and the 2 nm one shows how far the spectrum's sampling matters.
/// `colour_space` "acescg" gives ACEScg instead (models/spectrum.h).
struct FresnelColour {
    std::vector<std::array<double, 3>> rgb, error;  // per cosine
    int wavelengths = 0;                              // wavelengths summed
    int launches = 0;                                 // kernel launches (one per kind of term: 1)
};
FresnelColour fresnel_rgb_on_device(Engine& engine, const std::string& fresnel_spec, Precision precision,
                                    const std::vector<double>& cosines, const std::string& colour_space = "srgb");

}  // namespace brdfbake

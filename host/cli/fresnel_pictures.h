// The colour pictures of `brdfbake fresnel --rgb --swatch FILE.png`: metal swatches (one row per
// Fresnel spec, one swatch per angle) and a thin film's iridescence map (colour over the angle of
// incidence and the film's thickness). Each colour is the spectral colour in linear sRGB
// (fresnel_rgb_on_device) encoded as sRGB, 8 bits (srgb_encode_8bit): what a browser or an image
// viewer shows as that reflectance under D65. A PNG holds those levels exactly (ColourCell).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/fresnel_curve.h"

namespace brdfbake {

/// Swatches of each spec's colour at `thetas` (degrees): a row per spec, titled with it, each
/// swatch labelled with its angle. `colours[s].rgb` holds spec s's colour at each angle.
void write_swatches(const std::string& path, const std::vector<std::pair<std::string, FresnelColour>>& colours,
                    const std::vector<double>& thetas);

/// The iridescence map of a thin-film spec: its colour over theta in [0, 90] at 1 degree (x)
/// and the film's thickness over [lo_nm, hi_nm] (y, `rows` thicknesses), one launch per thickness.
/// Returns the largest spectral error (|1 nm - 2 nm sum|) over the map.
double write_iridescence_map(Engine& engine, const std::string& path, const std::string& thin_film_spec, double lo_nm,
                             double hi_nm, Precision precision, int rows = 121);

}  // namespace brdfbake

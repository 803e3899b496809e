// A spectral Fresnel term as three tabulated colour curves (tables/spectral_fresnel.h).
#include "tables/spectral_fresnel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_curve.h"
#include "brdfbake/fresnel_terms.h"
#include "models/key_reader.h"
#include "models/spectrum.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {

namespace {

/// FNV-1a over the values' bits, in 52 bits (a double holds it exactly): the curve's identity in
/// its parameters, so that two channels' launches differ in their settings (distributed_compute
/// keys its records by them).
double curve_id(const std::vector<double>& values) {
    std::uint64_t h = 1469598103934665603ull;
    for (double v : values) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
    }
    return double(h & ((std::uint64_t(1) << 52) - 1));
}

}  // namespace

bool rgb_wavelengths(const LutRequest& r) { return r.colour == "wavelengths"; }

bool spectral_colour(const LutRequest& r) {
    return r.wavelength_nm == 0.0 && fresnel_needs_wavelength(r.fresnel) && !rgb_wavelengths(r);
}

const std::vector<std::string>& colour_channel_names() {
    static const std::vector<std::string> names = {"R", "G", "B"};
    return names;
}

SpectralCurves spectral_curves(Engine& engine, const std::string& fresnel_spec, const std::string& colour,
                               Precision precision) {
    const int n = kSpectralCurveNodes;
    std::vector<double> cosines;
    for (int i = 0; i < n; ++i) cosines.push_back(double(i) / double(n - 1));
    for (int i = 0; i + 1 < n; ++i) cosines.push_back((i + 0.5) / double(n - 1));
    // The curves in double where the device has it: they are tabulated once and read by every
    // cell, so their rounding should stay below the tables' float rounding.
    const Precision p = engine.device().fp64 ? Precision::Double : precision;
    const FresnelColour c = fresnel_rgb_on_device(engine, fresnel_spec, p, cosines, colour);
    SpectralCurves s;
    s.colour = colour_space_text(colour);
    for (int ch = 0; ch < 3; ++ch) {
        FresnelConfig& f = s.channel[size_t(ch)];
        f.kind = BB_FRESNEL_TABLE;
        for (int i = 0; i < n; ++i) f.curve.push_back(c.rgb[size_t(i)][size_t(ch)]);
        for (const auto& e : c.error) s.spectral_error[size_t(ch)] = std::max(s.spectral_error[size_t(ch)], e[size_t(ch)]);
        for (int i = 0; i + 1 < n; ++i) {
            const double mid = c.rgb[size_t(n + i)][size_t(ch)];
            const double lerp = 0.5 * (f.curve[size_t(i)] + f.curve[size_t(i + 1)]);
            s.curve_error[size_t(ch)] = std::max(s.curve_error[size_t(ch)], std::fabs(mid - lerp));
        }
        f.params[BB_FRESNEL_TABLE_NODES] = double(n);
        f.params[BB_FRESNEL_TABLE_ID] = curve_id(f.curve);
        f.canonical = fresnel_spec + " " + colour_channel_names()[size_t(ch)] + " in " + s.colour;
    }
    return s;
}

AlbedoResult integrate_colour(Engine& engine, const LutRequest& r, const ModelConfig& m, const SpectralCurves& curves,
                              const std::vector<AlbedoCell>& cells, std::vector<std::vector<double>>& values,
                              std::vector<double>& error) {
    values.assign(3, {});
    error.assign(cells.size(), 0.0);
    AlbedoResult last;
    for (size_t ch = 0; ch < 3; ++ch) {
        const double own = curves.curve_error[ch] + curves.spectral_error[ch];
        double share = 1.0;
        if (r.tolerance.tolerance > 0.0) {
            share = 1.0 - own / r.tolerance.tolerance;
            if (share < 0.25)
                throw Error("--tolerance " + format_number(r.tolerance.tolerance) + " is below what the spectral colour " +
                            "itself allows in channel " + colour_channel_names()[ch] + ": its curve's error " +
                            format_number(curves.curve_error[ch]) + " and its 1 nm vs 2 nm spectral sums' " +
                            format_number(curves.spectral_error[ch]) + " (ask for at least " +
                            format_number(4.0 * own) + ", or give --wavelength NM)");
        }
        last = integrate(engine, r, m, curves.channel[ch], cells, share);
        for (size_t k = 0; k < cells.size(); ++k) {
            values[ch].push_back(last.values[k].value);
            error[k] = std::max(error[k], last.values[k].error + own);
        }
    }
    return last;
}

}  // namespace tables
}  // namespace brdfbake

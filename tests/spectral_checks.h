// The gap between the 1 nm and 5 nm colour of a spectral Fresnel term, on the host in double:
// how far a brute-force sum of single-wavelength tables at 5 nm may be from a table's 1 nm colour
// (test_fresnel_tables.cpp, test_thin_film_table.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/spec.h"
#include "models/spectrum.h"

namespace testing {

/// max over cos in [0, 1] of |F_c at 1 nm - F_c at 5 nm| for each channel, F evaluated on the
/// host in double: how far a 5 nm brute-force sum may be from the 1 nm colour.
inline std::array<double, 3> step_difference(const std::string& fresnel) {
    const brdfbake::SpectralWeights& fine = brdfbake::srgb_weights(1);
    const brdfbake::SpectralWeights& coarse = brdfbake::srgb_weights(5);
    std::array<double, 3> worst{};
    const auto at = brdfbake::fresnel_over_wavelengths(fresnel);
    std::vector<brdfbake::FresnelConfig> f;
    for (double nm : fine.nm) f.push_back(at(nm));
    for (int i = 0; i <= 200; ++i) {
        const double c = i / 200.0;
        std::array<double, 3> a{}, b{};
        for (size_t k = 0; k < fine.nm.size(); ++k) {
            const double v = brdfbake::fresnel_value(f[k], c);
            for (int ch = 0; ch < 3; ++ch) {
                a[ch] += fine.rgb[k][ch] * v;
                if ((k % 5) == 0) b[ch] += coarse.rgb[k / 5][ch] * v;
            }
        }
        for (int ch = 0; ch < 3; ++ch) worst[ch] = std::max(worst[ch], std::fabs(a[ch] - b[ch]));
    }
    return worst;
}

}  // namespace testing

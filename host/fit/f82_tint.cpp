#include "fit/f82_tint.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/fresnel_curve.h"

namespace brdfbake {
namespace fit {

F82TintFit fit_f82_tint(Engine& engine, const std::string& fresnel_spec, Precision precision) {
    // cos(theta) on a 0.25 degree grid (theta = 0 first), then mu_bar.
    const int steps = 360;
    const double mu_bar = 1.0 / 7.0;
    std::vector<double> cosines, thetas;
    for (int i = 0; i <= steps; ++i) {
        thetas.push_back(90.0 * i / steps);
        cosines.push_back(std::sin((90.0 - thetas.back()) * M_PI / 180.0));
    }
    cosines.push_back(mu_bar);
    const FresnelColour c = fresnel_rgb_on_device(engine, fresnel_spec, precision, cosines);
    F82TintFit r;
    for (int ch = 0; ch < 3; ++ch) {
        const double f0 = c.rgb[0][ch];
        r.f0[ch] = f0;
        r.tint[ch] = c.rgb.back()[ch] / bb_fresnel_schlick(mu_bar, f0);
        const double b = bb_f82_tint_b(f0, r.tint[ch]);
        for (size_t i = 0; i + 1 < cosines.size(); ++i) {
            const double d = std::fabs(bb_fresnel_gen_schlick(cosines[i], f0, 1.0, 5.0, b) - c.rgb[i][ch]);
            if (d > r.max_error[ch]) r.max_error[ch] = d, r.max_error_theta_deg[ch] = thetas[i];
            r.colour_error[ch] = std::max(r.colour_error[ch], c.error[i][ch]);
        }
    }
    return r;
}

}  // namespace fit
}  // namespace brdfbake

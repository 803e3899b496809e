// The README's picture of LTC fits (issue 33 item 8): at a few texels (mu, alpha) of GGX, the
// normalised lobe p = f cos(theta_i) / E in the plane of incidence beside the LTC D that brdfbake
// fits to it (host/fit/ltc_fit.h, on the device). p comes from the textbook GGX of
// benchmarks/reference/reference.h (Walter et al. 2007, height-correlated G2; Heitz 2014), not from
// the engine, and E from the fit's own sample points. Usage: brdfbake-ltc-lobes OUT.png
#include <cmath>
#include <cstdio>
#include <string>

#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "fit/ltc_fit.h"
#include "plot/plot.h"
#include "reference/reference.h"

using namespace brdfbake;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: brdfbake-ltc-lobes OUT.png\n");
        return 2;
    }
    try {
        Engine engine;
        const double kPi = 3.14159265358979323846;
        const double texels[][2] = {{0.9, 0.15}, {0.5, 0.3}, {0.2, 0.3}, {0.5, 0.7}};
        Figure figure;
        figure.columns = 2;
        for (const auto& tx : texels) {
            const double mu = tx[0], alpha = tx[1];
            const ModelConfig m = resolve_model("ggx:alpha=" + std::to_string(alpha));
            fit::LtcFitOptions options;
            const fit::LtcFit f = fit::fit_ltc_rows(engine, m, {{{mu, m.params}}}, options)[0][0];
            const ref::Dir wo{std::sqrt(1 - mu * mu), 0, mu};
            Curve lobe{"p = f cos / E (GGX)", {}, {}, "b-3"}, ltc{"D (the fitted LTC)", {}, {}, "r;3"};
            for (int k = 0; k <= 720; ++k) {
                const double t = -0.5 * kPi + kPi * k / 720.0;  // theta_i, signed: + on the viewer's side
                const std::array<double, 3> w = {std::sin(t), 0.0, std::cos(t)};
                const double p = double(ref::ggx_f(wo, {w[0], w[1], w[2]}, alpha, alpha, true)) * w[2] / f.albedo;
                lobe.x.push_back(t * 180 / kPi);
                lobe.y.push_back(p);
                ltc.x.push_back(t * 180 / kPi);
                ltc.y.push_back(fit::ltc_density(f.m, w));
            }
            PlotSpec panel;
            char title[160];
            std::snprintf(title, sizeof title, "\\mu_o = %.2f, \\alpha = %.2f: L1 distance %.3f", mu, alpha, f.distance);
            panel.title = title;
            panel.x = {"signed \\theta_i in the plane of incidence (degrees; the viewer at +)", -90, 90, 30};
            panel.y = {"density (1/sr)"};
            panel.y.lo = 0;
            panel.curves = {lobe, ltc};
            panel.lines = {{'x', -std::acos(mu) * 180 / kPi, "mirror"}};
            figure.panels.push_back(panel);
        }
        figure.caption = "GGX lobes (blue) and brdfbake's LTC fits (red, dashed), in the plane of incidence";
        write_figure(argv[1], figure);
        std::printf("wrote %s\n", argv[1]);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "brdfbake-ltc-lobes: error: %s\n", e.what());
        return 1;
    }
}

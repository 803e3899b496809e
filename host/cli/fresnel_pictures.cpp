// Colour pictures of Fresnel terms (cli/fresnel_pictures.h).
#include "cli/fresnel_pictures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "models/spectrum.h"
#include "plot/plot.h"
#include "tables/lut_common.h"

namespace brdfbake {

namespace {

ColourCell cell_of(const std::array<double, 3>& linear, double x0, double x1, double y0, double y1) {
    ColourCell c;
    c.x0 = x0, c.x1 = x1, c.y0 = y0, c.y1 = y1;
    for (int ch = 0; ch < 3; ++ch) c.rgb[ch] = srgb_encode_8bit(linear[size_t(ch)]);
    return c;
}

std::string angle_label(double theta) {
    char text[32];
    std::snprintf(text, sizeof text, "%g\\degree", theta);
    return text;
}

const char kEncoding[] = "linear sRGB (CIE 1931, D65) encoded as sRGB, 8 bits, clipped to [0, 1]";

}  // namespace

void write_swatches(const std::string& path, const std::vector<std::pair<std::string, FresnelColour>>& colours,
                    const std::vector<double>& thetas) {
    Figure fig;
    fig.columns = 1;
    const int n = int(thetas.size());
    fig.panel_width = std::max(600, 90 * n);
    fig.panel_height = 200;
    for (const auto& [spec, colour] : colours) {
        PlotSpec p;
        p.axes = false;
        p.title = plot_text(short_numbers(spec));  // each row's label; the figure's caption says what all show
        // Swatch i over [i + 0.06, i + 0.94] x [0, 1] on a mid-grey strip (where white and light
        // metals stand out), its angle below it.
        p.x = PlotAxis{"", 0.0, double(n), 0.0};
        p.y = PlotAxis{"", -0.3, 1.05, 0.0};
        ColourCell strip;
        strip.x0 = 0.0, strip.x1 = double(n), strip.y0 = -0.05, strip.y1 = 1.05;
        strip.rgb[0] = strip.rgb[1] = strip.rgb[2] = 119;  // sRGB 119: linear 0.18, photographers' mid grey
        p.cells.push_back(strip);
        for (int i = 0; i < n; ++i) {
            ColourCell c = cell_of(colour.rgb[size_t(i)], i + 0.06, i + 0.94, 0.0, 1.0);
            c.label = angle_label(thetas[size_t(i)]);
            p.cells.push_back(c);
        }
        fig.panels.push_back(p);
    }
    fig.caption = std::string("the reflectance at each angle (below each swatch), ") + kEncoding;
    write_figure(path, fig);
}

double write_iridescence_map(Engine& engine, const std::string& path, const std::string& thin_film_spec, double lo_nm,
                             double hi_nm, Precision precision, int rows) {
    std::vector<double> cosines;
    for (int t = 0; t <= 90; ++t) cosines.push_back(std::sin((90.0 - t) * M_PI / 180.0));
    PlotSpec p;
    p.title = plot_text(short_numbers(thin_film_spec)) + " over the film's thickness";
    p.x = PlotAxis{"angle of incidence \\theta  (degrees)", 0.0, 90.0, 15.0};
    // Ticks at a round step giving 4 to 10 of them (MathGL's automatic ticks factor out a power of ten).
    const double span = hi_nm - lo_nm, unit = std::pow(10.0, std::floor(std::log10(span)));
    const double tick = span / unit >= 5.0 ? unit : span / unit >= 2.0 ? unit / 2.0 : unit / 5.0;
    p.y = PlotAxis{"film thickness (nm)", lo_nm, hi_nm, tick};
    const double step = rows > 1 ? (hi_nm - lo_nm) / (rows - 1) : 1.0;
    double worst = 0.0;
    for (int j = 0; j < rows; ++j) {
        const double d = lo_nm + step * j;
        const FresnelColour c = fresnel_rgb_on_device(engine, tables::thin_film_at(thin_film_spec, d), precision, cosines);
        for (const auto& e : c.error) worst = std::max({worst, e[0], e[1], e[2]});
        for (int t = 0; t <= 90; ++t)
            p.cells.push_back(cell_of(c.rgb[size_t(t)], std::max(0.0, t - 0.5), std::min(90.0, t + 0.5),
                                      std::max(lo_nm, d - 0.5 * step), std::min(hi_nm, d + 0.5 * step)));
    }
    p.legend = LegendPlace::None;
    Figure fig;
    fig.panels.push_back(p);
    fig.panel_width = 900;
    fig.panel_height = 700;
    fig.caption = "linear sRGB (CIE 1931, D65) encoded as sRGB, 8 bits";
    write_figure(path, fig);
    return worst;
}

}  // namespace brdfbake

// PNG/SVG previews of tables: a heatmap per channel with axes and a colour bar (2D and 3D
// tables; a 3D table shows its middle z-slice), or curves for a 1D table.
#include <algorithm>
#include <cstdio>

#include "brdfbake/table.h"
#include "plot/plot.h"

namespace brdfbake {

void write_table_preview(const Table& table, const std::string& path) {
    // The picture runs every axis upwards: a flipped axis (lo > hi) is drawn unflipped.
    Table t = table;
    std::vector<std::string> flipped;
    for (const Axis* a : {&t.x, &t.y, &t.z})
        if (a->lo > a->hi && a->size > 1) flipped.push_back(a->name);
    arrange_axes(t, {}, flipped);
    Figure fig;
    if (t.height() == 1 && t.depth() == 1) {
        PlotSpec p;
        p.title = t.kind + " of " + (t.attributes.count("model") ? t.attributes.at("model") : std::string());
        p.x.label = t.x.name;
        p.y.label = t.kind;
        for (size_t c = 0; c < t.channels.size(); ++c) p.curves.push_back({t.channels[c], t.x.parameter, t.values[c], ""});
        fig.panels.push_back(p);
    } else {
        const int slice = t.depth() / 2;
        for (size_t c = 0; c < t.channels.size(); ++c) {
            PlotSpec p;
            std::string name = t.channels[c];  // MathGL reads _ as a subscript
            for (char& ch : name)
                if (ch == '_') ch = ' ';
            p.title = name + " (" + t.kind + ")";
            if (t.depth() > 1) {
                char b[64];
                std::snprintf(b, sizeof b, ", %s = %.3g", t.z.name.c_str(), t.z.parameter[size_t(slice)]);
                p.title += b;
            }
            p.x.label = t.x.name + " (" + t.x.mapping + ")";
            p.y.label = t.y.name + " (" + t.y.mapping + ")";
            p.legend = LegendPlace::None;
            Heatmap& h = p.heatmap;
            h.nx = t.width();
            h.ny = t.height();
            h.x_lo = t.x.lo;
            h.x_hi = t.x.hi;
            h.y_lo = t.y.lo;
            h.y_hi = t.y.hi;
            const size_t n = size_t(h.nx) * h.ny;
            h.z.assign(t.values[c].begin() + long(n * size_t(slice)), t.values[c].begin() + long(n * size_t(slice + 1)));
            // [0, 1] (an energy fraction's range) widened to the data, so that a value above 1 (a
            // sheen lobe's gain at grazing) or below 0 is shown, never clipped to the end colour.
            const auto [lo, hi] = std::minmax_element(h.z.begin(), h.z.end());
            h.z_lo = std::min(0.0, *lo);
            h.z_hi = std::max(1.0, *hi);
            h.colorbar_label = t.channels[c];
            fig.panels.push_back(p);
        }
        fig.columns = std::min<int>(int(t.channels.size()), 2);
        fig.panel_width = 760;
        fig.panel_height = 640;
        fig.flat = true;
    }
    write_figure(path, fig);
}

}  // namespace brdfbake

// PNG/SVG previews of tables: a heatmap per channel with labelled axes and a colour bar naming the
// channel and its range (2D tables; a 3D table shows every z-slice as a small multiple, or the one
// slice asked for), or curves for a 1D table. The picture runs every axis upwards, and its caption
// says where the file's row 0 is, so that the picture and the file cannot be misread.
#include <algorithm>
#include <cstdio>

#include "brdfbake/table.h"
#include "plot/plot.h"

namespace brdfbake {

namespace {

/// At most this many z-slices are drawn side by side; a deeper table shows that many, evenly spread.
constexpr int kMaxSlices = 8;

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return b;
}

/// ". <note>" where an axis's texels were computed elsewhere than their coordinate (a floor or a
/// clamp): the clause of its mapping that says so (the mapping's clauses are split by "; ").
std::string computed_at(const Axis& a) {
    size_t start = 0;
    while (start < a.mapping.size()) {
        const size_t end = std::min(a.mapping.find("; ", start), a.mapping.size());
        const std::string clause = a.mapping.substr(start, end - start);
        if (clause.find("computed at") != std::string::npos) return ". " + clause;
        start = end + 2;
    }
    return "";
}

}  // namespace

std::string plot_text(const std::string& plain) {
    // MathGL markup reads '_' as a subscript and '^' as a superscript; '\_' and '\^' are literal.
    std::string out;
    for (char c : plain) {
        if (c == '_' || c == '^') out += '\\';
        out += c;
    }
    return out;
}

std::string axis_label(const Axis& a) {
    // What the ticks show, with the quantity the mapping gives where they differ.
    if (a.name == "mu") return "\\mu{} = cos \\theta_o";
    if (a.name == "sqrt_mu") return "u = \\sqrt{\\mu}  (\\mu{} = u^2 = cos \\theta_o)";
    if (a.name == "alpha") return "\\alpha";
    if (a.name == "roughness") return "roughness r  (\\alpha{} = r^2)";
    if (a.name == "eta") return "\\eta";
    if (a.name == "f0") return "F_0 = ((\\eta{} - 1)/(\\eta{} + 1))^2";
    if (a.name == "cycles_z" && a.parameter_name == "eta") return "z = F_0^{1/4}  (Cycles' \\eta{} axis)";
    if (a.name == "cycles_z") return "z  (Cycles' " + plot_text(a.parameter_name) + " axis)";
    if (a.name == "theta_i") return "\\theta_i (degrees)";
    if (a.name == "theta_o") return "\\theta_o (degrees)";
    return plot_text(a.name);
}

namespace {

/// A heatmap panel of `values` (x fastest) over the axes x and y, coloured over [lo, hi], its
/// colour bar naming the channel and the range of its data.
PlotSpec heatmap_panel(const std::string& title, const Axis& x, const Axis& y, std::vector<double> values,
                       const std::string& channel, double lo, double hi, double data_lo, double data_hi) {
    PlotSpec p;
    p.title = title;
    p.x.label = axis_label(x);
    p.y.label = axis_label(y);
    p.legend = LegendPlace::None;
    Heatmap& h = p.heatmap;
    h.nx = int(x.coordinate.size());
    h.ny = int(y.coordinate.size());
    h.x_lo = x.lo;
    h.x_hi = x.hi;
    h.y_lo = y.lo;
    h.y_hi = y.hi;
    h.z = std::move(values);
    h.z_lo = lo;
    h.z_hi = hi;
    h.colorbar_label = plot_text(channel) + ": " + number(data_lo) + " to " + number(data_hi);
    return p;
}

}  // namespace

void write_table_preview(const Table& table, const std::string& path, int slice) {
    // The picture runs every axis upwards: a flipped axis (lo > hi) is drawn unflipped.
    Table t = table;
    std::vector<std::string> flipped;
    for (const Axis* a : {&t.x, &t.y, &t.z})
        if (a->lo > a->hi && a->size > 1) flipped.push_back(a->name);
    arrange_axes(t, {}, flipped);
    Figure fig;
    const std::string model = t.attributes.count("model") ? t.attributes.at("model") : std::string();
    if (t.height() == 1 && t.depth() == 1) {
        PlotSpec p;
        p.title = plot_text(t.kind + (model.empty() ? "" : " of " + model));
        p.x.label = axis_label(t.x);
        p.y.label = t.channels.size() == 1 ? plot_text(t.channels[0]) : "value";
        p.legend = t.channels.size() > 1 ? LegendPlace::Outside : LegendPlace::None;
        for (size_t c = 0; c < t.channels.size(); ++c)
            p.curves.push_back({plot_text(t.channels[c]), t.x.parameter, t.values[c], ""});
        fig.panels.push_back(p);
        write_figure(path, fig);
        return;
    }
    if (t.height() == 1 && t.depth() > 1) {
        // A 1D table with slices (dielectric-eavg: roughness x eta): one heatmap per channel over
        // x and the z axis, whose values are the file's rows in order (row z = slice z).
        const std::string z_param = t.z.name != "eta" && t.z.parameter_name == "eta" ? "; \\eta{} = " +
                                        number(t.z.parameter.front()) + " to " + number(t.z.parameter.back()) : "";
        for (size_t c = 0; c < t.channels.size(); ++c) {
            const auto [mn, mx] = std::minmax_element(t.values[c].begin(), t.values[c].end());
            // [0, 1] widened to the data, as the slices below
            fig.panels.push_back(heatmap_panel(plot_text(t.channels[c]) + " (" + plot_text(t.kind) + ")" + z_param, t.x,
                                               t.z, t.values[c], t.channels[c], std::min(0.0, *mn), std::max(1.0, *mx),
                                               *mn, *mx));
        }
        fig.columns = std::min<int>(int(t.channels.size()), 2);
        fig.panel_width = 760;
        fig.panel_height = 640;
        fig.flat = true;
        std::string caption = "file: row 0 holds " + t.z.name + " = " + number(table.z.coordinate.front()) +
                              (flipped.empty() ? " (the bottom row here)" : " (an axis is flipped in the file; drawn upwards here)");
        for (const Axis* a : {&t.x, &t.z}) caption += computed_at(*a);
        fig.caption = plot_text(caption);
        write_figure(path, fig);
        return;
    }
    // The slices drawn: the one asked for, or every one (at most kMaxSlices, evenly spread).
    std::vector<int> slices;
    if (slice >= 0) {
        slices.push_back(std::min(slice, t.depth() - 1));
    } else if (t.depth() <= kMaxSlices) {
        for (int z = 0; z < t.depth(); ++z) slices.push_back(z);
    } else {
        for (int k = 0; k < kMaxSlices; ++k) slices.push_back(int(double(k) * (t.depth() - 1) / (kMaxSlices - 1) + 0.5));
    }
    const size_t n = size_t(t.width()) * size_t(t.height());
    for (size_t c = 0; c < t.channels.size(); ++c) {
        // One colour range per channel, over the slices drawn, so that slices compare: [0, 1] (an
        // energy fraction's range) widened to the data, so that a value above 1 (a sheen lobe's
        // gain at grazing) or below 0 is shown, never clipped to the end colour.
        double lo = 0.0, hi = 1.0, data_lo = t.values[c][n * size_t(slices[0])], data_hi = data_lo;
        for (int z : slices) {
            const auto first = t.values[c].begin() + long(n * size_t(z));
            const auto [mn, mx] = std::minmax_element(first, first + long(n));
            data_lo = std::min(data_lo, *mn);
            data_hi = std::max(data_hi, *mx);
        }
        lo = std::min(lo, data_lo);
        hi = std::max(hi, data_hi);
        for (int z : slices) {
            std::string title = plot_text(t.channels[c]) + " (" + plot_text(t.kind) + ")";
            if (t.depth() > 1) title += ", " + axis_label(t.z) + " = " + number(t.z.coordinate[size_t(z)]);
            if (t.depth() > 1 && t.z.name != "eta" && !t.z.parameter_name.empty())
                title += " (" + (t.z.parameter_name == "eta" ? std::string("\\eta{}") : plot_text(t.z.parameter_name)) +
                         " = " + number(t.z.parameter[size_t(z)]) + ")";
            fig.panels.push_back(heatmap_panel(
                title, t.x, t.y,
                std::vector<double>(t.values[c].begin() + long(n * size_t(z)), t.values[c].begin() + long(n * size_t(z + 1))),
                t.channels[c], lo, hi, data_lo, data_hi));
        }
    }
    fig.columns = slices.size() > 1 ? int(slices.size()) : std::min<int>(int(t.channels.size()), 2);
    const bool small = slices.size() > 2;
    fig.panel_width = small ? 520 : 760;
    fig.panel_height = small ? 460 : 640;
    fig.flat = true;
    // Where the file's texels are: the picture's bottom row is the file's first row of each slice
    // unless an axis was flipped, and a 3D file stacks its slices along y.
    std::string row0 = "file: row 0 holds " + t.y.name + " = " + number(table.y.coordinate.front()) +
                       (flipped.empty() ? " (the bottom row here)" : " (the axis is flipped in the file; drawn upwards here)");
    if (table.depth() > 1) row0 += "; slices stacked along y, " + t.z.name + " = " + number(table.z.coordinate.front()) + " first";
    std::string caption = row0;
    for (const Axis* a : {&t.x, &t.y, &t.z})
        if (a != &t.z || t.depth() > 1) caption += computed_at(*a);
    fig.caption = plot_text(caption);
    write_figure(path, fig);
}

}  // namespace brdfbake

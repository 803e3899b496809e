// PNG/SVG previews of tables: a heatmap per channel with labelled axes and a colour bar naming the
// channel and its range (2D tables; a 3D table shows every z-slice as a small multiple, or the one
// slice asked for), or curves for a 1D table. The picture runs every axis upwards, and its caption
// says where the file's row 0 is, so that the picture and the file cannot be misread.
#include <algorithm>
#include <cmath>
#include <limits>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

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

std::string wrap_at_commas(const std::string& text, size_t width) {
    std::string out, line;
    size_t start = 0;
    while (start < text.size()) {
        const size_t comma = text.find(',', start);
        const size_t end = comma == std::string::npos ? text.size() : comma + 1;
        const std::string part = text.substr(start, end - start);
        if (!line.empty() && line.size() + part.size() > width) {
            out += line + "\n";
            line.clear();
        }
        line += part;
        start = end;
    }
    return out + line;
}

std::string short_numbers(const std::string& text, int digits) {
    std::string out;
    size_t i = 0;
    while (i < text.size()) {
        const bool starts = std::isdigit((unsigned char)text[i]) &&
                            (i == 0 || !(std::isalnum((unsigned char)text[i - 1]) || text[i - 1] == '_' || text[i - 1] == '.'));
        if (!starts) {
            out += text[i++];
            continue;
        }
        size_t end = i;
        while (end < text.size() && std::isdigit((unsigned char)text[end])) ++end;
        if (end + 1 < text.size() && text[end] == '.' && std::isdigit((unsigned char)text[end + 1]))
            for (++end; end < text.size() && std::isdigit((unsigned char)text[end]);) ++end;
        if (end + 1 < text.size() && (text[end] == 'e' || text[end] == 'E')) {
            size_t e = end + 1;
            if (e < text.size() && (text[e] == '+' || text[e] == '-')) ++e;
            if (e < text.size() && std::isdigit((unsigned char)text[e])) {
                while (e < text.size() && std::isdigit((unsigned char)text[e])) ++e;
                end = e;
            }
        }
        const std::string number_text = text.substr(i, end - i);
        char b[40];
        std::snprintf(b, sizeof b, "%.*g", digits, std::strtod(number_text.c_str(), nullptr));
        out += std::strlen(b) < number_text.size() ? std::string(b) : number_text;
        i = end;
    }
    return out;
}

std::string full_preview_path(const std::string& preview) {
    const size_t dot = preview.find_last_of('.'), slash = preview.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return preview + ".full";
    return preview.substr(0, dot) + ".full" + preview.substr(dot);
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

/// The colours of one channel: [0, 1] (an energy fraction's range) widened to the data between its
/// 0.5th and 99.5th percentiles, so that a value above 1 (a sheen lobe's gain at grazing) shows,
/// while one outlier texel (E = 11.4 among values below 1.2) cannot squash the rest into one colour.
/// Texels outside are drawn in red (kOutsideColour) and counted on the colour bar.
struct ColourRange {
    double lo = 0.0, hi = 1.0;            // the colours' range
    double data_lo = 0.0, data_hi = 1.0;  // the data's
    size_t below = 0, above = 0;          // texels outside [lo, hi]
};

const char* const kOutsideColour = "{xE41A1C}";

ColourRange robust_range(const std::vector<double>& values) {
    ColourRange r;
    std::vector<double> v;
    for (double x : values)
        if (std::isfinite(x)) v.push_back(x);
    if (v.empty()) return r;
    std::sort(v.begin(), v.end());
    auto at = [&](double q) { return v[size_t(q * double(v.size() - 1) + 0.5)]; };
    r.data_lo = v.front();
    r.data_hi = v.back();
    r.lo = std::min(0.0, at(0.005));
    r.hi = std::max(1.0, at(0.995));
    for (double x : v) {
        r.below += x < r.lo;
        r.above += x > r.hi;
    }
    return r;
}

/// The texels of `values` outside the range as NaN: the heatmap shows them in its gap colour.
std::vector<double> marked(std::vector<double> values, const ColourRange& r) {
    for (double& v : values)
        if (v < r.lo || v > r.hi) v = std::numeric_limits<double>::quiet_NaN();
    return values;
}

/// A heatmap panel of `values` (x fastest) over the axes x and y, coloured over the range, its
/// colour bar naming the channel, the range of its data and the texels drawn red outside it.
PlotSpec heatmap_panel(const std::string& title, const Axis& x, const Axis& y, const std::vector<double>& values,
                       const std::string& channel, const ColourRange& r) {
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
    h.z = marked(values, r);
    h.z_lo = r.lo;
    h.z_hi = r.hi;
    h.gap_colour = kOutsideColour;
    h.colorbar_label = plot_text(channel) + ": " + number(r.data_lo) + " to " + number(r.data_hi);
    if (r.above > 0) h.colorbar_label += "; red: " + std::to_string(r.above) + " > " + number(r.hi);
    if (r.below > 0) h.colorbar_label += "; red: " + std::to_string(r.below) + " < " + number(r.lo);
    return p;
}

/// Slices `slices` of every channel of the 3D (or 2D) table `t`, one row of panels per channel,
/// written to `path`; `table` is the table as the file holds it (for the caption).
void write_slices(const Table& t, const Table& table, const std::vector<std::string>& flipped,
                  const std::vector<int>& slices, int panel_width, int panel_height, const std::string& note,
                  const std::string& path) {
    Figure fig;
    const size_t n = size_t(t.width()) * size_t(t.height());
    for (size_t c = 0; c < t.channels.size(); ++c) {
        // One colour range per channel, over all its texels, so that slices (and the summary and
        // the full-size picture) compare.
        const ColourRange range = robust_range(t.values[c]);
        for (int z : slices) {
            std::string title = plot_text(t.channels[c]) + " (" + plot_text(t.kind) + ")";
            if (t.depth() > 1) title += ", " + axis_label(t.z) + " = " + number(t.z.coordinate[size_t(z)]);
            if (t.depth() > 1 && t.z.name != "eta" && !t.z.parameter_name.empty())
                title += " (" + (t.z.parameter_name == "eta" ? std::string("\\eta{}") : plot_text(t.z.parameter_name)) +
                         " = " + number(t.z.parameter[size_t(z)]) + ")";
            fig.panels.push_back(heatmap_panel(
                title, t.x, t.y,
                std::vector<double>(t.values[c].begin() + long(n * size_t(z)), t.values[c].begin() + long(n * size_t(z + 1))),
                t.channels[c], range));
        }
    }
    fig.columns = slices.size() > 1 ? int(slices.size()) : std::min<int>(int(t.channels.size()), 2);
    fig.panel_width = panel_width;
    fig.panel_height = panel_height;
    fig.flat = true;
    // Where the file's texels are: the picture's bottom row is the file's first row of each slice
    // unless an axis was flipped, and a 3D file stacks its slices along y.
    std::string row0 = "file: row 0 holds " + t.y.name + " = " + number(table.y.coordinate.front()) +
                       (flipped.empty() ? " (the bottom row here)" : " (the axis is flipped in the file; drawn upwards here)");
    if (table.depth() > 1) row0 += "; slices stacked along y, " + t.z.name + " = " + number(table.z.coordinate.front()) + " first";
    std::string caption = row0 + note;
    for (const Axis* a : {&t.x, &t.y, &t.z})
        if (a != &t.z || t.depth() > 1) caption += computed_at(*a);
    fig.caption = plot_text(caption);
    write_figure(path, fig);
}

/// `count` slices of `depth`, evenly spread from the first to the last.
std::vector<int> spread(int depth, int count) {
    std::vector<int> slices;
    if (depth <= count) {
        for (int z = 0; z < depth; ++z) slices.push_back(z);
    } else {
        for (int k = 0; k < count; ++k) slices.push_back(int(double(k) * (depth - 1) / (count - 1) + 0.5));
    }
    return slices;
}

}  // namespace

std::string write_table_preview(const Table& table, const std::string& path, int slice, PreviewLayout layout) {
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
        return "";
    }
    if (t.height() == 1 && t.depth() > 1) {
        // A 1D table with slices (dielectric-eavg: roughness x eta): one heatmap per channel over
        // x and the z axis, whose values are the file's rows in order (row z = slice z).
        const std::string z_param = t.z.name != "eta" && t.z.parameter_name == "eta" ? "; \\eta{} = " +
                                        number(t.z.parameter.front()) + " to " + number(t.z.parameter.back()) : "";
        for (size_t c = 0; c < t.channels.size(); ++c)
            fig.panels.push_back(heatmap_panel(plot_text(t.channels[c]) + " (" + plot_text(t.kind) + ")" + z_param, t.x,
                                               t.z, t.values[c], t.channels[c], robust_range(t.values[c])));
        fig.columns = std::min<int>(int(t.channels.size()), 2);
        fig.panel_width = 760;
        fig.panel_height = 640;
        fig.flat = true;
        std::string caption = "file: row 0 holds " + t.z.name + " = " + number(table.z.coordinate.front()) +
                              (flipped.empty() ? " (the bottom row here)" : " (an axis is flipped in the file; drawn upwards here)");
        for (const Axis* a : {&t.x, &t.z}) caption += computed_at(*a);
        fig.caption = plot_text(caption);
        write_figure(path, fig);
        return "";
    }
    if (slice >= 0 || t.depth() == 1) {
        const std::vector<int> slices{std::min(std::max(slice, 0), t.depth() - 1)};
        write_slices(t, table, flipped, slices, 760, 640, "", path);
        return "";
    }
    // A 3D table: kSummarySlices slices per channel at most kSummaryWidth pixels wide; a deeper
    // table gets its full-size picture (kMaxSlices slices) beside the summary, named in its caption.
    if (layout == PreviewLayout::Full && t.depth() > kSummarySlices) {
        write_slices(t, table, flipped, spread(t.depth(), kMaxSlices), 520, 460, "", path);
        return "";
    }
    const std::vector<int> summary = spread(t.depth(), kSummarySlices);
    std::string note, full;
    if (t.depth() > kSummarySlices && layout == PreviewLayout::Summary) {
        note = "; " + std::to_string(summary.size()) + " of " + std::to_string(t.depth()) +
               " slices (brdfbake show TABLE --plot FILE.png draws " +
               (t.depth() > kMaxSlices ? std::to_string(kMaxSlices) + " of them" : std::string("every slice")) + ")";
    } else if (t.depth() > kSummarySlices) {
        full = full_preview_path(path);
        write_slices(t, table, flipped, spread(t.depth(), kMaxSlices), 520, 460, "", full);
        note = "; " + std::to_string(summary.size()) + " of " + std::to_string(t.depth()) + " slices, more in " +
               full.substr(full.find_last_of('/') + 1);
    }
    const int columns = int(summary.size());
    const int width = columns <= 2 ? 760 : std::min(520, kSummaryWidth / columns);
    write_slices(t, table, flipped, summary, width, width * 460 / 520, note, path);
    return full;
}

}  // namespace brdfbake

#include "plot/plot.h"

#include <mgl2/mgl.h>
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

#include "brdfbake/error.h"
#include "brdfbake/output.h"

namespace brdfbake {

namespace {

enum class Kind { Png, Svg, Unknown };

Kind kind_of(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos) return Kind::Unknown;
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == "png") return Kind::Png;
    if (ext == "svg") return Kind::Svg;
    return Kind::Unknown;
}

// Colours that stay distinct in print and for the common colour-vision deficiencies:
// blue, red, green, orange, magenta, cyan, black, grey.
const char* const kPalette[] = {"b", "r", "g", "q", "m", "c", "k", "h"};

struct Bounds {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    void add(double v) {
        if (!std::isfinite(v)) return;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    bool empty() const { return !(lo <= hi); }
};

/// The axis range: the given bounds, or the data's with a 4% margin (and a unit span if flat).
void resolve_range(const PlotAxis& axis, Bounds data, double& lo, double& hi) {
    double dlo = data.lo, dhi = data.hi;
    if (dhi - dlo <= 0.0) {
        const double pad = std::max(1.0, std::fabs(dlo)) * 0.5;
        dlo -= pad;
        dhi += pad;
    } else {
        const double pad = 0.04 * (dhi - dlo);
        dlo -= pad;
        dhi += pad;
    }
    lo = std::isfinite(axis.lo) ? axis.lo : dlo;
    hi = std::isfinite(axis.hi) ? axis.hi : dhi;
    if (!(hi > lo)) hi = lo + 1.0;
}

/// The data of a curve with non-finite points replaced by NaN, which MathGL draws as gaps.
mglData to_mgl(const std::vector<double>& v) {
    mglData d(long(v.size()));
    for (size_t i = 0; i < v.size(); ++i) d.a[i] = std::isfinite(v[i]) ? v[i] : NAN;
    return d;
}

/// The fraction of a panel's width left of its axes box, for the y tick labels and the y label.
constexpr double kLeftMargin = 0.13;

/// The fraction of a panel's width that an Outside legend takes: enough for its longest entry.
double outside_legend_width(const PlotSpec& p) {
    size_t chars = 0;
    for (const Curve& c : p.curves) chars = std::max(chars, c.label.size());
    return std::min(0.45, 0.09 + 0.0125 * double(chars));
}

/// Where a panel's axes box ends, as a fraction of its width: room for a colour bar or an Outside
/// legend on the right.
double box_right(const PlotSpec& p) {
    if (p.heatmap.nx > 0 && !p.heatmap.colorbar_label.empty()) return 0.78;
    if (p.legend == LegendPlace::Outside) return 1.0 - outside_legend_width(p);
    return 0.96;
}

/// The characters a line of MathGL markup shows, roughly: TeX commands and braces take little room.
/// For several lines (split at '\n'), the longest.
size_t visible_chars(const std::string& text) {
    size_t longest = 0, visible = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n') {
            visible = 0;
            continue;
        }
        if (text[i] == '\\') {
            while (i + 1 < text.size() && std::isalpha((unsigned char)text[i + 1])) ++i;
            ++visible;
        } else if (text[i] != '{' && text[i] != '}' && text[i] != '_' && text[i] != '^') {
            ++visible;
        }
        longest = std::max(longest, visible);
    }
    return longest;
}

/// MathGL's text scales with the panel: small panels (a table's summary) get larger text, by this factor.
double font_scale(int panel_height) { return std::min(1.5, std::max(1.0, std::sqrt(560.0 / panel_height))); }

/// The height of a title's line as a fraction of its panel's height (MathGL's default font, size 1.15).
constexpr double kTitleLine = 0.075;

/// The lines of a panel's title.
int title_lines(const PlotSpec& p) { return p.title.empty() ? 0 : 1 + int(std::count(p.title.begin(), p.title.end(), '\n')); }

/// The size of a panel's title (MathGL's negative relative size): 1.15, smaller where its longest
/// line would not fit 90% of the cell's width. A character of size 1.15 is about 2.2% of the
/// cell's height wide (measured on MathGL's default font at font size 3).
double title_size(const std::string& title, int cell_width, int cell_height) {
    const double chars = double(std::max<size_t>(1, visible_chars(title)));
    const double width = chars * 0.0223 * cell_height * font_scale(cell_height);
    return -1.15 * std::max(0.45, std::min(1.0, 0.9 * cell_width / width));
}

/// The legend, drawn by hand in data coordinates: MathGL's Legend() scales its text with the
/// data ranges of an InPlot and comes out unreadably small or not at all.
void draw_legend(mglGraph& gr, const PlotSpec& p, const std::vector<std::pair<std::string, std::string>>& entries,
                 double x0, double x1, double y0, double y1) {
    const double dx = x1 - x0, dy = y1 - y0;
    size_t chars = 0;
    for (const auto& e : entries) chars = std::max(chars, visible_chars(e.first));
    const double row = 0.058 * dy, sample = 0.08 * dx, pad = 0.015 * dx;
    double w = pad + sample + pad + 0.0125 * dx * double(chars) + pad;
    if (p.legend == LegendPlace::Outside) {  // the strip write_figure left right of the box
        w = dx * (outside_legend_width(p) - 0.03) / (box_right(p) - kLeftMargin);
    }
    const double h = row * double(entries.size()) + 0.6 * row;
    const double m = 0.025;  // distance from the axes box, as a fraction of the range
    double left = x0 + m * dx, top = y1 - m * dy;
    if (p.legend == LegendPlace::Outside) left = x1 + 0.03 * dx;  // write_figure leaves room on the right
    if (p.legend == LegendPlace::TopRight || p.legend == LegendPlace::BottomRight) left = x1 - m * dx - w;
    if (p.legend == LegendPlace::BottomLeft || p.legend == LegendPlace::BottomRight) top = y0 + m * dy + h;
    if (std::isfinite(p.legend_x) && std::isfinite(p.legend_y)) {
        left = x0 + p.legend_x * dx;
        top = y0 + p.legend_y * dy;
    }
    const double right = left + w, bottom = top - h;
    gr.Face(mglPoint(left, bottom, 0.5), mglPoint(right, bottom, 0.5), mglPoint(left, top, 0.5),
            mglPoint(right, top, 0.5), "w");
    const char* frame = "k-1";
    gr.Line(mglPoint(left, bottom, 0.6), mglPoint(right, bottom, 0.6), frame);
    gr.Line(mglPoint(right, bottom, 0.6), mglPoint(right, top, 0.6), frame);
    gr.Line(mglPoint(right, top, 0.6), mglPoint(left, top, 0.6), frame);
    gr.Line(mglPoint(left, top, 0.6), mglPoint(left, bottom, 0.6), frame);
    for (size_t i = 0; i < entries.size(); ++i) {
        const double y = top - 0.8 * row - row * double(i);
        // A line, not Plot(): Plot clips to the axes box, and an Outside legend lies beyond it.
        gr.Line(mglPoint(left + pad, y, 0.7), mglPoint(left + pad + sample, y, 0.7), entries[i].second.c_str());
        gr.Puts(mglPoint(left + 2 * pad + sample, y, 0.7), entries[i].first.c_str(), ":L", -0.85);
    }
}

/// Draws the panel's heatmap (if any) and its colour bar; the ranges are already set.
void draw_heatmap(mglGraph& gr, const Heatmap& h, double x0, double x1, double y0, double y1) {
    if (h.nx <= 0) return;
    const double below = -std::numeric_limits<double>::infinity();  // log of z <= 0
    mglData z(h.nx, h.ny), x(h.nx), y(h.ny);
    Bounds bz;
    for (long k = 0; k < long(h.nx) * h.ny; ++k) {
        const double raw = h.z[size_t(k)];
        double v = raw;
        if (!std::isfinite(raw)) v = NAN;  // a gap
        else if (h.log_scale) v = raw > 0 ? std::log10(raw) : below;
        bz.add(v);
        z.a[k] = v;
    }
    auto scaled = [&](double v) { return h.log_scale && std::isfinite(v) ? (v > 0 ? std::log10(v) : below) : v; };
    double zlo = scaled(h.z_lo), zhi = scaled(h.z_hi);
    if (!std::isfinite(zlo)) zlo = bz.empty() ? 0.0 : bz.lo;
    if (!std::isfinite(zhi)) zhi = bz.empty() ? 1.0 : bz.hi;
    if (!(zhi > zlo)) zhi = zlo + 1.0;
    for (long k = 0; k < long(h.nx) * h.ny; ++k)
        if (z.a[k] == below) z.a[k] = zlo;  // drawn at the lower end rather than vanishing
    for (int i = 0; i < h.nx; ++i) x.a[i] = h.x_lo + (i + 0.5) * (h.x_hi - h.x_lo) / h.nx;
    for (int j = 0; j < h.ny; ++j) y.a[j] = h.y_lo + (j + 0.5) * (h.y_hi - h.y_lo) / h.ny;
    gr.SetRange('c', zlo, zhi);
    if (!h.gap_colour.empty()) {
        // Gaps (non-finite z) show this colour rather than the canvas: a face below the map (which
        // MathGL draws at the bottom of the z range, -1; larger z is nearer the viewer).
        // Within the axes box, which may end at the first and last cells' centres.
        const double fx0 = std::max(h.x_lo, x0), fx1 = std::min(h.x_hi, x1);
        const double fy0 = std::max(h.y_lo, y0), fy1 = std::min(h.y_hi, y1);
        gr.SetCut(false);
        gr.Face(mglPoint(fx0, fy0, -1.5), mglPoint(fx1, fy0, -1.5), mglPoint(fx0, fy1, -1.5), mglPoint(fx1, fy1, -1.5),
                h.gap_colour.c_str());
        gr.SetCut(true);
    }
    gr.Dens(x, y, z, h.scheme.c_str());
    if (!h.colorbar_label.empty()) {
        // Outside the axes box, on the right (write_figure leaves room for it).
        gr.Colorbar((h.scheme + "I>").c_str(), 1.06, 0.0, 1.0, 1.0);
        const std::string label = h.log_scale ? "log_{10} " + h.colorbar_label : h.colorbar_label;
        gr.SetCut(false);
        // Along the bar, right of its tick labels, reading upwards.
        const double xl = x1 + 0.24 * (x1 - x0), ym = 0.5 * (y0 + y1);
        gr.Puts(mglPoint(xl, ym), mglPoint(xl, ym + (y1 - y0)), label.c_str(), ":C", -0.9);
        gr.SetCut(true);
    }
}

/// A rectangle of pixels (columns x0..x1 - 1, rows y0..y1 - 1, row 0 at the top) to set to one colour.
struct PixelRect {
    long x0, x1, y0, y1;
    unsigned char rgb[3];
};

/// Draws a panel's colour cells as faces with their labels, and adds to `paint` the pixels that
/// each covers within the axes box [x0, x1] x [y0, y1] (the ranges are already set).
void draw_cells(mglGraph& gr, const PlotSpec& p, double x0, double x1, double y0, double y1,
                std::vector<PixelRect>& paint) {
    char colour[16];
    const mglPoint lo = gr.CalcScr(mglPoint(x0, y0)), hi = gr.CalcScr(mglPoint(x1, y1));
    const int height = gr.GetHeight();
    // Screen y from CalcScr grows upwards from the bottom; the RGB buffer's rows run downwards.
    auto column = [](double s) { return long(std::ceil(s - 0.5)); };
    for (const ColourCell& c : p.cells) {
        std::snprintf(colour, sizeof colour, "{x%02X%02X%02X}", c.rgb[0], c.rgb[1], c.rgb[2]);
        gr.Face(mglPoint(c.x0, c.y0, -0.5), mglPoint(c.x1, c.y0, -0.5), mglPoint(c.x0, c.y1, -0.5),
                mglPoint(c.x1, c.y1, -0.5), colour);
        if (!c.label.empty()) {
            gr.SetCut(false);
            gr.Puts(mglPoint(0.5 * (c.x0 + c.x1), c.y0 - 0.12 * (y1 - y0)), c.label.c_str(), ":C", -0.8);
            gr.SetCut(true);
        }
        const mglPoint a = gr.CalcScr(mglPoint(std::max(c.x0, x0), std::max(c.y0, y0)));
        const mglPoint b = gr.CalcScr(mglPoint(std::min(c.x1, x1), std::min(c.y1, y1)));
        // Inside the box's frame (one pixel in), whose line the cells must not cover.
        PixelRect r{std::max(column(a.x), column(lo.x) + 1), std::min(column(b.x), column(hi.x) - 1),
                    std::max(column(height - b.y), column(height - hi.y) + 1),
                    std::min(column(height - a.y), column(height - lo.y) - 1), {c.rgb[0], c.rgb[1], c.rgb[2]}};
        if (r.x1 > r.x0 && r.y1 > r.y0) paint.push_back(r);
    }
}

void draw_panel(mglGraph& gr, const PlotSpec& p, size_t panel_index, int cell_width, int cell_height,
                std::vector<PixelRect>& paint) {
    Bounds bx, by;
    for (const ColourCell& c : p.cells) {
        bx.add(c.x0);
        bx.add(c.x1);
        by.add(c.y0);
        by.add(c.y1);
    }
    if (p.heatmap.nx > 0) {
        if (p.heatmap.z.size() != size_t(p.heatmap.nx) * p.heatmap.ny)
            throw Error("plot '" + p.title + "': heatmap data does not fill its grid");
        bx.add(p.heatmap.x_lo);
        bx.add(p.heatmap.x_hi);
        by.add(p.heatmap.y_lo);
        by.add(p.heatmap.y_hi);
    }
    for (const Curve& c : p.curves) {
        if (c.x.size() != c.y.size())
            throw Error("plot '" + p.title + "': curve '" + c.label + "' has " + std::to_string(c.x.size()) +
                        " x values but " + std::to_string(c.y.size()) + " y values");
        for (size_t i = 0; i < c.x.size(); ++i)
            if (std::isfinite(c.x[i]) && std::isfinite(c.y[i])) {
                bx.add(c.x[i]);
                by.add(c.y[i]);
            }
    }
    if (bx.empty()) throw Error("plot '" + p.title + "' (panel " + std::to_string(panel_index + 1) + ") has no finite data");
    double x0, x1, y0, y1;
    PlotAxis ax = p.x, ay = p.y;
    if (p.heatmap.nx > 0 && !p.axes) {  // a picture: the whole grid
        ax.lo = p.heatmap.x_lo;
        ax.hi = p.heatmap.x_hi;
        ay.lo = p.heatmap.y_lo;
        ay.hi = p.heatmap.y_hi;
    } else if (p.heatmap.nx > 0) {  // a heatmap fills its box: from the first to the last cell centre
        const Heatmap& h = p.heatmap;
        const double hx = 0.5 * (h.x_hi - h.x_lo) / h.nx, hy = 0.5 * (h.y_hi - h.y_lo) / h.ny;
        if (!std::isfinite(ax.lo)) ax.lo = h.x_lo + (h.nx > 1 ? hx : 0.0);
        if (!std::isfinite(ax.hi)) ax.hi = h.x_hi - (h.nx > 1 ? hx : 0.0);
        if (!std::isfinite(ay.lo)) ay.lo = h.y_lo + (h.ny > 1 ? hy : 0.0);
        if (!std::isfinite(ay.hi)) ay.hi = h.y_hi - (h.ny > 1 ? hy : 0.0);
    }
    resolve_range(ax, bx, x0, x1);
    resolve_range(ay, by, y0, y1);

    gr.SetRanges(x0, x1, y0, y1);
    gr.SetOrigin(x0, y0);
    if (!p.title.empty()) {
        gr.SetCut(false);  // the title sits above the axes box, outside the data range
        // MathGL grows a title downwards from its first line: a picture's box is lowered by a line
        // for each beyond two (write_figure), and the title raised by as much.
        const int extra = p.axes ? 0 : std::max(0, title_lines(p) - 2);
        const double raise = extra * kTitleLine / (0.86 - kTitleLine * extra);
        gr.Puts(mglPoint(0.5 * (x0 + x1), y1 + (0.05 + raise) * (y1 - y0)), p.title.c_str(), ":C",
                title_size(p.title, cell_width, cell_height));
        gr.SetCut(true);
    }
    // Ticks counted from 0 (not from the range's lower end), so that they fall on round values.
    draw_heatmap(gr, p.heatmap, x0, x1, y0, y1);
    draw_cells(gr, p, x0, x1, y0, y1, paint);
    if (!p.axes) {
        for (const Curve& c : p.curves) gr.Plot(to_mgl(c.x), to_mgl(c.y), c.style.empty() ? "k-2" : c.style.c_str());
        return;
    }
    gr.SetTicks('x', p.x.tick, 0, 0.0);
    gr.SetTicks('y', p.y.tick, 0, 0.0);
    // A picture's axes (colour cells) read in their own units: no factored-out power of ten
    // (MathGL's default, 3, writes 0..1000 nm as 0..10 x 100).
    gr.SetTuneTicks(p.cells.empty() ? 3 : 0);
    gr.SetTickTempl('y', p.cells.empty() ? "" : "%g");  // 1000, not 1e3
    if (p.heatmap.nx == 0 && p.cells.empty()) gr.Grid("xy", "{h9}");
    gr.Box("k", false);
    gr.SetRotatedText(false);  // tick labels upright on the y axis too
    gr.Axis("xy");
    gr.SetRotatedText(true);
    // Axis labels placed by hand, clear of the tick labels (MathGL's Label() overlaps them at
    // this font size).
    gr.SetCut(false);
    const double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1), dx = x1 - x0, dy = y1 - y0;
    if (!p.x.label.empty()) gr.Puts(mglPoint(xm, y0 - 0.13 * dy), p.x.label.c_str(), ":C", -1.0);
    // Left of the upright tick labels, whatever the box's width (an Outside legend narrows it).
    // The label's centre 0.025 of the cell's width from its left edge, more for larger text.
    const double fs = font_scale(cell_height), left = kLeftMargin * fs;
    const double ylabel = (left - 0.025 - 0.04 * (fs - 1.0)) / (box_right(p) - left);
    if (!p.y.label.empty())
        gr.Puts(mglPoint(x0 - ylabel * dx, ym), mglPoint(x0 - ylabel * dx, ym + dy), p.y.label.c_str(), ":C", -1.0);
    gr.SetCut(true);

    for (const RefLine& l : p.lines) {
        mglPoint a = l.axis == 'x' ? mglPoint(l.value, y0) : mglPoint(x0, l.value);
        mglPoint b = l.axis == 'x' ? mglPoint(l.value, y1) : mglPoint(x1, l.value);
        gr.Line(a, b, "H=1");
        if (!l.label.empty()) {
            // Labels of successive lines at staggered heights so that close lines stay legible.
            const double f = 0.04 + 0.07 * double(&l - p.lines.data());
            mglPoint at = l.axis == 'x' ? mglPoint(l.value + 0.01 * (x1 - x0), y0 + f * (y1 - y0))
                                        : mglPoint(x0 + 0.02 * (x1 - x0), l.value + 0.015 * (y1 - y0));
            gr.Puts(at, l.label.c_str(), ":LH", -0.8);
        }
    }

    size_t auto_colour = 0;
    std::vector<std::pair<std::string, std::string>> entries;  // label, pen
    for (const Curve& c : p.curves) {
        std::string style = c.style;
        if (style.empty()) style = std::string(kPalette[auto_colour++ % (sizeof kPalette / sizeof kPalette[0])]) + "-2";
        const mglData x = to_mgl(c.x), y = to_mgl(c.y);
        gr.Plot(x, y, style.c_str());
        if (!c.label.empty()) entries.emplace_back(c.label, style);
    }
    if (p.legend != LegendPlace::None && !entries.empty()) {
        gr.SetCut(false);  // an Outside legend lies beyond the axes box
        draw_legend(gr, p, entries, x0, x1, y0, y1);
        gr.SetCut(true);
    }
}

}  // namespace

bool is_plot_path(const std::string& path) { return kind_of(path) != Kind::Unknown; }

void write_figure(const std::string& path, const Figure& figure) {
    const Kind kind = kind_of(path);
    if (kind == Kind::Unknown) throw Error("--plot '" + path + "': expected a file name ending in .png or .svg");
    if (figure.panels.empty()) throw Error("internal error: a figure without panels");
    const int n = int(figure.panels.size());
    const int cols = figure.columns > 0 ? std::min(figure.columns, n) : n;
    const int rows = (n + cols - 1) / cols;

    mglGraph::SuppressWarn(true);  // problems are checked below and reported as errors
    // One thread: MathGL's own took every core from the integration a bake runs beside its
    // previews, and gained little on pictures this size (measured: docs/performance.md).
    mgl_set_num_thr(1);
    omp_set_num_threads(1);  // this thread's OpenMP team, which MathGL's loops take
    // A shared colour bar takes a strip of its own on the right of the panels.
    const int strip = figure.colorbar_label.empty() ? 0 : 200;
    const int width = figure.panel_width * cols + strip;
    const double panels = double(figure.panel_width * cols) / width;  // their fraction of the canvas
    mglGraph gr(0, width, figure.panel_height * rows);
    gr.Clf('w');
    gr.SetQuality(figure.flat ? MGL_DRAW_FAST : MGL_DRAW_NORM);
    std::vector<PixelRect> paint;  // colour cells' pixels, set exactly after drawing
    for (int i = 0; i < n; ++i) {
        // Each panel is a cell of the grid (fractions of the canvas, y upwards); the axes box
        // leaves room for the y label on the left, the x label below and the title above.
        // A caption takes a strip at the bottom of the canvas (the panels' cells lie above it).
        const double caption = figure.caption.empty() ? 0.0 : 0.06 / rows;
        const double cw = panels / cols, ch = (1.0 - caption) / rows;
        const double cx = cw * (i % cols), cy = 1.0 - ch * (i / cols + 1);
        const PlotSpec& panel = figure.panels[size_t(i)];
        const double right = box_right(panel);
        const double bottom = 0.16;
        if (panel.axes)
            gr.InPlot(cx + kLeftMargin * font_scale(figure.panel_height) * cw, cx + right * cw, cy + bottom * ch,
                      cy + 0.90 * ch, false);
        else  // a picture: only the title needs room, a line more for each beyond two
            gr.InPlot(cx + 0.03 * cw, cx + 0.97 * cw, cy + 0.02 * ch,
                      cy + (0.88 - kTitleLine * std::max(0, title_lines(panel) - 2)) * ch, false);
        gr.SetPlotFactor(1.0);  // 2D plots: fill the cell instead of leaving room for rotation
        gr.SetFontSize(3.0 * font_scale(figure.panel_height));
        const PlotSpec& p = figure.panels[size_t(i)];
        draw_panel(gr, p, size_t(i), figure.panel_width, figure.panel_height, paint);
    }
    if (strip > 0) {
        // The strip as one plot (so that text keeps the panels' size), the bar in its left part.
        gr.InPlot(panels, 1.0, 0.0, 1.0, false);
        gr.SetPlotFactor(1.0);
        gr.SetRanges(0.0, 1.0, 0.0, 1.0);
        // Relative to the strip, which is narrower than a panel: tick labels and the label as large
        // as a panel's axis text, whatever the panels' height.
        gr.SetFontSize(8.0);
        gr.SetRange('c', figure.colorbar_lo, figure.colorbar_hi);
        gr.Colorbar((figure.colorbar_scheme + "I>").c_str(), 0.05, 0.06, 0.25, 0.82);
        gr.Puts(mglPoint(0.66, 0.5), mglPoint(0.66, 1.5), figure.colorbar_label.c_str(), ":C",
                -0.72 * std::min(1.0, 28.0 / double(std::max<size_t>(1, visible_chars(figure.colorbar_label)))));
    }
    if (!figure.caption.empty()) {
        gr.InPlot(0.0, 1.0, 0.0, 1.0, false);
        gr.SetPlotFactor(1.0);
        gr.SetRanges(0.0, 1.0, 0.0, 1.0);
        gr.SetFontSize(3.0 / rows);
        gr.SetCut(false);
        gr.Puts(mglPoint(0.01, 0.03 / rows), figure.caption.c_str(), ":L", -0.75);
        gr.SetCut(true);
    }
    if (gr.Message() && *gr.Message()) {
        // MathGL reports problems as messages rather than failures; they are not fatal for a plot
        // but would hide a wrong call, so they reach the user.
        std::fprintf(stderr, "brdfbake: MathGL: %s\n", gr.Message());
    }

    if (kind == Kind::Png) {
        // The canvas's RGB bytes through the project's PNG writer: libpng's errors (a full disk)
        // end in Error, where MathGL's own writer would abort the process.
        const unsigned char* rgb = gr.GetRGB();
        const int w = gr.GetWidth(), h = gr.GetHeight();
        if (!rgb || w <= 0 || h <= 0) throw Error("cannot write plot '" + path + "': MathGL drew nothing");
        std::vector<unsigned char> pixels(rgb, rgb + size_t(w) * size_t(h) * 3);
        for (const PixelRect& r : paint)
            for (long y = std::max(0L, r.y0); y < std::min(long(h), r.y1); ++y)
                for (long x = std::max(0L, r.x0); x < std::min(long(w), r.x1); ++x)
                    std::copy(r.rgb, r.rgb + 3, &pixels[3 * (size_t(y) * size_t(w) + size_t(x))]);
        write_png_file(path, w, h, 8, 3, pixels, {});
        return;
    }
    // SVG: MathGL writes the file itself and reports no failure; a file that does not end with
    // its closing tag was cut short (a full disk) and is removed.
    const OutputFile out = prepare_output(path);
    const std::string& tmp = out.temporary;
    // MathGL reports an unwritable file on stderr only; find out first, with the reason.
    if (FILE* probe = std::fopen(tmp.c_str(), "wb")) {
        std::fclose(probe);
    } else {
        throw Error("cannot write plot '" + path + "': " + std::strerror(errno));
    }
    errno = 0;
    gr.WriteSVG(tmp.c_str(), "brdfbake");
    const int err = errno;
    std::string tail;
    if (std::FILE* in = std::fopen(tmp.c_str(), "rb")) {
        char b[64] = {};
        if (std::fseek(in, -long(sizeof b - 1), SEEK_END) != 0) std::rewind(in);
        tail.assign(b, std::fread(b, 1, sizeof b - 1, in));
        std::fclose(in);
    }
    if (tail.find("</svg>") == std::string::npos) {
        std::remove(tmp.c_str());
        throw Error("cannot write plot '" + path + "': " + (err ? std::strerror(err) : "the SVG file was cut short"));
    }
    commit_output(out, path);
}

void write_plot(const std::string& path, const PlotSpec& panel, int width, int height) {
    Figure f;
    f.panels.push_back(panel);
    f.panel_width = width;
    f.panel_height = height;
    write_figure(path, f);
}

}  // namespace brdfbake

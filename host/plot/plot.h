// Plots for the commands (fresnel curves, albedo, reciprocity ...), drawn with MathGL and written
// as PNG or SVG by the file's extension. A figure is a grid of panels; a panel holds curves with
// axis labels, a title and a legend. Written atomically: a reader never sees a half-written file.
//
// Text (titles, axis labels, legend entries) is MathGL markup: TeX-like commands such as
// \theta, \mu, \eta and sub/superscripts x_{i}, x^{2} are rendered; plain text is plain.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace brdfbake {

/// One named curve: y over x (same length). Non-finite points are left out (a gap).
struct Curve {
    std::string label;  // legend entry; empty: not listed in the legend
    std::vector<double> x, y;
    /// MathGL pen: colour letter, dash and width, e.g. "r-3" (red solid), "b;2" (blue dashed),
    /// "k|2" (black long dashes), "g:2" (green dotted); a trailing mark adds markers ("ko").
    /// Empty: the next colour of the figure's palette, solid, 2 wide.
    std::string style;
};

/// One axis: its label and range. A NaN bound is chosen from the data (with a small margin).
struct PlotAxis {
    std::string label;
    double lo = std::numeric_limits<double>::quiet_NaN();
    double hi = std::numeric_limits<double>::quiet_NaN();
    double tick = 0.0;  // distance between labelled ticks; 0: automatic
};

/// Where a panel's legend goes: inside a corner of the axes box, or Outside it on the right (the
/// box narrows to make room), where it can never cover a curve.
enum class LegendPlace { TopRight, TopLeft, BottomRight, BottomLeft, Outside, None };

/// A vertical or horizontal reference line (e.g. the critical angle), drawn thin and grey.
struct RefLine {
    char axis = 'x';  // 'x': vertical line at x = value; 'y': horizontal line at y = value
    double value = 0.0;
    std::string label;  // drawn next to the line; may be empty
};

/// A colour map of z over a regular grid, drawn under the curves: z[j * nx + i] belongs to the
/// cell centred at x = x_lo + (i + 0.5)(x_hi - x_lo)/nx, y = y_lo + (j + 0.5)(y_hi - y_lo)/ny.
/// Non-finite z values are drawn as gaps.
struct Heatmap {
    int nx = 0, ny = 0;  // nx = 0: no heatmap
    std::vector<double> z;
    double x_lo = 0.0, x_hi = 1.0, y_lo = 0.0, y_hi = 1.0;
    double z_lo = std::numeric_limits<double>::quiet_NaN();  // NaN: from the data
    double z_hi = std::numeric_limits<double>::quiet_NaN();
    bool log_scale = false;      // colour by log10(z) (z <= 0 drawn at the lower end)
    std::string colorbar_label;  // empty: no colour bar
    std::string gap_colour;      // MathGL colour drawn where z is not finite (empty: the canvas)
    // MathGL colour scheme: viridis (van der Walt and Smith, matplotlib 2015) at five stops, which
    // is perceptually uniform and reads in grey and to colour-blind eyes; "kw" for grey levels.
    std::string scheme = "{x440154}{x3B528B}{x21918C}{x5EC962}{xFDE725}";
};

/// A rectangle of one exact colour in data coordinates (8 bits per channel, already encoded, e.g.
/// sRGB), drawn under the curves, with an optional label centred under it: a colour swatch, or a
/// cell of a true-colour picture. MathGL shades its faces by a few levels (a face of {xC8853B}
/// comes out 198, 131, 57), so a PNG gets the colour exactly: after drawing, every pixel whose
/// centre lies inside the rectangle (and inside the panel's box) is set to it. An SVG gets a face.
struct ColourCell {
    double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
    unsigned char rgb[3] = {0, 0, 0};
    std::string label;  // MathGL markup under the cell; empty: none
};

/// One panel of a figure.
struct PlotSpec {
    std::string title;
    PlotAxis x, y;
    std::vector<Curve> curves;
    std::vector<RefLine> lines;
    Heatmap heatmap;
    std::vector<ColourCell> cells;  // drawn under the curves, over the heatmap
    bool axes = true;  // false: no box, ticks, grid or axis labels (a picture)
    LegendPlace legend = LegendPlace::TopRight;
    /// Legend position inside the axes box as fractions (0,0 bottom left .. 1,1 top right),
    /// overriding `legend` where both are finite.
    double legend_x = std::numeric_limits<double>::quiet_NaN();
    double legend_y = std::numeric_limits<double>::quiet_NaN();
};

/// Panels laid out in a grid, row by row.
struct Figure {
    std::vector<PlotSpec> panels;
    int columns = 0;  // 0: every panel in one row
    int panel_width = 800;  // pixels per panel (PNG; SVG scales the same geometry)
    int panel_height = 600;
    // Draw without colour interpolation (MathGL's fast quality): every cell of a heatmap one flat
    // colour, which is what a table holds, in half the time (0.15 s less for a 64x64 preview).
    bool flat = false;
    /// One colour bar for every panel, in a strip right of them (empty label: none): the panels'
    /// heatmaps must use the same scheme and range.
    std::string colorbar_label;
    std::string colorbar_scheme;
    double colorbar_lo = 0.0, colorbar_hi = 1.0;
    /// A line of small text under the panels (MathGL markup), e.g. how the picture maps to a file.
    std::string caption;
};

/// Writes `figure` to `path`; the format follows the extension (.png or .svg, any case).
/// Throws Error for another extension, mismatched curve lengths, a panel without finite data,
/// or a file that cannot be written (the target is left untouched then).
void write_figure(const std::string& path, const Figure& figure);

/// A figure with one panel.
void write_plot(const std::string& path, const PlotSpec& panel, int width = 900, int height = 640);

/// True if `path` ends in .png or .svg (any case), the formats write_figure can produce.
bool is_plot_path(const std::string& path);

/// `text` broken into lines of at most `width` characters after its commas (a model spec keeps its
/// keys whole), so that a long title fits its panel; a part longer than `width` stays on one line.
std::string wrap_at_commas(const std::string& text, size_t width);

/// `text` with every decimal number written to at most `digits` significant digits
/// ("eta=1.3300000000000001" reads "eta=1.33"): for titles, never for a file's numbers.
std::string short_numbers(const std::string& text, int digits = 4);

/// Plain text as MathGL markup: '_' and '^' are escaped, so "R_inside" reads as written.
std::string plot_text(const std::string& plain);

struct Axis;
/// The label of a table axis: what its ticks show ("u = sqrt(mu)" on a sqrt-mapped mu axis,
/// "roughness r (alpha = r^2)"), as MathGL markup.
std::string axis_label(const Axis& axis);

struct Table;
/// A table's preview picture (.png or .svg): a heatmap per channel with labelled axes and a colour
/// bar naming the channel and its range, or curves for a 1D table. A 3D table shows z-slice
/// `slice`, or with slice = -1 every slice as a small multiple (at most 8, evenly spread). The
/// caption says which of the file's rows is at the bottom.
///
/// A 3D table with more slices than a summary shows (kSummarySlices per channel), with slice = -1:
/// by `layout`, a readable summary at `path` (at most kSummaryWidth pixels wide) and every slice,
/// full size, beside it at full_preview_path(path) (SummaryAndFull); the summary alone, its
/// caption saying how to draw every slice (Summary: bake's and lut's previews, which must cost
/// less than the integration they show); or every slice, full size, at `path` (Full: `show
/// --plot`). Colours are clipped at the 99.5th percentile of a channel's texels (widened to
/// [0, 1]); the colour bar's label says how many lie above and how far. Drawing is
/// single-threaded (MathGL's threads slowed the bakes that draw beside their integration).
/// Returns the full-size picture's path when one was written beside the summary, else "".
enum class PreviewLayout { SummaryAndFull, Summary, Full };
std::string write_table_preview(const Table& table, const std::string& path, int slice = -1,
                         PreviewLayout layout = PreviewLayout::SummaryAndFull);

/// Slices of a 3D table a summary preview shows per channel, and its width at most (pixels).
constexpr int kSummarySlices = 4;
constexpr int kSummaryWidth = 1600;

/// Where write_table_preview puts the full-size picture of a 3D table beside its summary at
/// `preview`: NAME.full.png for NAME.png (the same extension). The file exists only for tables
/// deeper than kSummarySlices.
std::string full_preview_path(const std::string& preview);

}  // namespace brdfbake

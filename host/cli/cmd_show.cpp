// `brdfbake show TABLE`: what a table file holds (its header, axes and per-channel statistics),
// a picture of any slice or curves along its first axis, and conversion to another format.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"
#include "cli/cli.h"
#include "models/key_reader.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

struct ShowOptions {
    std::string table;
    std::string format = "table";
    int slice = -1;  // z-slice of a 3D table; -1: the middle one
    std::string curves;
    std::string along = "x";  // --curves: the axis the curves run along, x or z
    double at_x = NAN;        // --along z: the x coordinate of the curves (default: the middle texel)
    std::string plot;
    std::string output;
    bool half = false;
};

/// Where texel k sits: its coordinates on each axis, as "mu = 0.5, alpha = 0.25".
std::string where(const Table& t, size_t k) {
    const size_t x = k % size_t(t.width()), y = (k / size_t(t.width())) % size_t(t.height()),
                 z = k / (size_t(t.width()) * size_t(t.height()));
    std::string s = t.x.name + " = " + format_number(t.x.coordinate[x]);
    if (t.height() > 1) s += ", " + t.y.name + " = " + format_number(t.y.coordinate[y]);
    if (t.depth() > 1) s += ", " + t.z.name + " = " + format_number(t.z.coordinate[z]);
    return s;
}

struct Statistic {
    double min = 0, max = 0, mean = 0;
    size_t at_min = 0, at_max = 0;
};

Statistic statistic(const std::vector<double>& v) {
    Statistic s;
    s.min = s.max = v.front();
    double sum = 0;
    for (size_t k = 0; k < v.size(); ++k) {
        if (v[k] < s.min) s.min = v[s.at_min = k];
        if (v[k] > s.max) s.max = v[s.at_max = k];
        sum += v[k];
    }
    s.mean = sum / double(v.size());
    return s;
}

nlohmann::ordered_json axis_json(const Axis& a) {
    return {{"name", a.name}, {"mapping", a.mapping}, {"lo", a.lo},
            {"hi", a.hi},     {"size", a.size},       {"texels", texels_name(a.texels)}};
}

std::string render(const Table& t, Format format) {
    std::vector<Statistic> stats;
    for (const auto& v : t.values) stats.push_back(statistic(v));
    const Statistic err = statistic(t.error);
    if (format == Format::Json) {
        nlohmann::ordered_json j;
        j["kind"] = t.kind;
        j["quantity"] = t.quantity;
        j["axes"] = nlohmann::ordered_json::array();
        j["axes"].push_back(axis_json(t.x));
        if (t.height() > 1) j["axes"].push_back(axis_json(t.y));
        if (t.depth() > 1) j["axes"].push_back(axis_json(t.z));
        j["channels"] = nlohmann::ordered_json::array();
        for (size_t c = 0; c < t.channels.size(); ++c)
            j["channels"].push_back({{"name", t.channels[c]},
                                     {"min", stats[c].min},
                                     {"min_at", where(t, stats[c].at_min)},
                                     {"max", stats[c].max},
                                     {"max_at", where(t, stats[c].at_max)},
                                     {"mean", stats[c].mean}});
        j["max_error"] = err.max;
        j["max_error_at"] = where(t, err.at_max);
        j["attributes"] = t.attributes;
        return j.dump(2) + "\n";
    }
    std::ostringstream o;
    char line[512];
    o << t.kind << ": " << t.quantity << "\n";
    for (const Axis* a : {&t.x, &t.y, &t.z}) {
        if (a != &t.x && a->size == 1) continue;
        std::snprintf(line, sizeof line, "  axis %-10s %4d texels (%s) over [%s, %s], %s\n", a->name.c_str(), a->size,
                      texels_name(a->texels), format_number(a->lo).c_str(), format_number(a->hi).c_str(),
                      a->mapping.c_str());
        o << line;
    }
    // Values in the shortest text that reads back as them at the table's precision.
    for (size_t c = 0; c < t.channels.size(); ++c) {
        std::snprintf(line, sizeof line, "  channel %-8s ", t.channels[c].c_str());
        o << line << "min " << table_value_text(t, stats[c].min) << " (" << where(t, stats[c].at_min) << "), max "
          << table_value_text(t, stats[c].max) << " (" << where(t, stats[c].at_max) << "), mean "
          << table_value_text(t, stats[c].mean) << "\n";
    }
    o << "  max error " << table_value_text(t, err.max) << " at " << where(t, err.at_max) << "\n";
    for (const auto& kv : t.attributes) o << "  " << kv.first << ": " << kv.second << "\n";
    return o.str();
}

/// The z-slice `slice` of a 3D table as a 2D table (a 2D table is returned as it is).
Table slice_of(const Table& t, int slice) {
    if (t.depth() == 1) {
        if (slice > 0) throw Error("--slice: the table is not 3D");
        return t;
    }
    const int z = slice < 0 ? t.depth() / 2 : slice;
    if (z >= t.depth())
        throw Error("--slice " + std::to_string(slice) + ": the table has " + std::to_string(t.depth()) +
                    " slices along " + t.z.name + " (0 to " + std::to_string(t.depth() - 1) + ")");
    Table s = t;
    const size_t n = size_t(t.width()) * size_t(t.height()), from = size_t(z) * n;
    for (auto& v : s.values) v = std::vector<double>(v.begin() + long(from), v.begin() + long(from + n));
    s.error = std::vector<double>(t.error.begin() + long(from), t.error.begin() + long(from + n));
    s.attributes["slice"] = t.z.name + " = " + format_number(t.z.coordinate[size_t(z)]) + " (z texel " +
                            std::to_string(z) + " of " + std::to_string(t.depth()) + ")";
    s.z = make_axis(t.z.name, t.z.mapping, t.z.coordinate[size_t(z)], t.z.coordinate[size_t(z)], 1);
    return s;
}

/// The texel of `axis` whose coordinate is nearest v.
size_t nearest(const Axis& axis, double v) {
    size_t best = 0;
    for (size_t j = 1; j < axis.coordinate.size(); ++j)
        if (std::fabs(axis.coordinate[j] - v) < std::fabs(axis.coordinate[best] - v)) best = j;
    return best;
}

/// Each channel of a 3D table along its z axis (eta) at the y texels nearest `at` and the x texel
/// nearest at_x (the middle one if NaN).
void write_curves_along_z(const Table& t, const std::vector<double>& at, double at_x, const std::string& path) {
    if (t.depth() == 1) throw Error("--along z: the table is not 3D");
    const size_t x = std::isnan(at_x) ? size_t(t.width() / 2) : nearest(t.x, at_x);
    PlotSpec p;
    p.title = plot_text(t.kind + " along " + t.z.name + " at " + t.x.name + " = " + format_number(t.x.coordinate[x]));
    p.x.label = axis_label(t.z);
    p.y.label = t.channels.size() == 1 ? plot_text(t.channels[0]) : "value";
    p.legend = LegendPlace::Outside;
    for (double v : at) {
        const size_t y = nearest(t.y, v);
        for (size_t c = 0; c < t.channels.size(); ++c) {
            Curve curve;
            curve.label = plot_text((t.channels.size() > 1 ? t.channels[c] + ", " : std::string()) + t.y.name + " = " +
                                    format_number(t.y.coordinate[y]));
            curve.x = t.z.coordinate;
            for (int z = 0; z < t.depth(); ++z)
                curve.y.push_back(t.values[c][(size_t(z) * size_t(t.height()) + y) * size_t(t.width()) + x]);
            p.curves.push_back(curve);
        }
    }
    write_plot(path, p, 1200, 640);
}

/// Each channel along the x axis at the y texels nearest `at` (values of the y coordinate).
void write_curves(const Table& t, const std::vector<double>& at, const std::string& path) {
    if (t.height() == 1) throw Error("--curves: a 1D table has one curve; drop --curves");
    PlotSpec p;
    p.title = t.kind + (t.attributes.count("model") ? ": " + t.attributes.at("model") : std::string());
    p.x.label = t.x.name;
    p.y.label = t.channels.size() == 1 ? t.channels[0] : "value";
    for (double v : at) {
        size_t best = 0;
        for (size_t j = 1; j < t.y.coordinate.size(); ++j)
            if (std::fabs(t.y.coordinate[j] - v) < std::fabs(t.y.coordinate[best] - v)) best = j;
        for (size_t c = 0; c < t.channels.size(); ++c) {
            Curve curve;
            curve.label = (t.channels.size() > 1 ? t.channels[c] + ", " : std::string()) + t.y.name + " = " +
                          format_number(t.y.coordinate[best]);
            curve.x = t.x.coordinate;
            for (int i = 0; i < t.width(); ++i) curve.y.push_back(t.values[c][best * size_t(t.width()) + size_t(i)]);
            p.curves.push_back(curve);
        }
    }
    write_plot(path, p);
}

int run_show(const ShowOptions& o, const GlobalOptions&) {
    const Format format = parse_format(o.format);
    if (format == Format::Csv) throw Error("--format: show prints a table or JSON; -o FILE.csv converts the table");
    check_plot_output(o.plot, "--plot");
    if (!o.output.empty()) check_table_path(o.output);
    std::vector<double> curves;
    if (!o.curves.empty()) {
        if (o.plot.empty()) throw Error("--curves draws a plot; give --plot FILE.png or FILE.svg");
        curves = parse_number_list(o.curves, "--curves");
    }
    if (o.slice < -1) throw Error("--slice must be a z texel index (0 or more)");
    if (o.along != "x" && o.along != "z") throw Error("--along must be x or z");
    if (o.along == "z" && curves.empty()) throw Error("--along z draws curves; give --curves Y1,Y2,... and --plot");
    const Table t = read_table(o.table);
    const Table slice = slice_of(t, o.slice);  // checks --slice before anything is written
    std::cout << render(t, format);
    OutputGroup together;  // the picture and the converted table land together or not at all
    if (!o.plot.empty()) {
        if (curves.empty())
            write_table_preview(o.slice < 0 ? t : slice, o.plot, -1, PreviewLayout::Full);  // every slice, or the one asked for
        else
            o.along == "z" ? write_curves_along_z(t, curves, o.at_x, o.plot) : write_curves(slice, curves, o.plot);
    }
    if (!o.output.empty()) {
        write_table(t, o.output, o.half);
    }
    together.commit();
    if (!o.plot.empty()) std::fprintf(stderr, "brdfbake: wrote %s\n", o.plot.c_str());
    if (!o.output.empty()) std::fprintf(stderr, "brdfbake: wrote %s\n", o.output.c_str());
    return kExitOk;
}

}  // namespace

void add_show_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<ShowOptions>(
        app, "show", "what a table file holds (header, axes, statistics), a picture of a slice, or a conversion",
        global, action, run_show);
    cmd->add_option("table", o->table, "a table brdfbake wrote: .exr, .csv, .npy or .png")->required();
    add_format_option(cmd, o->format, {"table", "json"});
    cmd->add_option("--slice", o->slice,
                    "z texel of a 3D table to draw (default: every slice as a small multiple; --curves: the middle one)");
    cmd->add_option("--curves", o->curves, "draw each channel along x at these values of the y axis (with --plot)");
    cmd->add_option("--along", o->along, "--curves run along x (default) or z, the eta axis of a 3D table")
        ->capture_default_str();
    cmd->add_option("--at", o->at_x, "with --along z: the x coordinate of the curves (default: the middle texel)");
    cmd->add_option("--plot", o->plot, "a picture of the slice (.png or .svg): its preview, or --curves");
    cmd->add_option("-o,--output", o->output, "convert: write the table as .exr, .csv, .h, .png, .npy, .js (three.js), .inc (Filament) or .tables (Cycles)");
    cmd->add_flag("--half", o->half, "with -o FILE.exr: half-float channels");
}

}  // namespace brdfbake

#include "brdfbake/table.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <unistd.h>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/version.h"

namespace brdfbake {

bool is_double_table(const Table& t) {
    const auto p = t.attributes.find("precision");
    return p != t.attributes.end() && p->second == "double";
}

std::string table_value_text(const Table& t, double v) { return round_trip_text(v, !is_double_table(t)); }

double Table::max_error() const {
    double m = 0.0;
    for (double e : error) m = std::max(m, e);
    return m;
}

Texels parse_texels(const std::string& text) {
    if (text == "centre" || text == "center") return Texels::Centre;
    if (text == "edge") return Texels::Edge;
    throw Error("--texels must be centre or edge, not '" + text + "'");
}

const char* texels_name(Texels texels) { return texels == Texels::Edge ? "edge" : "centre"; }

Axis make_axis(const std::string& name, const std::string& mapping, double lo, double hi, int size, Texels texels) {
    if (texels == Texels::Edge && size < 2)
        throw Error("edge texels need at least 2 texels on the " + name + " axis (one texel cannot sit on both ends)");
    Axis a;
    a.name = name;
    a.mapping = mapping;
    a.lo = lo;
    a.hi = hi;
    a.size = size;
    a.texels = texels;
    for (int i = 0; i < size; ++i) {
        const double t = texels == Texels::Edge ? double(i) / (size - 1) : (i + 0.5) / size;
        // The ends exactly: lo + (hi - lo) * 1 may round away from hi.
        a.coordinate.push_back(texels == Texels::Edge && i == size - 1 ? hi : lo + (hi - lo) * t);
    }
    return a;
}

namespace {

Axis& axis_at(Table& t, int which) { return which == 0 ? t.x : which == 1 ? t.y : t.z; }

}  // namespace

void arrange_axes(Table& t, const std::vector<std::string>& order, const std::vector<std::string>& flip) {
    const int n = t.depth() > 1 ? 3 : t.height() > 1 ? 2 : 1;
    auto find = [&](const std::string& name, const char* option) {
        for (int a = 0; a < 3; ++a)
            if (axis_at(t, a).name == name && (a < n || axis_at(t, a).size > 1)) return a;
        std::string known;
        for (int a = 0; a < n; ++a) known += (known.empty() ? "" : ", ") + axis_at(t, a).name;
        throw Error(std::string(option) + ": the " + t.kind + " table has no axis '" + name + "'; its axes: " + known);
    };
    std::vector<int> perm;  // new axis k is old axis perm[k]
    if (order.empty()) {
        for (int a = 0; a < n; ++a) perm.push_back(a);
    } else {
        if (int(order.size()) != n)
            throw Error("--axes: the " + t.kind + " table has " + std::to_string(n) + " axes; name each once (got " +
                        std::to_string(order.size()) + ")");
        for (const auto& name : order) {
            const int a = find(name, "--axes");
            if (std::find(perm.begin(), perm.end(), a) != perm.end()) throw Error("--axes: '" + name + "' is named twice");
            perm.push_back(a);
        }
    }
    std::vector<bool> flipped(3, false);
    for (const auto& name : flip) {
        const int a = find(name, "--flip");
        if (flipped[a]) throw Error("--flip: '" + name + "' is named twice");
        flipped[a] = true;
    }
    bool identity = true;
    for (int k = 0; k < n; ++k) identity = identity && perm[k] == k && !flipped[k];
    if (identity) return;
    const Axis old[3] = {t.x, t.y, t.z};
    const int size[3] = {old[0].size, old[1].size, old[2].size};
    for (int k = n; k < 3; ++k) perm.push_back(k);  // the axes of size 1 stay where they are
    auto moved = [&](const std::vector<double>& v) {
        if (v.empty()) return v;  // a table's shape without values (lut_table_shape)
        std::vector<double> out(v.size());
        int idx[3];
        for (idx[2] = 0; idx[2] < size[perm[2]]; ++idx[2])
            for (idx[1] = 0; idx[1] < size[perm[1]]; ++idx[1])
                for (idx[0] = 0; idx[0] < size[perm[0]]; ++idx[0]) {
                    int src[3] = {0, 0, 0};
                    for (int k = 0; k < 3; ++k) {
                        const int a = perm[k];
                        src[a] = flipped[a] ? size[a] - 1 - idx[k] : idx[k];
                    }
                    const size_t from = (size_t(src[2]) * size[1] + src[1]) * size[0] + src[0];
                    const size_t to = (size_t(idx[2]) * size[perm[1]] + idx[1]) * size[perm[0]] + idx[0];
                    out[to] = v[from];
                }
        return out;
    };
    for (auto& v : t.values) v = moved(v);
    t.error = moved(t.error);
    for (int k = 0; k < 3; ++k) {
        Axis a = old[perm[k]];
        if (flipped[perm[k]]) {
            std::swap(a.lo, a.hi);
            std::reverse(a.coordinate.begin(), a.coordinate.end());
            std::reverse(a.parameter.begin(), a.parameter.end());
        }
        axis_at(t, k) = a;
    }
}

std::vector<int> rgba_view(const Table& t) {
    switch (t.values.size()) {
        case 1: return {0, 0, 0, -1};
        case 2: return {0, 1, -1, -1};
        case 3: return {0, 1, 2, -1};
        case 4: return {0, 1, 2, 3};
        default: return {};
    }
}

std::string rgba_view_text(const Table& t) {
    const std::vector<int> view = rgba_view(t);
    if (view.empty()) return "none (more than four value channels)";
    std::string s;
    const char* slot[4] = {"R", "G", "B", "A"};
    for (int k = 0; k < 4; ++k) {
        if (k == 3 && view[k] < 0) break;
        s += std::string(k ? ", " : "") + slot[k] + " = " + (view[k] < 0 ? std::string("0") : t.channels[size_t(view[k])]);
    }
    return s;
}

void check_finite(const Table& t) {
    const size_t n = size_t(t.width()) * t.image_height();
    if (t.error.size() != n) throw Error("internal error: table '" + t.kind + "' has a wrong error channel size");
    for (size_t c = 0; c < t.values.size(); ++c) {
        if (t.values[c].size() != n) throw Error("internal error: table '" + t.kind + "' has a wrong channel size");
        for (size_t i = 0; i < n; ++i)
            if (!std::isfinite(t.values[c][i]) || !std::isfinite(t.error[i]))
                throw Error("table '" + t.kind + "': non-finite value in channel " + t.channels[c] + " at texel (" +
                            std::to_string(i % t.width()) + ", " + std::to_string(i / t.width()) +
                            "); nothing was written");
    }
}

namespace {

std::string number(double v) { return round_trip_text(v); }

/// The texel convention of an axis, in words.
std::string texel_text(const Axis& ax) {
    const std::string t = ax.texels == Texels::Edge ? "i / (size - 1) (edges: the first and last texel on the range's ends)"
                                                    : "(i + 0.5) / size (texel centres)";
    return "texel i holds coordinate lo + (hi - lo) t, t = " + t;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> table_description(const Table& t) {
    std::vector<std::pair<std::string, std::string>> a;
    a.emplace_back("kind", t.kind);
    a.emplace_back("quantity", t.quantity);
    for (const auto& kv : t.attributes) a.emplace_back(kv.first, kv.second);
    bool all_centres = true;
    auto axis = [&](const char* which, const Axis& ax) {
        a.emplace_back(std::string(which) + "_axis", ax.name);
        a.emplace_back(std::string(which) + "_mapping", ax.mapping);
        a.emplace_back(std::string(which) + "_range", number(ax.lo) + " " + number(ax.hi));
        a.emplace_back(std::string(which) + "_size", std::to_string(ax.size));
        if (ax.texels == Texels::Edge) a.emplace_back(std::string(which) + "_texels", texel_text(ax));
        if (ax.lo > ax.hi) a.emplace_back(std::string(which) + "_flipped", "texel 0 holds the range's upper end");
        all_centres = all_centres && ax.texels == Texels::Centre;
    };
    axis("x", t.x);
    if (t.height() > 1) axis("y", t.y);
    if (t.depth() > 1) {
        axis("z", t.z);
        a.emplace_back("layout", "3D: the " + std::to_string(t.depth()) + " z-slices are stacked along y; image row = z * " +
                                     std::to_string(t.height()) + " + y");
    }
    a.emplace_back("texel_convention", all_centres ? "texel i holds coordinate lo + (hi - lo)(i + 0.5)/size (texel centres)"
                                                   : "per axis (see x_texels, y_texels, z_texels); an axis without "
                                                     "one has texel centres, t = (i + 0.5) / size");
    std::string ch;
    for (const auto& c : t.channels) ch += (ch.empty() ? "" : " ") + c;
    a.emplace_back("channels", ch + " error");
    a.emplace_back("rgba_view", rgba_view_text(t));
    a.emplace_back("error_meaning", "estimated absolute error of the texel (max over channels): "
                                    "3 standard errors of the replicas plus 3 |E| / N (sampling) or the difference "
                                    "from the half-order rule (quadrature), plus a floating-point bound");
    a.emplace_back("max_error", table_value_text(t, t.max_error()));
    a.emplace_back("tool", std::string("brdfbake ") + BRDFBAKE_VERSION);
    return a;
}

std::string c_identifier(const std::string& name) {
    std::string out;
    for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return out;
}

std::string c_float_literal(double v, bool as_float) {
    // A float literal: the float nearest v (the nearest to v's 9 digits may be its neighbour).
    std::string literal = round_trip_text(as_float ? double(float(v)) : v, as_float);
    if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
    return as_float ? literal + "f" : literal;
}

std::string comment_line_text(const std::string& line) {
    std::string text = line;
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    if (!text.empty() && text.back() == '\\') text += '.';
    return text;
}

namespace {

std::string extension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot + 1);
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

/// An OpenEXR output stream into memory.
class MemoryStream : public Imf::OStream {
public:
    explicit MemoryStream(const std::string& name) : Imf::OStream(name.c_str()) {}
    void write(const char c[], int n) override {
        if (pos_ + size_t(n) > data.size()) data.resize(pos_ + size_t(n));
        std::memcpy(&data[pos_], c, size_t(n));
        pos_ += size_t(n);
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = size_t(pos); }
    std::string data;

private:
    size_t pos_ = 0;
};

}  // namespace

void write_exr(const Table& t, const std::string& path, bool half) {
    const int w = t.width(), h = t.image_height();
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& kv : table_description(t)) header.insert("brdfbake:" + kv.first, Imf::StringAttribute(kv.second));
    header.insert("brdfbake:max_error_value", Imf::FloatAttribute(float(t.max_error())));
    // The axes' per-texel parameters (alpha of a roughness axis, mu raised to its floor), which
    // the description gives only as a mapping in words: read_table restores them.
    for (const auto& [which, ax] : {std::pair<const char*, const Axis*>{"x", &t.x}, {"y", &t.y}, {"z", &t.z}}) {
        if (ax->parameter.size() != ax->coordinate.size() || (ax != &t.x && ax->size == 1)) continue;
        std::string values;
        char b[32];
        for (double v : ax->parameter) {
            std::snprintf(b, sizeof b, "%.17g", v);
            values += (values.empty() ? "" : " ") + std::string(b);
        }
        header.insert(std::string("brdfbake:") + which + "_parameter_values", Imf::StringAttribute(values));
        header.insert(std::string("brdfbake:") + which + "_parameter_name",
                      Imf::StringAttribute(ax->parameter_name.empty() ? ax->name : ax->parameter_name));
    }
    const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;

    // The channels: the RGB(A) view that a generic RGBA reader (Imf::RgbaInputFile) returns, then
    // every value channel under its name (under the layer "KIND." where its name is one of the
    // RGBA names but holds another channel: dfg's A and B), then the error, which RGBA readers
    // ignore. The frame buffer's pixel type must match the channel's: convert on the host.
    std::vector<const std::vector<double>*> sources;
    std::vector<std::string> names;
    const std::vector<int> view = rgba_view(t);
    const char* const slot[4] = {"R", "G", "B", "A"};
    for (size_t k = 0; k < view.size(); ++k)
        if (view[k] >= 0) {
            names.push_back(slot[k]);
            sources.push_back(&t.values[size_t(view[k])]);
        }
    for (size_t c = 0; c < t.channels.size(); ++c) {
        const std::string& name = t.channels[c];
        const auto same = std::find(names.begin(), names.end(), name);
        if (same != names.end()) {
            if (sources[size_t(same - names.begin())] == &t.values[c]) continue;  // the view slot holds it
            names.push_back(t.kind + "." + name);
        } else if (name == "R" || name == "G" || name == "B" || name == "A" || name == "Y") {
            names.push_back(t.kind + "." + name);
        } else {
            names.push_back(name);
        }
        sources.push_back(&t.values[c]);
    }
    names.push_back("error");
    sources.push_back(&t.error);
    std::string listing;
    for (const auto& n : names) listing += (listing.empty() ? "" : " ") + n;
    header.insert("brdfbake:exr_channels", Imf::StringAttribute(listing));
    std::vector<std::vector<float>> planes32;
    std::vector<std::vector<Imath::half>> planes16;
    planes32.reserve(names.size());
    planes16.reserve(names.size());
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
        header.channels().insert(names[c], Imf::Channel(type));
        char* base;
        size_t size;
        if (half) {
            planes16.emplace_back(sources[c]->begin(), sources[c]->end());
            base = reinterpret_cast<char*>(planes16.back().data());
            size = sizeof(Imath::half);
        } else {
            planes32.emplace_back(sources[c]->begin(), sources[c]->end());
            base = reinterpret_cast<char*>(planes32.back().data());
            size = sizeof(float);
        }
        fb.insert(names[c], Imf::Slice(type, base, size, size * size_t(w)));
    }
    // Encoded in memory, then written with every write checked: OpenEXR's file stream finishes
    // the file (its offset table) in a destructor that cannot report a full disk.
    MemoryStream bytes(path);
    try {
        Imf::OutputFile file(bytes, header);
        file.setFrameBuffer(fb);
        file.writePixels(h);
    } catch (const std::exception& e) {
        throw Error("cannot write '" + path + "': " + e.what());
    }
    write_file_atomically(path, bytes.data);
}

std::string table_csv(const Table& t) {
    std::ostringstream o;
    for (const auto& kv : table_description(t)) o << "# " << kv.first << ": " << kv.second << "\n";
    // Per axis: its coordinate under the axis's name, then the parameter the mapping derives
    // from it under the parameter's name where the two differ (roughness, then alpha).
    std::vector<const Axis*> axes = {&t.x};
    if (t.height() > 1) axes.push_back(&t.y);
    if (t.depth() > 1) axes.push_back(&t.z);
    // A parameter named as its coordinate but computed elsewhere (mu raised to its floor) goes
    // under NAME_computed.
    auto derived = [](const Axis& a) {
        return !a.parameter_name.empty() && a.parameter.size() == a.coordinate.size() &&
               (a.parameter_name != a.name || a.parameter != a.coordinate);
    };
    std::string head;
    for (const Axis* a : axes) {
        head += (head.empty() ? "" : ",") + a->name;
        if (derived(*a)) head += "," + a->parameter_name + (a->parameter_name == a->name ? "_computed" : "");
    }
    o << head;
    for (const auto& c : t.channels) o << "," << c;
    o << ",error\n";
    const bool as_float = !is_double_table(t);
    auto put = [&](const Axis& a, int i, bool first) {
        o << (first ? "" : ",") << round_trip_text(a.coordinate[size_t(i)]);
        if (derived(a)) o << "," << round_trip_text(a.parameter[size_t(i)]);
    };
    for (int l = 0; l < t.depth(); ++l)
        for (int j = 0; j < t.height(); ++j)
            for (int i = 0; i < t.width(); ++i) {
                const size_t k = (size_t(l) * t.height() + j) * t.width() + i;
                put(t.x, i, true);
                if (t.height() > 1) put(t.y, j, false);
                if (t.depth() > 1) put(t.z, l, false);
                for (const auto& v : t.values) o << "," << round_trip_text(v[k], as_float);
                o << "," << round_trip_text(t.error[k], as_float) << "\n";
            }
    return o.str();
}

std::string table_header(const Table& t, const std::string& symbol) {
    // A double table's arrays are double, a float table's float: each value in the shortest
    // text that reads back as it, always a floating literal (1.0f, never 1f, which C rejects).
    const bool as_float = !is_double_table(t);
    const char* type = as_float ? "float" : "double";
    std::ostringstream o;
    o << "// Generated by brdfbake; one " << type << " per texel, row-major: index = (z * " << t.height()
      << " + y) * " << t.width() << " + x.\n";
    for (const auto& kv : table_description(t)) {
        // A comment line: no line break inside, and no final backslash (which would splice the next line in).
        o << "// " << kv.first << ": " << comment_line_text(kv.second) << "\n";
    }
    o << "#pragma once\n\n";
    o << "static const int " << symbol << "_width = " << t.width() << ";\n";
    o << "static const int " << symbol << "_height = " << t.height() << ";\n";
    o << "static const int " << symbol << "_depth = " << t.depth() << ";\n";
    auto array = [&](const std::string& name, const std::vector<double>& v) {
        o << "static const " << type << " " << symbol << "_" << name << "[" << v.size() << "] = {";
        for (size_t i = 0; i < v.size(); ++i)
            o << (i % 8 == 0 ? "\n    " : " ") << c_float_literal(v[i], as_float) << (i + 1 < v.size() ? "," : "");
        o << "\n};\n";
    };
    for (size_t c = 0; c < t.channels.size(); ++c) array(c_identifier(t.channels[c]), t.values[c]);
    array("error", t.error);
    return o.str();
}

namespace {

/// A file format of write_table: its extension, what the refusal's list says of it, and its writer.
struct TableFormat {
    const char* extension;
    const char* note;  // "" or "(three.js)"
    void (*write)(const Table& t, const std::string& path, bool half);
    /// What the format refuses by the table's shape (channels, axes, model; no value read), or
    /// nullptr: it holds every table. write_table and check_table_format both run it.
    void (*check)(const Table& shape);
};

/// A C identifier from the file name's stem: brdfbake_<stem> (a header), table_<stem> (Cycles).
std::string stem_identifier(const std::string& path) {
    std::string stem = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
    return c_identifier(stem.substr(0, stem.find('.')));
}

void write_text(const std::string& path, const std::string& text) { write_file_atomically(path, text); }
void write_c_header(const Table& t, const std::string& p, bool) {
    write_text(p, table_header(t, "brdfbake_" + stem_identifier(p)));
}

/// Every format, by extension: the one place check_table_path and write_table read.
const std::vector<TableFormat>& table_formats() {
    using T = const Table&;
    using P = const std::string&;
    static const std::vector<TableFormat> formats = {
        {"exr", "", [](T t, P p, bool half) { write_exr(t, p, half); }, nullptr},
        {"csv", "", [](T t, P p, bool) { write_text(p, table_csv(t)); }, nullptr},
        {"h", "", write_c_header, nullptr},
        {"hpp", "", write_c_header, nullptr},
        {"png", "", [](T t, P p, bool) { write_png16(t, p); }, check_png_table},
        {"npy", "", [](T t, P p, bool) { write_npy(t, p); }, nullptr},
        {"js", "(three.js)", [](T t, P p, bool) { write_text(p, table_threejs_module(t)); }, check_threejs_table},
        {"inc", "(Filament)", [](T t, P p, bool) { write_text(p, table_filament_include(t)); }, check_filament_table},
        {"tables", "(Cycles)", [](T t, P p, bool) { write_text(p, table_cycles_tables(t, stem_identifier(p))); }, nullptr},
        {"cc", "(Blender EEVEE, 4.2 and later)", [](T t, P p, bool) { write_text(p, table_eevee_source(t, false)); },
         [](T t) { check_eevee_table(t, false); }},
        {"c", "(legacy EEVEE, Blender 2.80 to 4.1)", [](T t, P p, bool) { write_text(p, table_eevee_source(t, true)); },
         [](T t) { check_eevee_table(t, true); }},
        {"cs", "(Unity HDRP)", [](T t, P p, bool) { write_text(p, table_unity_hdrp_source(t)); }, check_unity_hdrp_table},
    };
    return formats;
}

const TableFormat* table_format(const std::string& path) {
    const std::string ext = extension(path);
    for (const TableFormat& f : table_formats())
        if (ext == f.extension) return &f;
    return nullptr;
}

}  // namespace

void check_table_path(const std::string& path) {
    if (!table_format(path)) {
        std::string known;
        const std::vector<TableFormat>& formats = table_formats();
        for (size_t k = 0; k < formats.size(); ++k)
            known += std::string(k == 0 ? "" : k + 1 == formats.size() ? " or " : ", ") + "." + formats[k].extension +
                     (*formats[k].note ? std::string(" ") + formats[k].note : "");
        throw Error("cannot tell the table format from '" + path + "': use " + known);
    }
    check_output_path(path);
    if (extension(path) == "npy") check_output_path(path + ".json");
}

void check_table_format(const Table& shape, const std::string& path) {
    check_table_path(path);
    const TableFormat* f = table_format(path);
    if (f->check) f->check(shape);
}

void write_table(const Table& t, const std::string& path, bool half) {
    check_table_format(t, path);
    check_finite(t);
    table_format(path)->write(t, path, half);
}

}  // namespace brdfbake

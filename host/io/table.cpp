#include "brdfbake/table.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <unistd.h>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/version.h"

namespace brdfbake {

double Table::max_error() const {
    double m = 0.0;
    for (double e : error) m = std::max(m, e);
    return m;
}

Axis make_axis(const std::string& name, const std::string& mapping, double lo, double hi, int size) {
    Axis a;
    a.name = name;
    a.mapping = mapping;
    a.lo = lo;
    a.hi = hi;
    a.size = size;
    for (int i = 0; i < size; ++i) a.coordinate.push_back(lo + (hi - lo) * (i + 0.5) / size);
    return a;
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

// The attributes every format carries, in a stable order.
std::vector<std::pair<std::string, std::string>> describe(const Table& t) {
    std::vector<std::pair<std::string, std::string>> a;
    auto num = [](double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%.9g", v);
        return std::string(b);
    };
    a.emplace_back("kind", t.kind);
    a.emplace_back("quantity", t.quantity);
    for (const auto& kv : t.attributes) a.emplace_back(kv.first, kv.second);
    auto axis = [&](const char* which, const Axis& ax) {
        a.emplace_back(std::string(which) + "_axis", ax.name);
        a.emplace_back(std::string(which) + "_mapping", ax.mapping);
        a.emplace_back(std::string(which) + "_range", num(ax.lo) + " " + num(ax.hi));
        a.emplace_back(std::string(which) + "_size", std::to_string(ax.size));
    };
    axis("x", t.x);
    if (t.height() > 1) axis("y", t.y);
    if (t.depth() > 1) {
        axis("z", t.z);
        a.emplace_back("layout", "3D: the " + std::to_string(t.depth()) + " z-slices are stacked along y; image row = z * " +
                                     std::to_string(t.height()) + " + y");
    }
    a.emplace_back("texel_convention", "texel i holds coordinate lo + (hi - lo)(i + 0.5)/size (texel centres)");
    std::string ch;
    for (const auto& c : t.channels) ch += (ch.empty() ? "" : " ") + c;
    a.emplace_back("channels", ch + " error");
    a.emplace_back("error_meaning", "estimated absolute error of the texel (max over channels): "
                                    "3 standard errors of the replicas plus 3 |E| / N (sampling) or the difference "
                                    "from the half-order rule (quadrature), plus a floating-point bound");
    a.emplace_back("max_error", num(t.max_error()));
    a.emplace_back("tool", std::string("brdfbake ") + BRDFBAKE_VERSION);
    return a;
}

std::string extension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot + 1);
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace

void write_exr(const Table& t, const std::string& path, bool half) {
    const int w = t.width(), h = t.image_height();
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& kv : describe(t)) header.insert("brdfbake:" + kv.first, Imf::StringAttribute(kv.second));
    header.insert("brdfbake:max_error_value", Imf::FloatAttribute(float(t.max_error())));
    const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;

    // The frame buffer's pixel type must match the channel's: convert on the host.
    std::vector<std::vector<double>> sources = t.values;
    sources.push_back(t.error);
    std::vector<std::string> names = t.channels;
    names.push_back("error");
    std::vector<std::vector<float>> planes32;
    std::vector<std::vector<Imath::half>> planes16;
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
        header.channels().insert(names[c], Imf::Channel(type));
        char* base;
        size_t size;
        if (half) {
            planes16.emplace_back(sources[c].begin(), sources[c].end());
            base = reinterpret_cast<char*>(planes16.back().data());
            size = sizeof(Imath::half);
        } else {
            planes32.emplace_back(sources[c].begin(), sources[c].end());
            base = reinterpret_cast<char*>(planes32.back().data());
            size = sizeof(float);
        }
        fb.insert(names[c], Imf::Slice(type, base, size, size * size_t(w)));
    }
    const OutputFile out = prepare_output(path);
    try {
        Imf::OutputFile file(out.temporary.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(h);
    } catch (const std::exception& e) {
        std::remove(out.temporary.c_str());
        throw Error("cannot write '" + path + "': " + e.what());
    }
    commit_output(out, path);
}

std::string table_csv(const Table& t) {
    std::ostringstream o;
    for (const auto& kv : describe(t)) o << "# " << kv.first << ": " << kv.second << "\n";
    o << t.x.name;
    if (t.height() > 1) o << "," << t.y.name;
    if (t.depth() > 1) o << "," << t.z.name;
    for (const auto& c : t.channels) o << "," << c;
    o << ",error\n";
    char b[64];
    for (int l = 0; l < t.depth(); ++l)
    for (int j = 0; j < t.height(); ++j)
        for (int i = 0; i < t.width(); ++i) {
            const size_t k = (size_t(l) * t.height() + j) * t.width() + i;
            std::snprintf(b, sizeof b, "%.9g", t.x.parameter[i]);
            o << b;
            if (t.height() > 1) {
                std::snprintf(b, sizeof b, ",%.9g", t.y.parameter[j]);
                o << b;
            }
            if (t.depth() > 1) {
                std::snprintf(b, sizeof b, ",%.9g", t.z.parameter[l]);
                o << b;
            }
            for (const auto& v : t.values) {
                std::snprintf(b, sizeof b, ",%.9g", v[k]);
                o << b;
            }
            std::snprintf(b, sizeof b, ",%.3e\n", t.error[k]);
            o << b;
        }
    return o.str();
}

std::string table_header(const Table& t, const std::string& symbol) {
    std::ostringstream o;
    o << "// Generated by brdfbake; one float per texel, row-major: index = (z * " << t.height() << " + y) * "
      << t.width() << " + x.\n";
    for (const auto& kv : describe(t)) o << "// " << kv.first << ": " << kv.second << "\n";
    o << "#pragma once\n\n";
    o << "static const int " << symbol << "_width = " << t.width() << ";\n";
    o << "static const int " << symbol << "_height = " << t.height() << ";\n";
    o << "static const int " << symbol << "_depth = " << t.depth() << ";\n";
    char b[32];
    auto array = [&](const std::string& name, const std::vector<double>& v) {
        o << "static const float " << symbol << "_" << name << "[" << v.size() << "] = {";
        for (size_t i = 0; i < v.size(); ++i) {
            std::snprintf(b, sizeof b, "%.9gf", v[i]);
            o << (i % 8 == 0 ? "\n    " : " ") << b << (i + 1 < v.size() ? "," : "");
        }
        o << "\n};\n";
    };
    for (size_t c = 0; c < t.channels.size(); ++c) array(t.channels[c], t.values[c]);
    array("error", t.error);
    return o.str();
}

void check_table_path(const std::string& path) {
    const std::string ext = extension(path);
    if (ext != "exr" && ext != "csv" && ext != "h" && ext != "hpp")
        throw Error("cannot tell the table format from '" + path + "': use .exr, .csv or .h");
    check_output_path(path);
}

void write_table(const Table& t, const std::string& path, bool half) {
    check_table_path(path);
    check_finite(t);
    const std::string ext = extension(path);
    if (ext == "exr") return write_exr(t, path, half);
    if (ext == "csv") return write_file_atomically(path, table_csv(t));
    if (ext == "h" || ext == "hpp") {
        // A C identifier from the file name: brdfbake_<stem>.
        std::string stem = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
        stem = stem.substr(0, stem.find('.'));
        std::string symbol = "brdfbake_";
        for (char c : stem) symbol += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
        return write_file_atomically(path, table_header(t, symbol));
    }
    write_file_atomically(path, table_csv(t));
}

}  // namespace brdfbake

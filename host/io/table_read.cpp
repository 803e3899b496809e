// Reading back a table that write_table wrote (.exr, .csv, .npy with its .json sidecar, 16-bit
// .png): the description (the brdfbake:* header, the CSV's "# key: value" lines, the sidecar's
// "description", the PNG's brdfbake:* tEXt chunks) gives the kind, the axes and the channels;
// the data gives values and error.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <nlohmann/json.hpp>
#include <png.h>

#include <cctype>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "brdfbake/error.h"
#include "brdfbake/table.h"
#include "io/png_memory.h"
#include "models/csv_text.h"
#include "models/input_file.h"

namespace brdfbake {

namespace {

using Description = std::map<std::string, std::string>;

constexpr std::uintmax_t kMaxTableFileBytes = std::uintmax_t(4) << 30;

std::string lower_extension(const std::string& path) {
    const size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot + 1);
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

std::vector<std::string> words(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

/// A number of the file's text; one that is not finite is refused here unless `finite_only` is
/// false (a texel's value: check_read_values then names its channel and texel).
double number_of(const std::string& text, const std::string& path, const std::string& what, bool finite_only = true) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw Error("'" + path + "': " + what + " '" + text + "' is not a number");
    if (finite_only && !std::isfinite(v)) throw Error("'" + path + "': " + what + " '" + text + "' is not a finite number");
    return v;
}

// The largest axis a reader takes: beyond every table brdfbake writes (a 4 GiB file holds fewer texels).
constexpr int kMaxAxisSize = 1 << 20;

/// Every value and error read is a finite number, every error non-negative: a file that holds
/// NaN or Inf was not written by brdfbake (check_finite refuses them) and is refused by name.
void check_read_values(const Table& t, const std::string& path) {
    const size_t n = size_t(t.width()) * size_t(t.image_height());
    auto where = [&](size_t k) {
        std::string s = "texel (" + std::to_string(k % size_t(t.width())) + ", " +
                        std::to_string((k / size_t(t.width())) % size_t(t.height()));
        if (t.depth() > 1) s += ", " + std::to_string(k / (size_t(t.width()) * size_t(t.height())));
        return s + ")";
    };
    for (size_t k = 0; k < n; ++k) {
        for (size_t c = 0; c < t.values.size(); ++c)
            if (!std::isfinite(t.values[c][k]))
                throw Error("'" + path + "': channel " + t.channels[c] + " holds " + std::to_string(t.values[c][k]) +
                            " at " + where(k) + "; a table holds finite values");
        if (!std::isfinite(t.error[k]) || t.error[k] < 0.0)
            throw Error("'" + path + "': the error channel holds " + std::to_string(t.error[k]) + " at " + where(k) +
                        "; an error estimate is a finite number, 0 or more");
    }
}

/// The table's kind, quantity, axes (coordinates recomputed from range, size and texels; the
/// parameters are the caller's) and channel names from a description; every other key is an
/// attribute.
Table table_from_description(const Description& d, const std::string& path) {
    auto get = [&](const std::string& key) -> const std::string& {
        const auto it = d.find(key);
        if (it == d.end()) throw Error("'" + path + "' is not a brdfbake table: its description has no '" + key + "'");
        return it->second;
    };
    Table t;
    t.kind = get("kind");
    t.quantity = get("quantity");
    std::set<std::string> structural = {"kind",          "quantity", "layout",    "texel_convention", "channels",
                                        "rgba_view",     "error_meaning", "max_error", "tool", "exr_channels",
                                        "max_error_value", "png_encoding"};
    auto axis = [&](const std::string& which, Axis& a) {
        if (!d.count(which + "_axis")) return;
        for (const char* k : {"_axis", "_mapping", "_range", "_size", "_texels", "_flipped", "_parameter_values",
                              "_parameter_name"})
            structural.insert(which + k);
        const std::vector<std::string> range = words(get(which + "_range"));
        if (range.size() != 2) throw Error("'" + path + "': " + which + "_range must hold two numbers");
        const double size_value = number_of(get(which + "_size"), path, which + "_size");
        if (size_value < 1 || size_value > kMaxAxisSize || size_value != std::floor(size_value))
            throw Error("'" + path + "': " + which + "_size '" + get(which + "_size") + "' is not a whole number from 1 to " +
                        std::to_string(kMaxAxisSize));
        const int size = int(size_value);
        const Texels texels = d.count(which + "_texels") ? Texels::Edge : Texels::Centre;
        a = make_axis(get(which + "_axis"), get(which + "_mapping"), number_of(range[0], path, which + "_range"),
                      number_of(range[1], path, which + "_range"), size, texels);
        // The per-texel parameters where the file stores them (EXR); else the coordinate until
        // the format's own record (a CSV column, the .npy sidecar) replaces it.
        a.parameter = a.coordinate;
        if (d.count(which + "_parameter_values")) {
            std::vector<double> p;
            for (const auto& w : words(d.at(which + "_parameter_values"))) p.push_back(number_of(w, path, "parameter"));
            if (p.size() != size_t(size)) throw Error("'" + path + "': " + which + "_parameter_values has the wrong length");
            a.parameter = p;
            if (d.count(which + "_parameter_name")) a.parameter_name = d.at(which + "_parameter_name");
        }
    };
    axis("x", t.x);
    axis("y", t.y);
    axis("z", t.z);
    std::vector<std::string> channels = words(get("channels"));
    if (channels.empty() || channels.back() != "error")
        throw Error("'" + path + "': its channels do not end with the error channel");
    channels.pop_back();
    t.channels = channels;
    for (const auto& kv : d)
        if (!structural.count(kv.first)) t.attributes[kv.first] = kv.second;
    return t;
}

size_t texels_of(const Table& t) { return size_t(t.width()) * size_t(t.image_height()); }

// ------------------------------------------------------------------ EXR

/// An OpenEXR input stream over bytes in memory (read through read_input_file, which opens only
/// regular files).
class MemoryInput : public Imf::IStream {
public:
    MemoryInput(const std::string& bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || pos_ + size_t(n) > bytes_.size()) throw std::runtime_error("the file is cut short");
        std::memcpy(c, bytes_.data() + pos_, size_t(n));
        pos_ += size_t(n);
        return pos_ < bytes_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = size_t(pos); }

private:
    const std::string& bytes_;
    size_t pos_ = 0;
};

Table read_exr(const std::string& path) {
    const std::string bytes = read_input_file(path, "table", kMaxTableFileBytes);
    try {
        MemoryInput stream(bytes, path);
        Imf::InputFile file(stream);
        const Imf::Header& header = file.header();
        Description d;
        for (auto it = header.begin(); it != header.end(); ++it) {
            const std::string name = it.name();
            if (name.rfind("brdfbake:", 0) != 0) continue;
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                d[name.substr(std::strlen("brdfbake:"))] = s->value();
        }
        Table t = table_from_description(d, path);
        const Imath::Box2i win = header.dataWindow();
        const int w = win.max.x - win.min.x + 1, h = win.max.y - win.min.y + 1;
        if (w != t.width() || h != t.image_height())
            throw Error("'" + path + "': the image is " + std::to_string(w) + "x" + std::to_string(h) +
                        " but its description says " + std::to_string(t.width()) + "x" + std::to_string(t.image_height()));
        // A value channel is stored under KIND.NAME where its name is an RGBA slot that holds
        // another channel, else under its name (write_exr).
        std::vector<std::string> names;
        for (const auto& c : t.channels) {
            const std::string layered = t.kind + "." + c;
            if (header.channels().findChannel(layered))
                names.push_back(layered);
            else if (header.channels().findChannel(c))
                names.push_back(c);
            else
                throw Error("'" + path + "' has no channel for '" + c + "'");
        }
        names.push_back("error");
        if (!header.channels().findChannel("error")) throw Error("'" + path + "' has no error channel");
        std::vector<std::vector<float>> planes(names.size(), std::vector<float>(texels_of(t)));
        Imf::FrameBuffer fb;
        for (size_t c = 0; c < names.size(); ++c) {
            char* base = reinterpret_cast<char*>(planes[c].data()) -
                         (size_t(win.min.x) + size_t(win.min.y) * size_t(w)) * sizeof(float);
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(win.min.y, win.max.y);
        for (size_t c = 0; c + 1 < names.size(); ++c) t.values.emplace_back(planes[c].begin(), planes[c].end());
        t.error.assign(planes.back().begin(), planes.back().end());
        return t;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("cannot read table '" + path + "': " + e.what());
    }
}

// ------------------------------------------------------------------ CSV

Table read_csv(const std::string& path) {
    const std::string text = read_input_file(path, "table", kMaxTableFileBytes);
    CsvText csv(text);
    const std::vector<std::string>& columns = csv.columns();
    Table t = table_from_description(csv.description(), path);
    std::vector<int> value_columns;
    for (const auto& c : t.channels) {
        const int i = csv.column(c);
        if (i < 0) throw Error("'" + path + "' has no column '" + c + "'");
        value_columns.push_back(i);
    }
    const int error_column = csv.column("error");
    if (error_column < 0) throw Error("'" + path + "' has no error column");
    // An axis's derived parameter sits in the column after its coordinate where the two differ.
    const Axis* axes[3] = {&t.x, &t.y, &t.z};
    int parameter_column[3] = {-1, -1, -1};
    for (int a = 0; a < 3; ++a) {
        const int i = axes[a]->size > 1 || a == 0 ? csv.column(axes[a]->name) : -1;
        if (i >= 0 && i + 1 < int(columns.size()) && i + 1 != value_columns.front()) {
            bool is_axis = false;
            for (int b = 0; b < 3; ++b) is_axis = is_axis || columns[size_t(i + 1)] == axes[b]->name;
            if (!is_axis) parameter_column[a] = i + 1;
        }
    }
    const size_t n = texels_of(t);
    if (n > text.size() / 2)  // a row takes at least two bytes: the description promises rows the file cannot hold
        throw Error("'" + path + "': its description's sizes make " + std::to_string(n) + " texels, more rows than the file holds");
    t.values.assign(t.channels.size(), std::vector<double>(n));
    t.error.assign(n, 0.0);
    std::vector<std::vector<double>> parameter(3);
    for (int a = 0; a < 3; ++a) parameter[a].assign(size_t(axes[a]->size), 0.0);
    size_t k = 0;
    for (std::vector<std::string> cells; csv.next_row(cells);) {
        if (k == n) throw Error("'" + path + "' has more rows than its " + std::to_string(n) + " texels");
        if (cells.size() != columns.size()) throw Error("'" + path + "': row " + std::to_string(k + 1) + " has " +
                                                        std::to_string(cells.size()) + " fields, not " +
                                                        std::to_string(columns.size()));
        for (size_t c = 0; c < value_columns.size(); ++c)
            t.values[c][k] = number_of(cells[size_t(value_columns[c])], path, "value", false);
        t.error[k] = number_of(cells[size_t(error_column)], path, "error", false);
        const size_t index[3] = {k % size_t(t.width()), (k / size_t(t.width())) % size_t(t.height()),
                                 k / (size_t(t.width()) * size_t(t.height()))};
        for (int a = 0; a < 3; ++a)
            if (parameter_column[a] >= 0)
                parameter[a][index[a]] = number_of(cells[size_t(parameter_column[a])], path, "parameter");
        ++k;
    }
    if (k != n) throw Error("'" + path + "' has " + std::to_string(k) + " rows for " + std::to_string(n) + " texels");
    Axis* writable[3] = {&t.x, &t.y, &t.z};
    for (int a = 0; a < 3; ++a) {
        writable[a]->parameter = parameter_column[a] >= 0 ? parameter[a] : writable[a]->coordinate;
        if (parameter_column[a] >= 0) writable[a]->parameter_name = columns[size_t(parameter_column[a])];
    }
    return t;
}

// ------------------------------------------------------------------ NPY

Table read_npy(const std::string& path) {
    nlohmann::json side;
    try {
        side = nlohmann::json::parse(read_input_file(path + ".json", "table description", std::uintmax_t(1) << 30));
    } catch (const nlohmann::json::exception& e) {
        throw Error("'" + path + ".json' is not valid JSON: " + e.what());
    }
    const std::string bytes = read_input_file(path, "table", kMaxTableFileBytes);
    try {
        Description d;
        for (const auto& kv : side.at("description").items()) d[kv.key()] = kv.value().get<std::string>();
        Table t = table_from_description(d, path);
        if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) throw Error("'" + path + "' is not a .npy file");
        const size_t header_len = size_t(static_cast<unsigned char>(bytes[8])) |
                                  size_t(static_cast<unsigned char>(bytes[9])) << 8;
        if (bytes[6] != '\x01' || 10 + header_len > bytes.size())
            throw Error("'" + path + "' is not a .npy file of format 1.0 (its header is cut short)");
        const std::string header = bytes.substr(10, header_len);
        if (header.find("'descr': '<f8'") == std::string::npos || header.find("'fortran_order': False") == std::string::npos)
            throw Error("'" + path + "': brdfbake reads little-endian float64 arrays in C order");
        // The array's own shape, the sidecar's record of it, and the description must agree.
        const std::vector<size_t> shape = npy_shape(t);
        const size_t open = header.find("'shape': ("), close = header.find(')', open);
        if (open == std::string::npos || close == std::string::npos)
            throw Error("'" + path + "': its header gives no shape");
        std::vector<size_t> header_shape;
        for (const std::string& w : csv_cells(header.substr(open + 10, close - open - 10)))
            if (w.find_first_not_of(' ') != std::string::npos)
                header_shape.push_back(size_t(number_of(w.substr(w.find_first_not_of(' ')), path, "shape")));
        auto shape_text = [](const std::vector<size_t>& v) {
            std::string s;
            for (size_t d : v) s += (s.empty() ? "" : ", ") + std::to_string(d);
            return "(" + s + ")";
        };
        if (header_shape != shape)
            throw Error("'" + path + "': the array's shape " + shape_text(header_shape) + " is not the " +
                        shape_text(shape) + " its description gives (axes' sizes, channels and error)");
        if (side.at("dtype").get<std::string>() != "<f8")
            throw Error("'" + path + ".json': dtype '" + side.at("dtype").get<std::string>() + "' is not the array's '<f8'");
        if (side.at("shape").get<std::vector<size_t>>() != shape)
            throw Error("'" + path + ".json': shape " + shape_text(side.at("shape").get<std::vector<size_t>>()) +
                        " is not the array's " + shape_text(shape));
        std::vector<std::string> channels = t.channels;
        channels.push_back("error");
        if (side.at("channels").get<std::vector<std::string>>() != channels)
            throw Error("'" + path + ".json': channels do not match the description's (" + d.at("channels") + ")");
        std::vector<const Axis*> order;  // the array's axes, outermost first: z, y, x
        if (t.depth() > 1) order.push_back(&t.z);
        if (t.height() > 1 || t.depth() > 1) order.push_back(&t.y);
        order.push_back(&t.x);
        const auto& axes = side.at("axes");
        if (!axes.is_array() || axes.size() != order.size())
            throw Error("'" + path + ".json': axes lists " + std::to_string(axes.size()) + " axes; the array has " +
                        std::to_string(order.size()));
        for (size_t a = 0; a < order.size(); ++a)
            if (axes[a].at("name").get<std::string>() != order[a]->name || axes[a].at("size").get<int>() != order[a]->size)
                throw Error("'" + path + ".json': axes[" + std::to_string(a) + "] is " +
                            axes[a].at("name").get<std::string>() + " of size " + std::to_string(axes[a].at("size").get<int>()) +
                            "; the description gives " + order[a]->name + " of size " + std::to_string(order[a]->size));
        const size_t n = texels_of(t), channel_count = t.channels.size() + 1;
        if (bytes.size() != 10 + header_len + n * channel_count * 8)
            throw Error("'" + path + "' does not hold " + std::to_string(n) + " texels of " + std::to_string(channel_count) +
                        " channels");
        t.values.assign(t.channels.size(), std::vector<double>(n));
        t.error.assign(n, 0.0);
        const char* data = bytes.data() + 10 + header_len;
        for (size_t k = 0; k < n; ++k)
            for (size_t c = 0; c < channel_count; ++c) {
                std::uint64_t bits = 0;
                for (int b = 0; b < 8; ++b)
                    bits |= std::uint64_t(static_cast<unsigned char>(data[(k * channel_count + c) * 8 + size_t(b)]))
                            << (8 * b);
                double v;
                std::memcpy(&v, &bits, sizeof v);
                (c + 1 < channel_count ? t.values[c][k] : t.error[k]) = v;
            }
        // The sidecar lists the axes in the array's order: z, y, x (checked above).
        for (size_t a = 0; a < order.size(); ++a) {
            Axis* axis = const_cast<Axis*>(order[a]);
            const auto p = axes[a].at("parameter_values").get<std::vector<double>>();
            if (p.size() != size_t(axis->size))
                throw Error("'" + path + ".json': axes[" + std::to_string(a) + "].parameter_values holds " +
                            std::to_string(p.size()) + " values for " + std::to_string(axis->size) + " texels");
            for (double v : p)
                if (!std::isfinite(v)) throw Error("'" + path + ".json': axes[" + std::to_string(a) + "].parameter_values holds a non-finite value");
            axis->parameter = p;
            axis->parameter_name = axes[a].at("parameter").get<std::string>();
        }
        return t;
    } catch (const nlohmann::json::exception& e) {
        throw Error("'" + path + ".json' is not a brdfbake table description: " + e.what());
    }
}


// ------------------------------------------------------------------ PNG

struct PngImage {
    png_uint_32 width = 0, height = 0;
    int depth = 0, channels = 0;
    std::vector<unsigned> samples;  // row-major, interleaved, as stored (no gamma or colour conversion)
    Description text;               // the brdfbake:KEY tEXt chunks, by KEY
};

/// Decodes `bytes` with libpng (PNG_TRANSFORM_IDENTITY: the samples as stored); false with
/// libpng's message on failure. Kept apart so that no local of the caller lives across libpng's
/// longjmp.
bool decode_png(const std::string& bytes, PngImage* image, std::string* message) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, message, png_error_to_message, png_warning_ignored);
    if (!png) {
        *message = "libpng could not start";
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        if (!info) *message = "libpng could not start";
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    PngMemorySource source{&bytes};
    png_set_read_fn(png, &source, read_png_from_memory);
    png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    image->width = png_get_image_width(png, info);
    image->height = png_get_image_height(png, info);
    image->depth = png_get_bit_depth(png, info);
    image->channels = png_get_channels(png, info);
    const png_bytepp rows = png_get_rows(png, info);
    const size_t per_row = size_t(image->width) * size_t(image->channels);
    image->samples.resize(per_row * image->height);
    for (png_uint_32 y = 0; y < image->height; ++y)
        for (size_t s = 0; s < per_row; ++s)
            image->samples[y * per_row + s] =
                image->depth == 16 ? unsigned(rows[y][2 * s]) << 8 | rows[y][2 * s + 1] : unsigned(rows[y][s]);
    png_textp text = nullptr;
    const int n_text = png_get_text(png, info, &text, nullptr);
    for (int i = 0; i < n_text; ++i) {
        const std::string key = text[i].key;
        if (key.rfind("brdfbake:", 0) == 0) image->text[key.substr(9)] = std::string(text[i].text, text[i].text_length);
    }
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

/// A 16-bit PNG table (write_png16): value = sample / 65535 through the RGB(A) view; the error of
/// every texel is the description's max_error plus half a step (the PNG stores no error channel).
Table read_png(const std::string& path) {
    const std::string bytes = read_input_file(path, "table", kMaxTableFileBytes);
    // The image the header declares must fit in the file's compressed data (deflate expands at
    // most 1032:1): a few hostile bytes must not make libpng allocate gigabytes of rows.
    if (bytes.size() >= 33 && bytes.compare(12, 4, "IHDR") == 0) {
        auto u32 = [&](size_t p) { return uint64_t(uint8_t(bytes[p])) << 24 | uint64_t(uint8_t(bytes[p + 1])) << 16 |
                                          uint64_t(uint8_t(bytes[p + 2])) << 8 | uint64_t(uint8_t(bytes[p + 3])); };
        const uint64_t raw = (u32(16) * 4 * uint64_t(uint8_t(bytes[24])) / 8 + 1) * u32(20);  // at most 4 samples
        if (raw > uint64_t(bytes.size()) * 1032 + (uint64_t(64) << 20))
            throw Error("cannot read table '" + path + "': its header declares an image larger than its data can hold");
    }
    PngImage image;
    std::string message;
    if (!decode_png(bytes, &image, &message)) throw Error("cannot read table '" + path + "': " + message);
    Table t = table_from_description(image.text, path);
    if (image.width != png_uint_32(t.width()) || image.height != png_uint_32(t.image_height()))
        throw Error("'" + path + "': the image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " but its description says " + std::to_string(t.width()) + "x" + std::to_string(t.image_height()));
    const size_t n = texels_of(t);
    t.values.assign(t.channels.size(), std::vector<double>(n));  // rgba_view counts the value channels
    const std::vector<int> view = rgba_view(t);
    const int samples = view.empty() ? 0 : view[3] >= 0 ? 4 : 3;
    if (image.depth != 16 || image.channels != samples)
        throw Error("'" + path + "': a table PNG holds 16-bit " + (samples == 4 ? "RGBA" : "RGB") + " samples for its " +
                    std::to_string(t.channels.size()) + " channels; this one has " + std::to_string(image.channels) +
                    " channels of " + std::to_string(image.depth) + " bits");
    for (size_t k = 0; k < n; ++k)
        for (int s = samples - 1; s >= 0; --s)  // R last: a one-channel table's R = G = B
            if (view[size_t(s)] >= 0)
                t.values[size_t(view[size_t(s)])][k] = image.samples[k * size_t(samples) + size_t(s)] / 65535.0;
    const auto max_error = image.text.find("max_error");
    if (max_error == image.text.end()) throw Error("'" + path + "' is not a brdfbake table: its description has no 'max_error'");
    t.error.assign(n, number_of(max_error->second, path, "max_error") + 0.5 / 65535.0);
    return t;
}

}  // namespace

Table read_table_file(const std::string& path) {
    const std::string e = lower_extension(path);
    Table t;
    if (e == "exr")
        t = read_exr(path);
    else if (e == "csv")
        t = read_csv(path);
    else if (e == "npy")
        t = read_npy(path);
    else if (e == "png")
        t = read_png(path);
    else
        throw Error("cannot read '" + path + "' as a table: brdfbake reads back .exr, .csv, .npy (with its .json) and .png");
    check_read_values(t, path);
    return t;
}

}  // namespace brdfbake

// NumPy .npy tables: one array in numpy's format 1.0 (the magic string, a header dict with
// 'descr', 'fortran_order' and 'shape', then the raw little-endian float64 data in C order), and
// a sidecar PATH.json with the axes (coordinates and parameters per texel), the channels and the
// description, because numpy's header takes no keys beyond those three.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/table.h"

namespace brdfbake {
namespace {

std::string npy_bytes(const Table& t, const std::vector<size_t>& shape) {
    std::string dims;
    for (size_t d : shape) dims += std::to_string(d) + ", ";
    if (shape.size() > 1) dims.resize(dims.size() - 2);  // (3,) for one dimension, (3, 2) for two
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + dims + "), }";
    // Magic (6) + version (2) + header length (2) + header, padded with spaces and ended by a
    // newline to a multiple of 64 bytes (the format's alignment).
    const size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header += '\n';
    std::string out("\x93NUMPY\x01\x00", 8);
    out += char(header.size() & 0xff);
    out += char(header.size() >> 8);
    out += header;
    const size_t n = size_t(t.width()) * t.image_height(), channels = t.channels.size() + 1;
    out.reserve(out.size() + n * channels * 8);
    for (size_t k = 0; k < n; ++k)
        for (size_t c = 0; c < channels; ++c) {
            const double v = c + 1 < channels ? t.values[c][k] : t.error[k];
            std::uint64_t bits;
            std::memcpy(&bits, &v, sizeof bits);
            for (int b = 0; b < 8; ++b) out += char((bits >> (8 * b)) & 0xff);  // little-endian
        }
    return out;
}

nlohmann::json axis_json(const Axis& a) {
    return {{"name", a.name},
            {"parameter", a.parameter_name.empty() ? a.name : a.parameter_name},
            {"mapping", a.mapping},
            {"range", {a.lo, a.hi}},
            {"size", a.size},
            {"texels", texels_name(a.texels)},
            {"coordinate", a.coordinate},
            {"parameter_values", a.parameter}};
}

}  // namespace

std::vector<size_t> npy_shape(const Table& t) {
    std::vector<size_t> shape;
    if (t.depth() > 1) shape.push_back(size_t(t.depth()));
    if (t.height() > 1 || t.depth() > 1) shape.push_back(size_t(t.height()));
    shape.push_back(size_t(t.width()));
    shape.push_back(t.channels.size() + 1);
    return shape;
}

void write_npy(const Table& t, const std::string& path) {
    const std::vector<size_t> shape = npy_shape(t);
    nlohmann::json j;
    const size_t slash = path.find_last_of('/');
    j["array"] = slash == std::string::npos ? path : path.substr(slash + 1);
    j["dtype"] = "<f8";
    j["shape"] = shape;
    nlohmann::json axes = nlohmann::json::array();
    std::string index = "[";
    if (t.depth() > 1) {
        axes.push_back(axis_json(t.z));
        index += "z, ";
    }
    if (t.height() > 1 || t.depth() > 1) {
        axes.push_back(axis_json(t.y));
        index += "y, ";
    }
    axes.push_back(axis_json(t.x));
    index += "x, channel]";
    j["index"] = index;
    j["axes"] = axes;  // in the array's order, the channel axis excluded
    std::vector<std::string> channels = t.channels;
    channels.push_back("error");
    j["channels"] = channels;
    nlohmann::json description = nlohmann::json::object();
    for (const auto& kv : table_description(t)) description[kv.first] = kv.second;
    j["description"] = description;
    // Both or neither: the array never stands without its description, nor the description
    // without its array (the sidecar is renamed first).
    OutputGroup together;
    write_file_atomically(path + ".json", j.dump(2) + "\n");
    write_file_atomically(path, npy_bytes(t, shape));
    together.commit();
}

}  // namespace brdfbake

#include "io/part_file.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/version.h"
#include "engine/embedded_sources.h"

namespace brdfbake {
namespace {

constexpr const char* kFormat = "brdfbake part file 1";

std::string to_hex(const std::string& bytes) {
    static const char* digits = "0123456789abcdef";
    std::string out;
    out.reserve(bytes.size() * 2);
    for (unsigned char b : bytes) {
        out.push_back(digits[b >> 4]);
        out.push_back(digits[b & 15]);
    }
    return out;
}

std::string from_hex(const std::string& hex, const std::string& path) {
    auto nibble = [&](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        throw Error("'" + path + "' is not a brdfbake part file (a record is not hexadecimal)");
    };
    if (hex.size() % 2) throw Error("'" + path + "' is not a brdfbake part file (a record is cut short)");
    std::string out(hex.size() / 2, '\0');
    for (size_t i = 0; i < out.size(); ++i) out[i] = char(nibble(hex[2 * i]) << 4 | nibble(hex[2 * i + 1]));
    return out;
}

}  // namespace

std::string source_digest() {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bits
    auto add = [&](const std::string& s) {
        for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
        h = (h ^ 0xffu) * 1099511628211ull;  // a separator
    };
    add(BRDFBAKE_VERSION);
    for (const std::string& name : embedded_source_names()) {
        add(name);
        add(embedded_source(name));
    }
    std::ostringstream o;
    o << std::hex;
    o.width(16);
    o.fill('0');
    o << h;
    return o.str();
}

void write_part_file(const PartFile& part, const std::string& path) {
    nlohmann::json j;
    j["format"] = kFormat;
    j["version"] = part.version;
    j["source"] = part.source;
    j["command"] = part.command;
    j["shard"] = part.shard;
    j["shards"] = part.shards;
    j["texts"] = part.texts;
    nlohmann::json cells = nlohmann::json::object();
    for (const auto& [key, bytes] : part.cells) cells[key] = to_hex(bytes);
    j["cells"] = cells;
    write_file_atomically(path, j.dump(1) + "\n");
}

PartFile read_part_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read part file '" + path + "'");
    nlohmann::json j;
    try {
        in >> j;
    } catch (const nlohmann::json::exception&) {
        throw Error("'" + path + "' is not a brdfbake part file (not JSON)");
    }
    if (!j.is_object() || j.value("format", "") != kFormat)
        throw Error("'" + path + "' is not a brdfbake part file (written by `brdfbake lut ... --shard K/N`)");
    PartFile p;
    try {
        p.version = j.at("version").get<std::string>();
        p.source = j.at("source").get<std::string>();
        p.command = j.at("command").get<std::vector<std::string>>();
        p.shard = j.at("shard").get<int>();
        p.shards = j.at("shards").get<int>();
        p.texts = j.at("texts").get<std::vector<std::string>>();
        for (const auto& [key, hex] : j.at("cells").items()) p.cells[key] = from_hex(hex.get<std::string>(), path);
    } catch (const nlohmann::json::exception&) {
        throw Error("'" + path + "' is not a brdfbake part file (a field is missing or of the wrong type)");
    }
    if (p.shards < 1 || p.shard < 0 || p.shard >= p.shards)
        throw Error("'" + path + "' names shard " + std::to_string(p.shard) + " of " + std::to_string(p.shards));
    return p;
}

}  // namespace brdfbake

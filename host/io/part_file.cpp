#include "io/part_file.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdio>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/version.h"
#include "engine/embedded_sources.h"
#include "engine/hash.h"
#include "models/input_file.h"

namespace brdfbake {
namespace {

// A part file holds one shard's records in hex: 1 GiB is far beyond any table brdfbake computes.
constexpr std::uintmax_t kMaxPartFileBytes = std::uintmax_t(1) << 30;

constexpr const char* kFormat = "brdfbake part file 2";
constexpr const char* kOldFormat = "brdfbake part file 1";  // without a checksum

// FNV-1a, 64 bits, of `text`, as 16 hex digits: a checksum that catches any change to a part
// file by accident (a bit flip, an edit, a copy cut short), not a signature against forgery.
std::string fnv1a_hex(const std::string& text) {
    const std::uint64_t h = fnv1a(text);
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
    return b;
}

// The checksum of a part file's JSON: of its canonical text (nlohmann's dump, keys sorted)
// without the checksum itself. It covers the command, the version, the shard and every record.
std::string checksum_of(nlohmann::json j) {
    j.erase("checksum");
    return fnv1a_hex(j.dump());
}

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
    Fnv1a hash;
    auto add = [&](const std::string& s) {
        hash.add(s).add(static_cast<unsigned char>(0xff));  // a separator
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
    o << hash.h;
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
    j["checksum"] = checksum_of(j);
    write_file_atomically(path, j.dump(1) + "\n");
}

PartFile read_part_file(const std::string& path) {
    // Only a regular file, and not beyond the limit: a FIFO or a device must not block or fill memory.
    const std::string text = read_input_file(path, "part file", kMaxPartFileBytes);
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception&) {
        throw Error("'" + path + "' is not a brdfbake part file (not JSON)");
    }
    if (j.is_object() && j.value("format", "") == kOldFormat)
        throw Error("'" + path + "' is a part file of an older brdfbake, without a checksum: compute the shard again");
    if (!j.is_object() || j.value("format", "") != kFormat)
        throw Error("'" + path + "' is not a brdfbake part file (written by `brdfbake lut ... --shard K/N`)");
    if (!j.contains("checksum") || !j["checksum"].is_string() || j["checksum"].get<std::string>() != checksum_of(j))
        throw Error("part file '" + path +
                    "' is corrupted: its checksum does not match its content (changed or cut short after "
                    "`brdfbake lut --shard` wrote it); compute that shard again");
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

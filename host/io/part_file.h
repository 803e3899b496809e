// Part files: one shard of a table (`brdfbake lut ... --shard K/N -o PART`), read back by
// `brdfbake merge`. JSON: the command that made it, the brdfbake version and a digest of the
// kernel sources it ran, the shard's index and count, and the recorded cell results (opaque
// packed bytes, in hex, keyed by the integration call's settings and the cell).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace brdfbake {

struct PartFile {
    std::vector<std::string> command;  // the command line, less the options that do not change results
    std::string version;               // BRDFBAKE_VERSION
    std::string source;                // source_digest() of the program that wrote it
    int shard = 0, shards = 1;         // K of N
    std::map<std::string, std::string> cells;  // key -> packed results (bytes)
    std::vector<std::string> texts;            // method texts the packed results refer to
};

/// A digest of everything a result depends on besides the command: the version and the embedded
/// kernel sources and shared BRDF headers (16 hex digits).
std::string source_digest();

/// Writes `part` to `path` atomically (as every output). Throws Error.
void write_part_file(const PartFile& part, const std::string& path);
/// Reads a part file; throws Error (naming `path`) if it is not one.
PartFile read_part_file(const std::string& path);

}  // namespace brdfbake

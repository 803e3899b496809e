// Output helpers: formats, number text, and atomic file writes.
#pragma once

#include <string>
#include <vector>

namespace brdfbake {

enum class Format { Table, Json, Csv };

/// "table", "json" or "csv"; throws Error otherwise.
Format parse_format(const std::string& text);

/// Writes `content` to `path` through a temporary file in the same folder and a rename, so a
/// reader never sees a half-written file and a failure leaves nothing behind. Throws Error.
void write_file_atomically(const std::string& path, const std::string& content);

/// Writes to `path`, or to standard output when `path` is empty or "-".
void emit(const std::string& path, const std::string& content);

/// Parses a comma-separated list of finite numbers ("0.1,0.5,1"); `what` names it in errors.
std::vector<double> parse_number_list(const std::string& text, const std::string& what);

}  // namespace brdfbake

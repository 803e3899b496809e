// Output helpers: formats, number text, and atomic file writes.
#pragma once

#include <string>
#include <vector>

namespace brdfbake {

enum class Format { Table, Json, Csv };

/// "table", "json" or "csv"; throws Error otherwise.
Format parse_format(const std::string& text);

/// An output file about to be written: where it lands and the temporary file it is written to
/// first, beside it, then renamed onto it, so that a reader never sees a half-written file and a
/// failure leaves nothing behind.
struct OutputFile {
    std::string target;     // `path`, or the resolved target of a symbolic link at `path`
    std::string temporary;  // ".NAME.tmp-PID" in the target's folder: hidden, matching no "*.ext" glob
};

/// Checks that `path` can be replaced by an output file and plans the write. A regular file or
/// an absent path is written; a symbolic link is followed, and its target replaced (the link
/// stays); a directory, device, FIFO or socket, or a link to nothing, is refused with Error (a
/// file must never replace /dev/null or a pipe). Temporary files that an earlier run left in that
/// folder (its process is gone) are removed. Throws Error; writes nothing else.
OutputFile prepare_output(const std::string& path);

/// Renames the written temporary file onto the target; on failure removes it and throws Error
/// naming `path`.
void commit_output(const OutputFile& file, const std::string& path);

/// Throws Error if prepare_output would refuse `path`; for commands to check their outputs before
/// any work.
void check_output_path(const std::string& path);

/// Writes `content` to `path` through prepare_output and commit_output. Throws Error.
void write_file_atomically(const std::string& path, const std::string& content);

/// Writes to `path`, or to standard output when `path` is empty or "-".
void emit(const std::string& path, const std::string& content);

/// Parses a comma-separated list of finite numbers ("0.1,0.5,1"); `what` names it in errors.
std::vector<double> parse_number_list(const std::string& text, const std::string& what);

}  // namespace brdfbake

// Output helpers: formats, number text, and atomic file writes.
#pragma once

#include <string>
#include <utility>
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
/// naming `path`. Inside an OutputGroup the rename waits for the group's commit().
void commit_output(const OutputFile& file, const std::string& path);

/// Output files that land together or not at all (a table and its .npy sidecar, a table and its
/// preview): while a group is open, commit_output only stages each written temporary file;
/// commit() renames them all, in the order they were written, and a group that ends without
/// commit() (an error was thrown) removes them, so a failure leaves none of the files. Groups
/// nest: an inner group's files join the outermost group's commit.
class OutputGroup {
public:
    OutputGroup();
    ~OutputGroup();
    /// Renames every staged file onto its target (the outermost group only). Throws Error.
    void commit();
    OutputGroup(const OutputGroup&) = delete;
    OutputGroup& operator=(const OutputGroup&) = delete;

private:
    bool outermost_;
};

/// Throws Error if prepare_output would refuse `path`; for commands to check their outputs before
/// any work.
void check_output_path(const std::string& path);

/// Writes `content` to `path` through prepare_output and commit_output. Throws Error.
void write_file_atomically(const std::string& path, const std::string& content);

/// Writes `content` to the temporary file of `out` (prepare_output), checking every write and the
/// close (a full disk shows there); on failure removes the temporary file and throws Error naming
/// `path`. The caller commits.
void write_temporary(const OutputFile& out, const std::string& path, const std::string& content);

/// Writes an 8- or 16-bit PNG (libpng; rows of `bytes`, big-endian 16-bit samples) to `path`
/// atomically, with tEXt chunks of `text` and a gAMA chunk of `gamma` (0: none). libpng's errors
/// (a full disk) end in Error, never in abort(): nothing is left. `channels`: 1 (grey), 3 (RGB)
/// or 4 (RGBA).
void write_png_file(const std::string& path, int width, int height, int bit_depth, int channels,
                    const std::vector<unsigned char>& bytes, const std::vector<std::pair<std::string, std::string>>& text,
                    double gamma = 0.0);

/// Writes to `path`, or to standard output when `path` is empty or "-".
void emit(const std::string& path, const std::string& content);

/// The shortest text that reads back (strtod) as exactly `v` (std::to_chars); with `as_float`,
/// 9 significant digits (%.9g: what reads back as the same float where v is one; a value a float
/// computation accumulated in double keeps its 9 digits, it is not rounded to a float first).
/// "nan", "inf", "-inf" for those.
std::string round_trip_text(double v, bool as_float = false);

/// Parses a comma-separated list of finite numbers ("0.1,0.5,1"); `what` names it in errors.
std::vector<double> parse_number_list(const std::string& text, const std::string& what);

}  // namespace brdfbake

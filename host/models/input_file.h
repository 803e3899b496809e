// Reading an input file the user names (n,k data, scene JSON, glTF): only a regular file, only
// up to a size limit, judged before a byte is read, so that `/dev/zero`, a FIFO or a huge file
// gives one clear error instead of filling memory or blocking.
#pragma once

#include <cstdint>
#include <string>

namespace brdfbake {

/// The whole content of `path`. `what` names the file in messages ("n,k file", "scene").
/// Throws Error if the path does not exist, is not a regular file (a directory, device, FIFO or
/// socket; a symbolic link is followed), is larger than `max_bytes`, or cannot be read.
std::string read_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

}  // namespace brdfbake

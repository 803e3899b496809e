#include "models/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "brdfbake/error.h"

namespace brdfbake {

namespace {

std::string size_words(std::uintmax_t bytes) {
    if (bytes >= (std::uintmax_t(1) << 20) && bytes % (std::uintmax_t(1) << 20) == 0)
        return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string read_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error("cannot read " + what + " '" + path + "': " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw Error(what + " '" + path + "' is a directory");
    if (!S_ISREG(st.st_mode))
        throw Error(what + " '" + path + "' is not a regular file (a device, FIFO or socket cannot be read as one)");
    if (std::uintmax_t(st.st_size) > max_bytes)
        throw Error(what + " '" + path + "' is " + std::to_string(std::uintmax_t(st.st_size)) +
                    " bytes; the limit is " + size_words(max_bytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read " + what + " '" + path + "': " + std::strerror(errno));
    // Read in chunks up to one byte past the limit: a file that grew since stat() is still refused.
    std::string text;
    char chunk[1 << 16];
    while (in && text.size() <= max_bytes) {
        in.read(chunk, sizeof chunk);
        text.append(chunk, std::size_t(in.gcount()));
    }
    if (in.bad()) throw Error("cannot read " + what + " '" + path + "'");
    if (text.size() > max_bytes)
        throw Error(what + " '" + path + "' is larger than the limit of " + size_words(max_bytes));
    return text;
}

}  // namespace brdfbake

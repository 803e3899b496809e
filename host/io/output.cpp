#include "brdfbake/output.h"

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <regex>

#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "engine/distributed.h"

namespace brdfbake {

Format parse_format(const std::string& text) {
    if (text == "table") return Format::Table;
    if (text == "json") return Format::Json;
    if (text == "csv") return Format::Csv;
    throw Error("unknown format '" + text + "'; expected table, json or csv");
}

namespace {

std::string folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

std::string name_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

// Where a write to `path` lands; throws Error for what must not be replaced.
std::string resolve_target(const std::string& path) {
    if (path.empty()) throw Error("empty output path");
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) {
        if (errno != ENOENT) throw Error("cannot write '" + path + "': " + std::strerror(errno));
        // A new file: its folder must exist and take files, found out before any work is done.
        const std::string folder = folder_of(path);
        if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
            throw Error("cannot write '" + path + "': folder '" + folder + "' does not exist");
        if (::access(folder.c_str(), W_OK | X_OK) != 0)
            throw Error("cannot write '" + path + "': folder '" + folder + "' is not writable (" + std::strerror(errno) +
                        ")");
        return path;
    }
    std::string target = path;
    if (S_ISLNK(st.st_mode)) {
        char resolved[PATH_MAX];
        if (!::realpath(path.c_str(), resolved))
            throw Error("cannot write '" + path + "': it is a symbolic link to nothing (" + std::strerror(errno) + ")");
        target = resolved;
        if (::stat(target.c_str(), &st) != 0) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    }
    if (!S_ISREG(st.st_mode))
        throw Error("refusing to write '" + path + "': it is " + kind_of(st.st_mode) + ", not a regular file");
    return target;
}

// Removes the temporary files of runs that are gone: ".NAME.tmp-PID", and those of earlier
// versions, "NAME.EXT.tmp-PID[.exr|.png|.svg]" with an output extension, whose process no
// longer exists.
void remove_stale_temporaries(const std::string& folder) {
    static const std::regex stale(
        R"(^(\..+|.+\.(exr|csv|h|hpp|json|png|svg|txt))\.tmp-([0-9]+)(\.(exr|png|svg))?$)");
    DIR* dir = ::opendir(folder.c_str());
    if (!dir) return;
    while (const dirent* e = ::readdir(dir)) {
        std::cmatch m;
        if (!std::regex_match(e->d_name, m, stale)) continue;
        const long pid = std::strtol(m[3].str().c_str(), nullptr, 10);
        if (pid <= 0 || pid == long(::getpid())) continue;
        if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
        const std::string file = folder + "/" + e->d_name;
        struct stat st {};
        if (::lstat(file.c_str(), &st) == 0 && S_ISREG(st.st_mode)) std::remove(file.c_str());
    }
    ::closedir(dir);
}

}  // namespace

void check_output_path(const std::string& path) { resolve_target(path); }

OutputFile prepare_output(const std::string& path) {
    OutputFile f;
    f.target = resolve_target(path);
    const std::string folder = folder_of(f.target);
    // Only the writing rank judges stale files: a rank on another node cannot see rank 0's process.
    if (dist::is_writer()) remove_stale_temporaries(folder);
    f.temporary = folder + "/." + name_of(f.target) + ".tmp-" + std::to_string(::getpid());
    if (!dist::is_writer()) {
        // An MPI rank other than 0 writes its copy to a private temporary file that commit_output
        // removes: the same code path on every rank, one file at the target (rank 0's).
        const char* tmp = std::getenv("TMPDIR");
        f.temporary = std::string(tmp && *tmp ? tmp : "/tmp") + "/.brdfbake-rank" + std::to_string(dist::rank()) + "-" +
                      std::to_string(::getpid()) + "-" + name_of(f.target);
    }
    return f;
}

void commit_output(const OutputFile& f, const std::string& path) {
    // In an MPI job no file lands unless every rank has come this far without failing.
    try {
        dist::agree();
    } catch (...) {
        std::remove(f.temporary.c_str());
        throw;
    }
    if (!dist::is_writer()) {
        std::remove(f.temporary.c_str());
        return;
    }
    if (std::rename(f.temporary.c_str(), f.target.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(f.temporary.c_str());
        throw Error("cannot write '" + path + "': " + why);
    }
}

void write_file_atomically(const std::string& path, const std::string& content) {
    const OutputFile f = prepare_output(path);
    {
        std::ofstream out(f.temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error("cannot write '" + path + "': " + std::strerror(errno));
        out << content;
        out.flush();
        if (!out) {
            std::remove(f.temporary.c_str());
            throw Error("cannot write '" + path + "': " + std::strerror(errno));
        }
    }
    commit_output(f, path);
}

void emit(const std::string& path, const std::string& content) {
    if (path.empty() || path == "-") {
        std::cout << content << std::flush;
        return;
    }
    write_file_atomically(path, content);
}

std::vector<double> parse_number_list(const std::string& text, const std::string& what) {
    std::vector<double> out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t comma = text.find(',', start);
        if (comma == std::string::npos) comma = text.size();
        out.push_back(parse_number(text.substr(start, comma - start), what));
        start = comma + 1;
    }
    return out;
}

}  // namespace brdfbake

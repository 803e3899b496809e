#include "brdfbake/output.h"

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

// The temporary file a write to `target` goes through: ".NAME.tmp-PID" beside it; on an MPI rank
// other than 0 (which writes nothing that stays) a private file in $TMPDIR that commit_output removes.
std::string temporary_path(const std::string& target) {
    if (!dist::is_writer()) {
        const char* tmp = std::getenv("TMPDIR");
        return std::string(tmp && *tmp ? tmp : "/tmp") + "/.brdfbake-rank" + std::to_string(dist::rank()) + "-" +
               std::to_string(::getpid()) + "-" + name_of(target);
    }
    return folder_of(target) + "/." + name_of(target) + ".tmp-" + std::to_string(::getpid());
}

// A name whose temporary file the file system cannot hold is refused before any work, not after it.
void check_temporary_name(const std::string& target, const std::string& path) {
    const std::string temporary = temporary_path(target);
    const std::string folder = folder_of(temporary), name = name_of(temporary);
    long max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    if (max <= 0) max = NAME_MAX;
    if (name.size() > size_t(max))
        throw Error("cannot write '" + path + "': its name is " + std::to_string(name_of(target).size()) +
                    " bytes, and its temporary file '" + name.substr(0, 24) + "...' would be " +
                    std::to_string(name.size()) + ", over the file system's limit of " + std::to_string(max) +
                    "; give a shorter name");
    if (temporary.size() >= PATH_MAX)
        throw Error("cannot write '" + path + "': its temporary file's path would be " + std::to_string(temporary.size()) +
                    " bytes, over the limit of " + std::to_string(PATH_MAX - 1));
}

// Where a write to `path` lands, before the temporary name is judged; throws Error for what must
// not be replaced.
std::string resolve_existing_target(const std::string& path) {
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

// Where a write to `path` lands; throws Error for what must not be replaced.
std::string resolve_target(const std::string& path) {
    const std::string target = resolve_existing_target(path);
    check_temporary_name(target, path);
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
    // An MPI rank other than 0 writes its copy to a private temporary file that commit_output
    // removes: the same code path on every rank, one file at the target (rank 0's).
    f.temporary = temporary_path(f.target);
    return f;
}

namespace {

struct Staged {
    OutputFile file;
    std::string path;
};

// The files of the open OutputGroup, waiting for its commit (null: no group is open).
thread_local std::vector<Staged>* g_staged = nullptr;

void remove_temporaries(const std::vector<Staged>& staged, size_t from = 0) {
    for (size_t i = from; i < staged.size(); ++i) std::remove(staged[i].file.temporary.c_str());
}

// Renames the temporary files onto their targets once every rank of an MPI job has come this far
// (only rank 0 renames; the others remove theirs). A failure removes what is not yet renamed.
void rename_all(const std::vector<Staged>& staged) {
    try {
        dist::agree();
    } catch (...) {
        remove_temporaries(staged);
        throw;
    }
    if (!dist::is_writer()) return remove_temporaries(staged);
    for (size_t i = 0; i < staged.size(); ++i)
        if (std::rename(staged[i].file.temporary.c_str(), staged[i].file.target.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            remove_temporaries(staged, i);
            throw Error("cannot write '" + staged[i].path + "': " + why);
        }
}

}  // namespace

void commit_output(const OutputFile& f, const std::string& path) {
    if (g_staged) {
        for (const Staged& s : *g_staged)
            if (s.file.temporary == f.temporary) return;  // written twice: one rename
        g_staged->push_back({f, path});
        return;
    }
    rename_all({{f, path}});
}

OutputGroup::OutputGroup() : outermost_(g_staged == nullptr) {
    if (outermost_) g_staged = new std::vector<Staged>;
}

OutputGroup::~OutputGroup() {
    if (!outermost_ || !g_staged) return;
    remove_temporaries(*g_staged);  // not committed: an error ends the group
    delete g_staged;
    g_staged = nullptr;
}

void OutputGroup::commit() {
    if (!outermost_ || !g_staged) return;
    const std::vector<Staged> staged = std::move(*g_staged);
    delete g_staged;
    g_staged = nullptr;
    rename_all(staged);
}

void write_temporary(const OutputFile& f, const std::string& path, const std::string& content) {
    std::FILE* out = std::fopen(f.temporary.c_str(), "wb");
    if (!out) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    errno = 0;
    const bool written = std::fwrite(content.data(), 1, content.size(), out) == content.size();
    const int write_errno = errno;
    const bool closed = std::fclose(out) == 0;  // the buffer's last write: a full disk may show only here
    if (!written || !closed) {
        const int err = !written ? write_errno : errno;
        std::remove(f.temporary.c_str());
        throw Error("cannot write '" + path + "': " + (err ? std::strerror(err) : "write failed"));
    }
}

void write_file_atomically(const std::string& path, const std::string& content) {
    const OutputFile f = prepare_output(path);
    write_temporary(f, path, content);
    commit_output(f, path);
}

void emit(const std::string& path, const std::string& content) {
    if (path.empty() || path == "-") {
        std::cout << content << std::flush;
        return;
    }
    write_file_atomically(path, content);
}

std::string round_trip_text(double v, bool as_float) {
    char b[64];
    if (as_float) {  // never rounded to a float first: a float table's value may carry more
        std::snprintf(b, sizeof b, "%.9g", v);
        return b;
    }
    const std::to_chars_result r = std::to_chars(b, b + sizeof b, v);
    return std::string(b, r.ptr);
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

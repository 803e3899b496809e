#include "scene/bake_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/crc.hpp>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "brdfbake/error.h"
#include "engine/distributed.h"

namespace brdfbake {

const char* const kContentHashAlgorithm = "CRC-64/XZ";

std::uint64_t crc64_xz(const std::string& bytes) {
    // Width 64, polynomial 0x42F0E1EBA9EA3693 (ECMA-182), initial value and final XOR all ones,
    // input and output reflected: CRC-64/XZ in the CRC catalogue, the check of the XZ format.
    boost::crc_optimal<64, 0x42F0E1EBA9EA3693ULL, ~0ULL, ~0ULL, true, true> crc;
    crc.process_bytes(bytes.data(), bytes.size());
    return crc.checksum();
}

std::string content_hash_of_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read '" + path + "': " + std::strerror(errno));
    std::stringstream s;
    s << in.rdbuf();
    if (in.bad()) throw Error("cannot read '" + path + "'");
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(crc64_xz(s.str())));
    return hex;
}

namespace {

std::string read_holder(const std::string& lock_path) {
    std::ifstream in(lock_path);
    std::string pid;
    in >> pid;
    return pid.find_first_not_of("0123456789") == std::string::npos && !pid.empty() ? pid : "";
}

}  // namespace

BakeFolder::BakeFolder(const std::string& folder, double wait_seconds) : folder_(folder) {
    if (folder.empty()) throw Error("-o: give an output folder");
    if (!(wait_seconds >= 0) || !std::isfinite(wait_seconds))
        throw Error("--lock-timeout must be a finite number of seconds, 0 or more");
    // In an MPI job only the writing rank (rank 0) makes the folder and holds its lock; the other
    // ranks compute their share of the cells and write nothing (waiting on rank 0's lock would
    // deadlock the job's collective steps).
    if (!dist::is_writer()) return;
    try {
        // The folder and its missing parents, each remembered so that a failed bake removes them.
        std::string partial = folder[0] == '/' ? "/" : "";
        std::stringstream in(folder);
        std::string part;
        while (std::getline(in, part, '/')) {
            if (part.empty()) continue;
            if (!partial.empty() && partial.back() != '/') partial += "/";
            partial += part;
            struct stat st {};
            if (::stat(partial.c_str(), &st) == 0) {
                if (!S_ISDIR(st.st_mode))
                    throw Error("output folder '" + folder + "': '" + partial + "' is not a folder");
                continue;
            }
            if (errno != ENOENT) throw Error("output folder '" + folder + "': '" + partial + "': " + std::strerror(errno));
            if (::mkdir(partial.c_str(), 0777) != 0) {
                if (errno == EEXIST) continue;  // another process made it just now
                throw Error("cannot create output folder '" + folder + "': " + std::strerror(errno));
            }
            created_.push_back(partial);
        }
        lock_path_ = (folder.back() == '/' ? folder : folder + "/") + lock_name();

        // flock(2) on the lock file. The holder removes the file when it finishes, so a lock won
        // on a file that is no longer the one at lock_path_ is worthless: check, and retry.
        const auto deadline =
            std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                   std::chrono::duration<double>(std::min(wait_seconds, 1e9)));
        bool announced = false;
        for (;;) {
            const int fd = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
            if (fd < 0)
                throw Error("cannot lock output folder '" + folder + "' (" + lock_path_ + "): " + std::strerror(errno));
            if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
                struct stat held {}, now {};
                if (::fstat(fd, &held) == 0 && ::stat(lock_path_.c_str(), &now) == 0 && held.st_ino == now.st_ino &&
                    held.st_dev == now.st_dev) {
                    const std::string pid = std::to_string(::getpid()) + "\n";
                    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
                        // The pid is only for the messages of a waiting bake; the lock holds without it.
                    }
                    fd_ = fd;
                    break;
                }
                ::close(fd);
                continue;
            }
            const int why = errno;
            ::close(fd);
            if (why != EWOULDBLOCK && why != EINTR)
                throw Error("cannot lock output folder '" + folder + "' (" + lock_path_ + "): " + std::strerror(why));
            const std::string holder = read_holder(lock_path_);
            const std::string who = holder.empty() ? "another bake" : "another bake (pid " + holder + ")";
            char waited[64];
            std::snprintf(waited, sizeof waited, "%g", wait_seconds);
            if (std::chrono::steady_clock::now() >= deadline)
                throw Error(who + " is writing into '" + folder + "'" +
                            (wait_seconds > 0 ? std::string(" and did not finish within ") + waited + " s" : "") +
                            "; wait for it, or raise --lock-timeout (lock file " + lock_path_ + ")");
            if (!announced) {
                std::fprintf(stderr, "brdfbake: waiting for %s to finish writing into %s (up to %s s, --lock-timeout)\n",
                             who.c_str(), folder.c_str(), waited);
                std::fflush(stderr);
                announced = true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
    } catch (...) {
        for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());
        throw;
    }
}

BakeFolder::~BakeFolder() {
    if (fd_ >= 0) {
        ::unlink(lock_path_.c_str());  // while still holding the lock: see the constructor
        ::close(fd_);
    }
    if (!committed_)
        for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());  // only if empty
}

}  // namespace brdfbake

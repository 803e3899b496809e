// Test scratch files: a temporary directory removed at scope exit, writing a file, and the check
// that a table the chosen file format cannot hold is refused when written.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "checks.h"
#include "support.h"

namespace testing {

/// A fresh directory /tmp/brdfbake-NAME-XXXXXX, removed with all it holds when it goes out of scope.
struct ScratchDir {
    std::string path;
    explicit ScratchDir(const std::string& name) {
        std::string t = "/tmp/brdfbake-" + name + "-XXXXXX";
        if (::mkdtemp(t.data()) == nullptr) throw std::runtime_error("mkdtemp " + t + " failed");
        path = t;
    }
    ~ScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    std::string operator/(const std::string& name) const { return path + "/" + name; }
};

/// Writes `text` to `path` (replacing it).
inline void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// `brdfbake ARGS --samples 256 --no-preview -o OUT` refused when its table is written (after the
/// computation; the progress display held back so that stderr holds the message alone): bad
/// input, the message naming OUT's extension, nothing at OUT.
inline void check_refused_when_written(const std::string& args, const std::string& out) {
    INFO(args << " -o " << out);
    const CliResult r = run_shell("BRDFBAKE_PROGRESS_DELAY=100000 " + std::string(BRDFBAKE_EXE) + " " + args +
                                  " --samples 256 --no-preview -o " + out);
    check_usage_error(r);
    CHECK(r.err.find(out.substr(out.rfind('.'))) != std::string::npos);
    CHECK_FALSE(std::ifstream(out).good());
}

}  // namespace testing

// Test scratch files: a temporary directory removed at scope exit, writing a file, and the check
// that a table the chosen file format cannot hold is refused when written.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "brdfbake/table.h"
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

/// A test table on three.js's LTC grid (n x n, x = roughness, y = sqrt(1 - mu), edge texels, as the
/// EEVEE and Unity HDRP layouts share it) with the given channels, values zero, error 1e-6, float.
inline brdfbake::Table ltc_engine_grid_table(int n, std::vector<std::string> channels) {
    brdfbake::Table t;
    t.kind = "ltc";
    t.quantity = "test values naming their texel";
    t.x = brdfbake::make_axis("roughness", "alpha = r^2 (r = sqrt(alpha))", 0, 1, n, brdfbake::Texels::Edge);
    t.y = brdfbake::make_axis("sqrt_one_minus_mu", "mu = 1 - u^2", 0, 1, n, brdfbake::Texels::Edge);
    t.channels = std::move(channels);
    t.values.assign(t.channels.size(), std::vector<double>(size_t(n) * n));
    t.error.assign(size_t(n) * n, 1e-6);
    t.attributes["precision"] = "float";
    return t;
}

}  // namespace testing

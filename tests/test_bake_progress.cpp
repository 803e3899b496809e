// Progress within a bake written to a log (stderr not a terminal): lines come from within a
// table's computation, not only one per table, and never more than about 5 s apart (the display's
// promise, host/cli/progress_bar.cpp); the preview is a step of its own. BRDFBAKE_PROGRESS_DELAY=0
// shows the bake's stage from its start, however fast the machine.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support.h"

namespace {

std::string source_dir() { return BRDFBAKE_SOURCE_DIR; }  // the repository (CMake defines it)

}  // namespace

TEST_CASE("bake progress: lines from within a table in a log, at most about 5 s apart", "[bake][progress][cli]") {
    namespace fs = std::filesystem;
    const std::string dir = "/tmp/brdfbake-bake-progress-" + std::to_string(::getpid());
    fs::remove_all(dir);
    // One albedo table of 64 x ~20 texels at 2^21 samples: 2.8e9 samples, seconds on two cores
    // (2^19 took under a second on a quiet machine: too quick for a line from within the table).
    const auto r = testing::run_shell("BRDFBAKE_PROGRESS_DELAY=0 " + std::string(BRDFBAKE_EXE) + " bake " + source_dir() +
                                      "/tests/data/small_bake.json --tables albedo --mu-texels 64 --alpha-texels 64 "
                                      "--samples 2097152 --no-report -o " + dir);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.find('\r') == std::string::npos);  // a log: no terminal control
    std::istringstream lines(r.err);
    std::string line;
    bool inside = false;
    int within = 0, preview_steps = 0;
    std::vector<double> clocks;  // the elapsed seconds each progress line gives
    const std::regex progress(R"(brdfbake: +[0-9]+% of bake of 1 table into [^:]+: \[1/1\] albedo-ggx\.exr.*\(([0-9.]+) s)");
    while (std::getline(lines, line)) {
        if (line.find("[1/1] albedo-ggx.exr: computing") != std::string::npos) inside = true;
        if (line.find("[1/1] wrote") != std::string::npos) inside = false;
        std::smatch m;
        if (inside && std::regex_search(line, m, progress)) {
            ++within;
            clocks.push_back(std::stod(m[1]));
            preview_steps += line.find("drawing its preview previews/albedo-ggx.exr.png") != std::string::npos;
        }
    }
    // From within the table, not only the lines that begin and end it: the display shows a line
    // once a tenth of the work is done and a second has passed, so a table of two seconds has one.
    std::smatch wrote;
    REQUIRE(std::regex_search(r.err, wrote, std::regex(R"(\[1/1\] wrote .* in ([0-9.]+) s)")));
    if (std::stod(wrote[1]) >= 2.0)
        CHECK(within >= 1);
    else
        WARN("the table took " << wrote[1] << " s: too quick for a line from within it");
    for (size_t k = 1; k < clocks.size(); ++k) CHECK(clocks[k] - clocks[k - 1] <= 7.0);  // 5 s, with slack for a busy machine
    // The preview, when it lasts long enough to be shown, is named as what runs (not the table).
    if (preview_steps == 0) WARN("the preview was drawn too quickly for a progress line");
    fs::remove_all(dir);
}

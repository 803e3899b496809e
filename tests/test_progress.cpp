// Progress of a long run on stderr: plain lines when stderr is not a terminal, a bar redrawn in
// place on a terminal (run under `script`, which gives the command a pseudo-terminal), nothing
// with --quiet, nothing for a short run, and never a change in the numbers.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <regex>

#include "support.h"

using testing::run_cli;

namespace {

// 4096 texels x 2^20 samples: 2^32 samples, sliced into launches (more than 2^28), a few seconds.
const std::string kLong = "lut albedo --model ggx --size 64x64 --samples 1048576 --no-preview -o ";

std::string scratch(const std::string& name) {
    return "/tmp/brdfbake-progress-" + std::to_string(::getpid()) + "-" + name;
}

}  // namespace

TEST_CASE("progress: lines when stderr is not a terminal, nothing with --quiet, same table", "[cli][progress]") {
    const std::string a = scratch("a.csv"), b = scratch("b.csv");
    const auto shown = run_cli(kLong + a);
    REQUIRE(shown.status == 0);
    INFO(shown.err);
    const std::regex line(R"(brdfbake: +([0-9]+)% of albedo of 4096 cells, 1048576 samples each \([0-9.]+ s)");
    CHECK(std::regex_search(shown.err, line));
    CHECK(shown.err.find("100% of albedo") != std::string::npos);
    CHECK(shown.err.find('\r') == std::string::npos);  // no terminal control in a log
    const auto quiet = run_cli("--quiet " + kLong + b);
    REQUIRE(quiet.status == 0);
    CHECK(quiet.err.find("% of") == std::string::npos);
    CHECK(testing::slurp(a) == testing::slurp(b));
    // Slicing the launch changes no number: texel (10, 20) equals the same cell integrated alone
    // in one launch (one cell of 2^20 samples is far below the slicing threshold).
    const auto alone = run_cli("albedo --model ggx:alpha=0.3203125 --mu 0.1640625 --samples 1048576 --format csv");
    REQUIRE(alone.status == 0);
    // The last line: mu,phi_deg,albedo,error.
    const std::string last = alone.out.substr(alone.out.rfind('\n', alone.out.size() - 2) + 1);
    const size_t second_comma = last.find(',', last.find(',') + 1);
    const double value = std::stod(last.substr(second_comma + 1));
    const std::string table = testing::slurp(a);
    const size_t row = table.find("\n0.1640625,0.3203125,");
    REQUIRE(row != std::string::npos);
    const double texel = std::stod(table.substr(row + std::string("\n0.1640625,0.3203125,").size()));
    CHECK(std::fabs(texel - value) <= 5e-9 * value);
    const auto short_run = run_cli("albedo --model ggx:alpha=0.5 --mu 0.5");
    CHECK(short_run.err.find("% of") == std::string::npos);
    std::remove(a.c_str());
    std::remove(b.c_str());
}

TEST_CASE("progress: a bar redrawn in place on a terminal", "[cli][progress]") {
    const std::string out = scratch("t.csv"), log = scratch("tty.log");
    // script(1) runs the command with a pseudo-terminal as its stdin, stdout and stderr.
    const std::string cmd = "script -qec '" + std::string(BRDFBAKE_EXE) + " " + kLong + out + "' " + log +
                            " >/dev/null 2>&1";
    REQUIRE(WEXITSTATUS(std::system(cmd.c_str())) == 0);
    const std::string text = testing::slurp(log);
    INFO(text);
    CHECK(text.find("\r\033[K[") != std::string::npos);       // redrawn in place
    CHECK(std::regex_search(text, std::regex(R"(\[#+\.*\] +[0-9]+%  albedo of 4096 cells)")));
    CHECK(text.find("brdfbake:  ") == std::string::npos);      // not the plain lines
    std::remove(out.c_str());
    std::remove(log.c_str());
}

// Progress of a long run on stderr: plain lines when stderr is not a terminal, a bar redrawn in
// place on a terminal (run under `script`, which gives the command a pseudo-terminal), nothing
// with --quiet, nothing for a short run, and never a change in the numbers.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <vector>

#include "brdfbake/progress.h"
#include "support.h"

using testing::run_cli;

namespace {

// BRDFBAKE_PROGRESS_DELAY=0 shows a command's progress from the start, so that the forms are
// tested however fast the machine (a run shorter than the default second would show nothing, as
// it should).
const std::string kShow = "BRDFBAKE_PROGRESS_DELAY=0 ";

testing::CliResult run_shown(const std::string& args) {
    return testing::run_shell(kShow + std::string(BRDFBAKE_EXE) + " " + args);
}

/// run_shown of a command that must succeed.
testing::CliResult run_shown_ok(const std::string& args) {
    testing::CliResult r = run_shown(args);
    INFO(args << ": " << r.err);
    REQUIRE(r.status == 0);
    return r;
}

// 4096 texels x 2^20 samples: 2^32 samples, sliced into launches (more than 2^28), a second or two.
const std::string kLong = "lut albedo --model ggx --size 64x64 --samples 1048576 --no-preview -o ";

std::string scratch(const std::string& name) {
    return "/tmp/brdfbake-progress-" + std::to_string(::getpid()) + "-" + name;
}

}  // namespace

TEST_CASE("progress: lines when stderr is not a terminal, nothing with --quiet, same table", "[cli][progress]") {
    const std::string a = scratch("a.csv"), b = scratch("b.csv");
    const auto shown = run_shown_ok(kLong + a);
    INFO(shown.err);
    const std::regex line(R"(brdfbake: +([0-9]+)% of albedo table into [^:]+: albedo of 4096 cells, 1048576 samples each [0-9]+% \([0-9.]+ s)");
    CHECK(std::regex_search(shown.err, line));
    CHECK(shown.err.find("100% of albedo table into " + a) != std::string::npos);
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
    // kShow: the bar from the start, however fast the run (without it the test needed a run
    // longer than the default second of delay, and would fail on a fast device).
    const std::string cmd = "script -qec '" + kShow + std::string(BRDFBAKE_EXE) + " " + kLong + out + "' " + log +
                            " >/dev/null 2>&1";
    REQUIRE(WEXITSTATUS(std::system(cmd.c_str())) == 0);
    const std::string text = testing::slurp(log);
    INFO(text);
    CHECK(text.find("\r\033[K[") != std::string::npos);       // redrawn in place
    CHECK(std::regex_search(text, std::regex(R"(\[#+\.*\] +[0-9]+%  albedo table into [^:]+: albedo of 4096 cells)")));
    CHECK(text.find("brdfbake:  ") == std::string::npos);      // not the plain lines
    std::remove(out.c_str());
    std::remove(log.c_str());
}

namespace {

const std::string kDielectric =
    "lut dielectric --model ggx --size 16x16x8 --eta-range 1,3 --tolerance 1e-4 --no-preview -o ";
const std::string kCheck = "check --model ggx:alpha=0.5 --resolution 256 --phi-resolution 256";
const std::string kReciprocity = "reciprocity --model ggx:alpha=0.5 --resolution 256 --phi-resolution 256 -o ";


/// The lines of `text` that match `re`, with their first group as a number.
std::vector<double> matches(const std::string& text, const std::regex& re) {
    std::vector<double> out;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back(std::stod((*it)[1].str()));
    return out;
}

}  // namespace

TEST_CASE("progress: a tolerance table reports cells certified over its rounds", "[cli][progress]") {
    const std::string a = scratch("d1.csv"), b = scratch("d2.csv");
    const auto shown = run_shown_ok(kDielectric + a);
    INFO(shown.err);
    // 16x16x8 texels, two sides of the interface: 4096 cells, counted as they are certified.
    const std::regex line(
        R"(brdfbake: +[0-9]+% of dielectric table into [^:]+: rough dielectric of 4096 cells to tolerance 0.0001 \(([0-9]+) of 4096 cells certified\))");
    const std::vector<double> certified = matches(shown.err, line);
    REQUIRE(certified.size() >= 2);
    CHECK(certified.front() == 0);       // the first line, at the start of round 1
    CHECK(certified.back() == 4096);     // the last: every cell met the tolerance
    CHECK(std::is_sorted(certified.begin(), certified.end()));
    CHECK(shown.err.find("brdfbake: 100% of dielectric table into " + a) != std::string::npos);
    CHECK(shown.err.find('\r') == std::string::npos);
    const auto quiet = testing::run_shell(kShow + std::string(BRDFBAKE_EXE) + " --quiet " + kDielectric + b);
    REQUIRE(quiet.status == 0);
    CHECK(quiet.err.find("% of") == std::string::npos);
    CHECK(testing::slurp(a) == testing::slurp(b));  // the display changes no number
    std::remove(a.c_str());
    std::remove(b.c_str());
}

TEST_CASE("progress: check and reciprocity report their scans", "[cli][progress]") {
    const auto shown = run_shown_ok(kCheck);
    INFO(shown.err);
    // The stage from its start to its end (the lines between, naming the scan or the furnace,
    // depend on the machine's speed).
    CHECK(std::regex_search(shown.err, std::regex(R"(brdfbake: +0% of check of ggx:alpha=0.5)")));
    CHECK(shown.err.find("brdfbake: 100% of check of ggx:alpha=0.5") != std::string::npos);
    const auto quiet = run_shown("--quiet " + kCheck);
    REQUIRE(quiet.status == 0);
    CHECK(quiet.err.find("% of") == std::string::npos);
    CHECK(quiet.out == shown.out);

    const std::string a = scratch("r1.exr"), b = scratch("r2.exr");
    const auto map = run_shown(kReciprocity + a);
    REQUIRE(map.status == 0);
    INFO(map.err);
    // The scan runs in slices of theta_o rows, each reported: percentages that only grow.
    const std::vector<double> pct =
        matches(map.err, std::regex(R"(brdfbake: +([0-9]+)% of reciprocity scan of 256x256 directions x 256 azimuths)"));
    REQUIRE(pct.size() >= 2);
    CHECK(std::is_sorted(pct.begin(), pct.end()));
    CHECK(pct.back() == 100);
    const auto quiet_map = run_shown("--quiet " + kReciprocity + b);
    REQUIRE(quiet_map.status == 0);
    CHECK(quiet_map.err.find("% of") == std::string::npos);
    CHECK(testing::slurp(a) == testing::slurp(b));
    std::remove(a.c_str());
    std::remove(b.c_str());
}

TEST_CASE("progress: a tolerance table's bar on a terminal", "[cli][progress]") {
    const std::string out = scratch("td.csv"), log = scratch("ttyd.log");
    const std::string cmd = "script -qec '" + kShow + std::string(BRDFBAKE_EXE) + " " + kDielectric + out + "' " +
                            log + " >/dev/null 2>&1";
    REQUIRE(WEXITSTATUS(std::system(cmd.c_str())) == 0);
    const std::string text = testing::slurp(log);
    INFO(text);
    CHECK(std::regex_search(
        text, std::regex(R"(\r\x1b\[K\[[#.]+\] +[0-9]+%  dielectric table into [^:]+: rough dielectric of 4096 cells to tolerance 0.0001 \([0-9]+ of 4096 cells certified\))")));
    CHECK(text.find("brdfbake:  ") == std::string::npos);  // not the plain lines
    std::remove(out.c_str());
    std::remove(log.c_str());
}

namespace {

/// Keeps every state and message it is given.
struct RecordingSink : brdfbake::ProgressSink {
    std::vector<brdfbake::ProgressState> states;
    std::vector<std::string> messages;
    void update(const brdfbake::ProgressState& s) override { states.push_back(s); }
    void message(const std::string& line) override { messages.push_back(line); }
};

}  // namespace

TEST_CASE("progress stages: steps, launches and nested stages fold into the outermost", "[progress][quick]") {
    using namespace brdfbake;
    RecordingSink sink;
    set_progress_sink(&sink);
    {
        ProgressStage outer("outer", 4, "cells", "certified", false);
        REQUIRE(!sink.states.empty());
        const std::uint64_t id = sink.states.back().stage_id;
        outer.update(1, "round 1", 2);
        CHECK(sink.states.back().step == "round 1");
        CHECK(sink.states.back().fraction == Approx(0.25));
        // A launch inside the step: its fraction places the step within the stage.
        report_progress("launch of 8 items", 4, 8);
        CHECK(sink.states.back().step == "round 1");
        CHECK(sink.states.back().step_fraction == Approx(0.5));
        CHECK(sink.states.back().fraction == Approx((1 + 0.5 * 2) / 4.0));
        CHECK(sink.states.back().left_is_step);  // not estimable: the time left is the step's
        {
            ProgressStage inner("inner", 10, "cells");
            inner.update(5, "part");
            const ProgressState& s = sink.states.back();
            CHECK(s.stage_id == id);  // still the outer stage on display
            CHECK(s.what == "outer");
            CHECK(s.step.find("round 1; inner (5 of 10 cells): part") == 0);
            CHECK(s.step_fraction == Approx(0.5));
        }
        CHECK(!sink.states.back().finished);  // the inner stage's end is not the outer's
        outer.update(4);
        {
            ProgressSilence quiet;
            const size_t n = sink.states.size();
            outer.update(4, "silenced");
            report_progress("launch", 1, 2);
            CHECK(sink.states.size() == n);
        }
    }
    CHECK(sink.states.back().finished);
    CHECK(sink.states.back().fraction == 1.0);
    CHECK(sink.states.back().step.empty());
    // Outside any stage, a launch is a stage of its own that may end without a last report.
    report_progress("alone", 1, 3);
    CHECK(sink.states.back().what == "alone");
    CHECK(!sink.states.back().closes);
    report_progress("alone", 3, 3);
    CHECK(sink.states.back().finished);
    progress_message("a line");
    CHECK(sink.messages == std::vector<std::string>{"a line"});
    set_progress_sink(nullptr);
}

TEST_CASE("progress passes: 'pass k of n: NAME', the launch's fraction its pass's share", "[progress][quick]") {
    using namespace brdfbake;
    RecordingSink sink;
    set_progress_sink(&sink);
    {
        // Inside a stage with a step (as bake computes a table): the step names the pass, and a
        // launch halfway through pass 2 of 2 is 3/4 of the step.
        ProgressStage stage("bake", 100);
        stage.update(0, "[1/1] t.exr", 100);
        ProgressPasses passes({"E", "B"});
        progress_next_pass();
        CHECK(sink.states.back().step == "[1/1] t.exr: pass 1 of 2: E");
        report_progress("albedo of 8 cells", 4, 8);
        CHECK(sink.states.back().milestone);  // a pass's first launch: a log writes it at once
        report_progress("albedo of 8 cells", 4, 8);
        CHECK(!sink.states.back().milestone);
        // The words give the launch's own share (half of it), the bar its share of both passes.
        CHECK(sink.states.back().step_fraction == Approx(0.5));
        CHECK(sink.states.back().fraction == Approx(0.25));
        progress_next_pass();
        report_progress("albedo of 8 cells", 4, 8);
        CHECK(sink.states.back().step == "[1/1] t.exr: pass 2 of 2: B");
        CHECK(sink.states.back().step_fraction == Approx(0.5));
        CHECK(sink.states.back().fraction == Approx(0.75));
        // A pass beyond the names counts on with the last name.
        progress_next_pass();
        CHECK(sink.states.back().step == "[1/1] t.exr: pass 3 of 3: B");
    }
    {
        // Outside any stage (`lut`): each pass's launch is a stage of its own, named by its pass.
        ProgressPasses passes({"R at 650 nm", "G at 550 nm"});
        progress_next_pass();
        report_progress("albedo of 8 cells", 8, 8);
        CHECK(sink.states.back().what == "pass 1 of 2: R at 650 nm: albedo of 8 cells");
        progress_next_pass();
        report_progress("albedo of 8 cells", 2, 8);
        CHECK(sink.states.back().what == "pass 2 of 2: G at 550 nm: albedo of 8 cells");
        CHECK(sink.states.back().fraction == Approx(0.25));
    }
    // Without passes, nothing is added.
    report_progress("albedo of 8 cells", 8, 8);
    CHECK(sink.states.back().what == "albedo of 8 cells");
    set_progress_sink(nullptr);
}

TEST_CASE("progress: a split-sum table names its two passes, E then B (Karis 2013)", "[cli][progress]") {
    // dfg integrates every cell twice: E with F = 1 and B with Schlick's F at f0 = 0.
    const std::string out = scratch("dfg.csv"), picture = scratch("dfg.png");
    const auto shown = run_shown_ok("lut dfg --model ggx --size 64x64 --samples 65536 --preview " + picture + " -o " + out);
    INFO(shown.err);
    const size_t first = shown.err.find("pass 1 of 2: E (F = 1): albedo of 4096 cells");
    const size_t second = shown.err.find("pass 2 of 2: B (F = Schlick, f0 = 0): albedo of 4096 cells");
    const size_t drawing = shown.err.find("dfg table into " + out + ": drawing its preview " + picture);
    CHECK(first != std::string::npos);
    CHECK(second != std::string::npos);
    CHECK(drawing != std::string::npos);  // the preview is a step of its own, after the passes
    CHECK(first < second);
    CHECK(second < drawing);
    CHECK(shown.err.find("pass 3") == std::string::npos);
    // One bar across both passes, as in a bake: every line is of the one stage, its percentage
    // never goes back, and the second pass starts at half of it (two passes of equal samples).
    const std::regex line(R"(brdfbake: +([0-9]+)% of (.+?)(?=: | \())");
    std::vector<double> pct;
    for (auto it = std::sregex_iterator(shown.err.begin(), shown.err.end(), line); it != std::sregex_iterator(); ++it) {
        CHECK((*it)[2].str() == "dfg table into " + out);
        pct.push_back(std::stod((*it)[1].str()));
    }
    REQUIRE(pct.size() >= 3);
    CHECK(std::is_sorted(pct.begin(), pct.end()));
    CHECK(pct.back() == 100);
    const std::string second_line = shown.err.substr(shown.err.rfind('\n', second) + 1);
    std::smatch at_second;
    REQUIRE(std::regex_search(second_line, at_second, std::regex(R"(^brdfbake: +([0-9]+)%)")));
    CHECK(std::stod(at_second[1].str()) >= 50);
    std::remove(out.c_str());
    std::remove(picture.c_str());
}

// `plan`'s estimates from a calibration file (host/scene/calibration.h, docs/scenes.md
// "Estimates"): a table's estimate is its samples over the file's rate plus the file's fixed and
// preview seconds (the figures written here, not the program's); another machine's file and a
// file that is not a calibration leave the built-in figures, the latter with one warning, and are
// never overwritten; a bake records its stages into the file; a corrupt file never crashes.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "scene/calibration.h"
#include "scene_support.h"
#include "support.h"

namespace {

using nlohmann::json;

std::string host_name() {
    char name[256] = {0};
    ::gethostname(name, sizeof name - 1);
    return name;
}

std::string slurp_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream f(path);
    f << text;
    REQUIRE(f.good());
}

/// A fresh scratch folder, created.
std::string scratch_dir(const std::string& name) {
    const std::string dir = testing::scene::fresh_tmp_dir(name);
    REQUIRE(std::system(("mkdir -p " + dir).c_str()) == 0);
    return dir;
}

/// A calibration of this machine: GGX albedo tables at `rate` samples/s after `fixed` s, previews
/// of `preview` s plus 1e-6 s a texel (two runs on each line, so that the lines are exact).
std::string calibration_text(double rate, double fixed, double preview, const std::string& host = host_name()) {
    json j = {{"format", "brdfbake-calibration"},
              {"version", 2},
              {"host", host},
              {"hardware_threads", std::max(1u, std::thread::hardware_concurrency())},
              {"bakes", 3},
              {"tables", {{"albedo ggx float", {{"runs", {{1e8, fixed + 1e8 / rate}, {4e8, fixed + 4e8 / rate}}}}}}},
              {"previews", {{"runs", {{0.0, preview}, {1e6, preview + 1.0}}}}}};
    return j.dump();
}

/// `plan` of the one-albedo-table scene with BRDFBAKE_CALIBRATION=`calibration`.
/// BRDFBAKE_SLOWDOWN=`slowdown`: assumed, not measured (by default idle cores: the figures alone
/// make the estimate).
json plan_with(const std::string& calibration, const std::string& slowdown = "1") {
    const auto r = testing::run_shell("BRDFBAKE_SLOWDOWN=" + slowdown + " BRDFBAKE_CALIBRATION='" + calibration + "' " +
                                      std::string(BRDFBAKE_EXE) + " plan " + testing::scene::data("small_bake.json") +
                                      " --tables albedo --samples 4096 --format json");
    INFO(r.err);
    REQUIRE(r.status == 0);
    return json::parse(r.out);
}

/// The albedo table's estimate, samples and texels.
struct Estimate {
    double seconds = 0, samples = 0, texels = 0;
};

Estimate albedo_table(const json& plan) {
    for (const auto& t : plan["tables"])
        if (t["kind"] == "albedo")
            return {t["estimated_seconds"].get<double>(), t["samples_total"].get<double>(), t["cells"].get<double>()};
    FAIL("no albedo table in the plan");
    return {};
}

}  // namespace

TEST_CASE("plan: a calibration file's figures give the estimate, proportionally", "[scene][calibration][cli]") {
    const std::string dir = scratch_dir("calibration");
    const std::string fast = dir + "/fast.json", slow = dir + "/slow.json";
    write_file(fast, calibration_text(8e8, 0.25, 0.125));
    write_file(slow, calibration_text(2e8, 0.25, 0.125));
    const json p_fast = plan_with(fast), p_slow = plan_with(slow);
    const Estimate e_fast = albedo_table(p_fast), e_slow = albedo_table(p_slow);
    REQUIRE(e_fast.samples > 0);
    REQUIRE(e_slow.samples == e_fast.samples);
    // samples / rate + fixed + the preview's line at the table's texels, from the figures above.
    const double preview = 0.125 + 1e-6 * e_fast.texels;
    CHECK(e_fast.seconds == Approx(e_fast.samples / 8e8 + 0.25 + preview).epsilon(1e-9));
    CHECK(e_slow.seconds == Approx(e_fast.samples / 2e8 + 0.25 + preview).epsilon(1e-9));
    CHECK((e_slow.seconds - 0.25 - preview) / (e_fast.seconds - 0.25 - preview) == Approx(4.0).epsilon(1e-6));
    CHECK(p_fast["estimate"]["basis"].get<std::string>().find("calibrated on this machine") != std::string::npos);
    CHECK(p_fast["warnings"].empty());
    // The file is read, never written, by plan.
    CHECK(slurp_file(fast) == calibration_text(8e8, 0.25, 0.125));
}

TEST_CASE("plan: the estimates are idle-core seconds times the machine's slowdown now", "[scene][calibration][cli]") {
    const std::string dir = scratch_dir("calibration-slowdown");
    const std::string cal = dir + "/cal.json";
    write_file(cal, calibration_text(8e8, 0.25, 0.125));
    const json idle = plan_with(cal), shared = plan_with(cal, "3");
    // The table's integration (its kernels) 3x, its preview (one thread) max(1, 3 / threads)x,
    // from the figures written: samples / 8e8 + 0.25 s, the preview 0.125 s + 1e-6 s a texel.
    const Estimate e = albedo_table(idle);
    const double threads = std::max(1u, std::thread::hardware_concurrency());
    const double integration = e.samples / 8e8 + 0.25, preview = 0.125 + 1e-6 * e.texels;
    CHECK(e.seconds == Approx(integration + preview).epsilon(1e-9));
    CHECK(albedo_table(shared).seconds == Approx(3 * integration + std::max(1.0, 3 / threads) * preview).epsilon(1e-9));
    CHECK(shared["estimate"]["seconds"].get<double>() > 1.4 * idle["estimate"]["seconds"].get<double>());
    CHECK(shared["estimate"]["basis"].get<std::string>().find("3.0x slower than on idle cores") != std::string::npos);
    // A value that is not a slowdown: one line naming the variable, exit 2.
    for (const std::string bad : {"0.5", "fast", "2x"}) {
        const auto r = testing::run_shell("BRDFBAKE_SLOWDOWN=" + bad + " BRDFBAKE_CALIBRATION='" + cal + "' " +
                                          std::string(BRDFBAKE_EXE) + " plan " + testing::scene::data("small_bake.json"));
        INFO(bad << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(r.err.rfind("brdfbake: error: BRDFBAKE_SLOWDOWN='" + bad + "' is not a number", 0) == 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
    // Unset, plan measures it: at least 1 (never faster than idle cores); the basis says so when above.
    const auto measured = testing::run_shell("BRDFBAKE_CALIBRATION='" + cal + "' " + std::string(BRDFBAKE_EXE) + " plan " +
                                             testing::scene::data("small_bake.json") +
                                             " --tables albedo --samples 4096 --format json");
    REQUIRE(measured.status == 0);
    CHECK(albedo_table(json::parse(measured.out)).seconds >= albedo_table(idle).seconds * (1 - 1e-9));
}

TEST_CASE("slowdown clock: one busy thread has one of the hardware threads", "[scene][calibration][quick]") {
    // A single thread can use one core: wall x threads / CPU is at least the thread count (more
    // when others share the core), whatever the machine.
    const double threads = std::max(1u, std::thread::hardware_concurrency());
    const brdfbake::SlowdownClock clock;
    volatile double x = 0;
    while (clock.wall_seconds() < 0.2) x = x + std::sqrt(x + 1.0);
    CHECK(clock.slowdown() >= 0.9 * threads);
    // Too little CPU time to say (a sleep): 1.
    const brdfbake::SlowdownClock idle;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    CHECK(idle.slowdown() == 1.0);
}

TEST_CASE("calibration: a bake's times are recorded over the slowdown it ran at", "[scene][calibration][quick]") {
    using namespace brdfbake;
    BakeTimings t;
    t.tables.push_back({"albedo", "ggx", "float", 1000000, 6.0});
    t.previews.push_back({4096.0, 1.5});
    t.programs = 2;
    t.build_seconds = 3.0;
    t.report_checks = 4;
    t.report_seconds = 12.0;
    t.slowdown = 3.0;
    Calibration c;
    add_bake_timings(c, t);
    REQUIRE(c.tables["albedo ggx float"].runs.size() == 1);
    CHECK(c.tables["albedo ggx float"].runs[0].second == Approx(2.0));
    // Previews and builds are single-threaded: over max(1, 3 / threads).
    const double serial = std::max(1.0, 3.0 / std::max(1u, std::thread::hardware_concurrency()));
    CHECK(c.previews.runs[0].second == Approx(1.5 / serial));
    CHECK(c.build_seconds_per_program.value == Approx(1.5 / serial));
    CHECK(c.report_check_seconds.value == Approx(1.0));
}

TEST_CASE("plan: another machine's calibration and none give the built-in figures", "[scene][calibration][cli]") {
    const std::string dir = scratch_dir("calibration-other");
    const std::string other = dir + "/other.json";
    write_file(other, calibration_text(1e3, 100.0, 100.0, host_name() + "-elsewhere"));
    const json builtin = plan_with("off"), elsewhere = plan_with(other), missing = plan_with(dir + "/none.json");
    CHECK(albedo_table(elsewhere).seconds == albedo_table(builtin).seconds);
    CHECK(albedo_table(missing).seconds == albedo_table(builtin).seconds);
    CHECK(builtin["estimate"]["basis"].get<std::string>().find("built-in") != std::string::npos);
    CHECK(elsewhere["warnings"].empty());
}

TEST_CASE("plan: a file that is not a calibration is ignored with one warning and left as it is",
          "[scene][calibration][cli]") {
    const std::string dir = scratch_dir("calibration-corrupt");
    const double builtin = albedo_table(plan_with("off")).seconds;
    const std::string cases[] = {
        "",
        "not json at all",
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"tables\": {",  // cut short
        "[]",
        "{}",
        "{\"format\": \"something-else\"}",
        "{\"format\": \"brdfbake-calibration\", \"version\": 7}",
        calibration_text(-5, 0.1, 0.1),    // a negative rate
        calibration_text(0, 0.1, 0.1),     // a zero rate
        calibration_text(1e8, -1, 0.1),    // negative fixed seconds
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"host\": 5, \"tables\": []}",
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"tables\": {\"albedo ggx float\": "
        "{\"runs\": [[1e8, \"fast\"]]}}}",
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"tables\": {\"albedo ggx float\": "
        "{\"samples_per_second\": 1e8}}}",
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"previews\": {\"runs\": [[64, 1e999]]}}",
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"previews\": {\"runs\": [[64]]}}",
        "{\"format\": \"brdfbake-calibration\", \"version\": 2, \"kernel_build_seconds\": {\"value\": 0, "
        "\"measurements\": 1}}",
    };
    int k = 0;
    for (const std::string& text : cases) {
        const std::string path = dir + "/bad" + std::to_string(k++) + ".json";
        write_file(path, text);
        INFO("calibration file: " << text);
        const json p = plan_with(path);
        CHECK(albedo_table(p).seconds == builtin);
        int warnings = 0;
        for (const auto& w : p["warnings"])
            if (w.get<std::string>().find("calibration file '" + path + "' ignored") != std::string::npos) ++warnings;
        CHECK(warnings == 1);
        CHECK(slurp_file(path) == text);
    }
    // A bake with such a file bakes, says so once, and does not write into it.
    const std::string bad = dir + "/bad1.json", out = dir + "/out";
    const auto r = testing::run_shell("BRDFBAKE_CALIBRATION='" + bad + "' " + std::string(BRDFBAKE_EXE) + " bake " +
                                      testing::scene::data("small_bake.json") +
                                      " --tables albedo --no-report --no-previews -o " + out);
    INFO(r.err);
    CHECK(r.status == 0);
    size_t said = 0;
    for (size_t at = r.err.find("calibration file"); at != std::string::npos; at = r.err.find("calibration file", at + 1))
        ++said;
    CHECK(said == 1);
    CHECK(slurp_file(bad) == "not json at all");
    // A file of this format that cannot be used (another version) is this program's: the next
    // bake replaces it with its measurements.
    const std::string old_version = dir + "/bad6.json";
    const auto replaced = testing::run_shell("BRDFBAKE_CALIBRATION='" + old_version + "' " + std::string(BRDFBAKE_EXE) +
                                             " bake " + testing::scene::data("small_bake.json") +
                                             " --tables albedo --no-report --no-previews --force -o " + out);
    INFO(replaced.err);
    CHECK(replaced.status == 0);
    CHECK(replaced.err.find("the next bake replaces it") != std::string::npos);
    CHECK(json::parse(slurp_file(old_version))["bakes"] == 1);
}

TEST_CASE("bake records its stages into the calibration file, which plan then uses", "[scene][calibration][cli]") {
    const std::string dir = scratch_dir("calibration-bake");
    const std::string cal = dir + "/sub/calibration.json", out = dir + "/out";
    const auto r = testing::run_shell("BRDFBAKE_CALIBRATION='" + cal + "' " + std::string(BRDFBAKE_EXE) + " bake " +
                                      testing::scene::data("small_bake.json") + " --tables albedo --no-report -o " + out);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const json c = json::parse(slurp_file(cal));
    CHECK(c["format"] == "brdfbake-calibration");
    CHECK(c["bakes"] == 1);
    CHECK(c["host"] == host_name());
    REQUIRE(c["tables"].contains("albedo ggx float"));
    CHECK(c["tables"]["albedo ggx float"]["runs"].size() == 1);
    REQUIRE(c["previews"]["runs"].size() == 1);
    CHECK(c["previews"]["runs"][0][0].get<double>() == albedo_table(plan_with("off")).texels);  // its texels
    CHECK(c["previews"]["runs"][0][1].get<double>() > 0);
    CHECK(!c.contains("report_check_seconds"));  // --no-report: no check was timed
    // plan now says where its figures come from.
    CHECK(plan_with(cal)["estimate"]["basis"].get<std::string>().find("from 1 bake") != std::string::npos);
    // A second bake adds to it; no temporary file is left beside it.
    const auto again = testing::run_shell("BRDFBAKE_CALIBRATION='" + cal + "' " + std::string(BRDFBAKE_EXE) + " bake " +
                                          testing::scene::data("small_bake.json") +
                                          " --tables albedo --no-report --force -o " + out);
    REQUIRE(again.status == 0);
    CHECK(json::parse(slurp_file(cal))["bakes"] == 2);
    CHECK(testing::run_shell("ls -a " + dir + "/sub").out == ".\n..\ncalibration.json\n");
}

TEST_CASE("bake: each table's logged estimate is the plan's at the same slowdown", "[scene][calibration][cli]") {
    // The figures written (8e8 samples/s after 0.25 s; a preview 0.125 s + 1e-6 s a texel) at a
    // slowdown of 3 give the table's estimate: its integration 3x, its preview max(1, 3 / threads)x.
    // The bake logs that estimate before the table (its first: no table has measured the machine yet).
    const std::string dir = scratch_dir("calibration-bake-estimate");
    const std::string cal = dir + "/cal.json", out = dir + "/out";
    write_file(cal, calibration_text(8e8, 0.25, 0.125));
    const Estimate e = albedo_table(plan_with(cal, "3"));
    const auto r = testing::run_shell("BRDFBAKE_SLOWDOWN=3 BRDFBAKE_CALIBRATION='" + cal + "' " + std::string(BRDFBAKE_EXE) +
                                      " bake " + testing::scene::data("small_bake.json") +
                                      " --tables albedo --samples 4096 --no-report -o " + out);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const size_t at = r.err.find("[1/");
    REQUIRE(at != std::string::npos);
    const size_t est = r.err.find("(estimate ", at);
    REQUIRE(est != std::string::npos);
    const double logged = std::stod(r.err.substr(est + 10));
    const double threads = std::max(1u, std::thread::hardware_concurrency());
    const double expected = 3 * (e.samples / 8e8 + 0.25) + std::max(1.0, 3 / threads) * (0.125 + 1e-6 * e.texels);
    CHECK(logged == Approx(expected).epsilon(6e-3));  // printed to 3 significant digits
}

TEST_CASE("plan: a cold PoCL kernel cache is found and its builds estimated as compiles", "[scene][calibration][cli]") {
    // A fresh POCL_CACHE_DIR holds no program: the probe's build compiles (the compiler starts),
    // and the plan says the cache is cold; once that program is cached, the next plan finds it warm.
    const std::string dir = scratch_dir("calibration-cold");
    const std::string run = "POCL_CACHE_DIR='" + dir + "/pocl' BRDFBAKE_CALIBRATION='" + dir + "/cal.json' " +
                            std::string(BRDFBAKE_EXE) + " plan " + testing::scene::data("small_bake.json") +
                            " --format json";
    const auto cold = testing::run_shell(run);
    INFO(cold.err);
    REQUIRE(cold.status == 0);
    const auto warm = testing::run_shell(run);
    REQUIRE(warm.status == 0);
    const json c = json::parse(cold.out)["estimate"], w = json::parse(warm.out)["estimate"];
    CHECK(c["kernel_cache_cold"] == true);
    CHECK(w["kernel_cache_cold"] == false);
    // A compile costs ~20x a cached build (1.2 s against 0.02-0.05 s): more than the two plans'
    // slowdowns can differ by.
    CHECK(c["kernel_build_seconds"].get<double>() > w["kernel_build_seconds"].get<double>());
}

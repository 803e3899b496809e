// `brdfbake bench`'s table-kind rows and estimate (benchmarks/harness/bench.h), in the quick
// mode: a row per kind of the registry, each from a table that met its tolerance, and an
// estimate with its phases. Speed itself is measured by the benchmark, never asserted here.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "brdfbake/table_kinds.h"
#include "harness/bench.h"
#include "harness/bench_internal.h"

using namespace brdfbake;

TEST_CASE("bench: a row per table kind of the registry, an estimate and its phases", "[bench][device]") {
    BenchOptions o = BenchOptions::quick_options();
    o.build_times = false;  // keep the test's PoCL cache (a fresh one would rebuild every kernel)
    std::ostringstream log;
    const BenchReport r = run_bench(o, log);
    REQUIRE(r.agreed);
    INFO(log.str());
    const auto& rows = r.json.at("kinds");
    std::set<std::string> seen;
    for (const auto& row : rows) {
        INFO(row.dump());
        CHECK(row.at("precision") == "float");
        seen.insert(row.at("kind").get<std::string>());
        // Every kind has a model and Fresnel term of the registry that it accepts, and its
        // table, computed to the tolerance, reports an error within it.
        REQUIRE(row.contains("seconds"));
        CHECK(row.at("seconds").get<double>() > 0.0);
        // (a simulated kind runs a fixed walk count: its error is reported, no tolerance asked)
        if (!table_kind(row.at("kind").get<std::string>()).simulated)
            CHECK(row.at("max_error").get<double>() <= o.kind_tolerance);
        CHECK(row.at("cells").get<double>() >= row.at("texels").get<double>());
        CHECK(r.markdown.find("| " + row.at("kind").get<std::string>() + " | ") != std::string::npos);
    }
    CHECK(rows.size() == table_kinds().size());
    for (const TableKind* k : table_kinds()) CHECK(seen.count(k->name) == 1);
    // The estimate came first in the log, and each phase has its estimate and its time.
    CHECK(log.str().rfind("machine: ", 0) == 0);
    CHECK(log.str().find("bench: about ") < log.str().find("float: kernel"));
    CHECK(r.json.at("estimated_seconds").get<double>() > 0.0);
    REQUIRE(!r.json.at("phases").empty());
    for (const auto& p : r.json.at("phases")) {
        CHECK(p.at("estimated_seconds").get<double>() > 0.0);
        CHECK(p.contains("seconds"));
    }
}

TEST_CASE("bench: POCL_CACHE_DIR is set only for the build times, then restored", "[bench]") {
    using bench_detail::ScopedEnvironment;
    const char* name = "BRDFBAKE_TEST_SCOPED_ENV";
    ::unsetenv(name);
    {
        ScopedEnvironment e(name, std::string("/tmp/a"));
        CHECK(std::string(std::getenv(name)) == "/tmp/a");
    }
    CHECK(std::getenv(name) == nullptr);  // unset before: unset after
    ::setenv(name, "before", 1);
    {
        ScopedEnvironment e(name, std::string("/tmp/b"));
        CHECK(std::string(std::getenv(name)) == "/tmp/b");
        e.restore();
        CHECK(std::string(std::getenv(name)) == "before");
        ::setenv(name, "changed later", 1);
    }
    CHECK(std::string(std::getenv(name)) == "changed later");  // restored once, not twice
    { ScopedEnvironment e(name, std::nullopt); }                 // no value: left alone
    CHECK(std::string(std::getenv(name)) == "changed later");
    ::unsetenv(name);
}

namespace {

/// The bench caches in `dir`: the bench creates its fresh PoCL cache in the temporary directory.
std::set<std::string> bench_caches(const std::filesystem::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().filename().string().rfind("brdfbake-bench-cache-", 0) == 0) names.insert(entry.path().string());
    return names;
}

/// One bench run with build times under POCL_CACHE_DIR = `value` (unset without one): the value
/// comes back and the run's fresh cache directory is removed. PoCL reads its cache directory once
/// per process, at its first use, so each value is a test case of its own (ctest runs every case
/// in a process of its own): a second run in one process would build into the first run's
/// removed directory. The run gets a temporary directory of its own (TMPDIR), so that a bench
/// running beside it (ctest -j) cannot be taken for a cache this one left behind.
void check_bench_gives_cache_dir_back(const std::optional<std::string>& value) {
    BenchOptions o = BenchOptions::quick_options();
    o.build_times = true;
    o.scaling_sizes = {};
    o.scaling_samples = {};
    o.kind_texels = 0;
    const char* old = std::getenv("POCL_CACHE_DIR");
    const std::optional<std::string> before = old ? std::optional<std::string>(old) : std::nullopt;
    namespace fs = std::filesystem;
    const char* old_tmp = std::getenv("TMPDIR");
    const std::optional<std::string> tmp_before = old_tmp ? std::optional<std::string>(old_tmp) : std::nullopt;
    const fs::path private_tmp = fs::temp_directory_path() / ("brdfbake-bench-test-" + std::to_string(::getpid()));
    fs::remove_all(private_tmp);
    fs::create_directories(private_tmp);
    ::setenv("TMPDIR", private_tmp.c_str(), 1);
    if (value)
        ::setenv("POCL_CACHE_DIR", value->c_str(), 1);
    else
        ::unsetenv("POCL_CACHE_DIR");
    std::ostringstream log;
    const BenchReport r = run_bench(o, log);
    REQUIRE(r.agreed);
    CHECK(r.json.at("build").size() >= 1);
    const char* after = std::getenv("POCL_CACHE_DIR");
    if (value) {
        REQUIRE(after != nullptr);
        CHECK(std::string(after) == *value);
    } else {
        CHECK(after == nullptr);
    }
    CHECK(bench_caches(private_tmp).empty());  // none left behind
    if (tmp_before)
        ::setenv("TMPDIR", tmp_before->c_str(), 1);
    else
        ::unsetenv("TMPDIR");
    fs::remove_all(private_tmp);
    if (before)
        ::setenv("POCL_CACHE_DIR", before->c_str(), 1);
    else
        ::unsetenv("POCL_CACHE_DIR");
}

}  // namespace

TEST_CASE("bench: a run with build times gives a set POCL_CACHE_DIR back and removes its cache", "[bench][device]") {
    const std::string sentinel = (std::filesystem::temp_directory_path() / "brdfbake-test-sentinel-cache").string();
    std::filesystem::create_directories(sentinel);
    check_bench_gives_cache_dir_back(sentinel);
}

TEST_CASE("bench: a run with build times leaves an unset POCL_CACHE_DIR unset and removes its cache", "[bench][device]") {
    check_bench_gives_cache_dir_back(std::nullopt);
}

// `brdfbake bench`'s table-kind rows and estimate (benchmarks/harness/bench.h), in the quick
// mode: a row per kind of the registry, each from a table that met its tolerance, and an
// estimate with its phases. Speed itself is measured by the benchmark, never asserted here.
#include <catch2/catch.hpp>

#include <set>
#include <sstream>

#include "brdfbake/table_kinds.h"
#include "harness/bench.h"

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

// Shards (`lut --shard K/N`, `brdfbake merge`) and launch-independent cell values, the basis of
// both shards and MPI jobs (docs/cluster.md). The reference is always the program's own
// unsharded run: the property under test is that the split changes no bit of the file.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <string>
#include <vector>

#include "support.h"

using testing::run_cli;
using testing::slurp;

namespace {

std::string shard_path(const std::string& name) {
    return "/tmp/brdfbake-shard-" + std::to_string(::getpid()) + "-" + name;
}

bool exists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

// Runs `lut ARGS` whole into NAME.exr and as `shards` shards merged into NAME-merged.exr.
void check_shards_reproduce(const std::string& args, const std::string& name, int shards) {
    const std::string whole = shard_path(name + ".exr"), merged = shard_path(name + "-merged.exr");
    const auto w = run_cli("lut " + args + " --no-preview -q -o " + whole);
    REQUIRE(w.status == 0);
    std::string parts;
    for (int k = 0; k < shards; ++k) {
        const std::string part = shard_path(name + ".part" + std::to_string(k));
        const auto s = run_cli("lut " + args + " --no-preview -q --shard " + std::to_string(k) + "/" +
                               std::to_string(shards) + " -o " + part);
        INFO(s.err);
        REQUIRE(s.status == 0);
        parts += " " + part;
    }
    const auto m = run_cli("merge" + parts + " -q -o " + merged);
    INFO(m.err);
    REQUIRE(m.status == 0);
    const std::string a = slurp(whole), b = slurp(merged);
    REQUIRE(!a.empty());
    CHECK(a == b);
    std::remove(whole.c_str());
    std::remove(merged.c_str());
    for (int k = 0; k < shards; ++k) std::remove(shard_path(name + ".part" + std::to_string(k)).c_str());
}

}  // namespace

TEST_CASE("mc: a cell's value does not depend on the other cells of its launch", "[shard][device]") {
    using namespace brdfbake;
    // The Philox stream of a cell comes from its content (cell_identity), so the middle cell of
    // a three-cell launch and the same cell alone see the same samples: equal to the last bit.
    AlbedoRequest all = testing::albedo_request("ggx:alpha=0.5", {0.2, 0.5, 0.9}, Method::MonteCarlo,
                                                Precision::Double, 1 << 12);
    AlbedoRequest one = testing::albedo_request("ggx:alpha=0.5", {0.5}, Method::MonteCarlo, Precision::Double, 1 << 12);
    const AlbedoResult a = compute_albedo(testing::engine(), all), b = compute_albedo(testing::engine(), one);
    CHECK(a.values[1].value == b.values[0].value);
    CHECK(a.values[1].error == b.values[0].error);
    // And two different cells do not share a stream: their replicas differ.
    CHECK(a.values[0].value != a.values[2].value);
}

TEST_CASE("lut --shard K/N + merge reproduce the unsharded table byte for byte", "[shard][device]") {
    SECTION("fixed sample count, 3 shards") {
        check_shards_reproduce("albedo --model ggx --size 8x4 --samples 4096", "fixed", 3);
    }
    SECTION("tolerance mode (quadrature and importance sampling rounds), 2 shards") {
        check_shards_reproduce("albedo --model torrance-sparrow --size 6x3 --tolerance 1e-3 --max-samples 262144",
                               "tolerance", 2);
    }
    SECTION("3D dielectric table, 2 shards") {
        check_shards_reproduce("dielectric --model ggx --size 4x3x3 --samples 1024", "dielectric", 2);
    }
}

TEST_CASE("merge refuses missing, duplicate and mismatched shards (exit 2, one line, no table)", "[shard][device]") {
    const std::string args = "lut albedo --model ggx --size 4x2 --samples 1024 --no-preview -q";
    const std::string p0 = shard_path("r.part0"), p1 = shard_path("r.part1"), p2 = shard_path("r.part2"),
                      other = shard_path("r.other1"), out = shard_path("r-merged.exr");
    REQUIRE(run_cli(args + " --shard 0/3 -o " + p0).status == 0);
    REQUIRE(run_cli(args + " --shard 1/3 -o " + p1).status == 0);
    REQUIRE(run_cli(args + " --shard 2/3 -o " + p2).status == 0);
    REQUIRE(run_cli("lut albedo --model ggx --size 4x2 --samples 2048 --no-preview -q --shard 1/3 -o " + other).status ==
            0);
    struct Case {
        std::string parts, says;
    };
    for (const Case& c : {Case{p0 + " " + p2, "shard 1 of 3 missing"}, Case{p0 + " " + p1 + " " + p1 + " " + p2, "both shard 1"},
                          Case{p0 + " " + other + " " + p2, "different commands"},
                          Case{p0 + " " + shard_path("none.part"), "cannot read part file"}}) {
        const auto r = run_cli("merge " + c.parts + " -o " + out);
        INFO(c.parts << "\n" << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(r.err.find(c.says) != std::string::npos);
        CHECK(!exists(out));
    }
    // A part file from another shard count.
    const std::string q = shard_path("r.q");
    REQUIRE(run_cli(args + " --shard 1/2 -o " + q).status == 0);
    const auto r = run_cli("merge " + p0 + " " + q + " " + p2 + " -o " + out);
    CHECK(r.status == 2);
    CHECK(!exists(out));
    // --shard needs K < N.
    CHECK(run_cli(args + " --shard 3/3 -o " + q).status == 2);
    for (const std::string& p : {p0, p1, p2, other, q}) std::remove(p.c_str());
}

// Hostile and large scenes (issue 31, item 5): nesting depth and value count of a scene's JSON are
// bounded (one line naming the file and the limit, exit 2, within little memory), and planning a
// scene of many materials grows linearly with their number.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <string>

#include "brdfbake/error.h"
#include "scene/json_read.h"
#include "scene/scene.h"
#include "scene_support.h"
#include "support.h"

using namespace brdfbake;
using namespace testing::scene;

namespace {

std::string write_scene(const std::string& name, const std::string& text) {
    const std::string path = "/tmp/brdfbake-limits-" + std::to_string(::getpid()) + "-" + name;
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
    return path;
}

/// A scene whose "comment" nests `depth` arrays.
std::string nested(std::size_t depth) {
    return "{\"comment\": " + std::string(depth, '[') + std::string(depth, ']') +
           ", \"materials\": [{\"name\": \"a\", \"model\": \"ggx\", \"roughness\": 0.5}]}";
}

/// A scene of `n` GGX materials, each its own name and roughness range.
std::string many_materials(int n) {
    std::string s = "{\"materials\": [\n";
    for (int i = 0; i < n; ++i) {
        char m[160];
        std::snprintf(m, sizeof m, "%s{\"name\": \"m%d\", \"model\": \"ggx\", \"fresnel\": \"schlick:f0=0.04\", "
                                   "\"roughness\": [%.6f, 0.9]}",
                      i ? ",\n" : "", i, 0.1 + 0.5 * i / n);
        s += m;
    }
    return s + "]}\n";
}

double seconds_to_plan(const std::string& text) {
    const auto t0 = std::chrono::steady_clock::now();
    const Plan p = make_plan(parse_scene_json(text, "many.json"));
    const std::string report = plan_text(p) + plan_json(p);
    CHECK(p.tables.size() == 2);  // albedo and eavg, shared by all
    CHECK(p.tables[0].materials.size() == p.materials.size());
    CHECK(!report.empty());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("scene JSON nesting deeper than the limit is refused with the file and the limit", "[scene][quick]") {
    const std::size_t limit = scene_json::kMaxJsonDepth;
    CHECK_NOTHROW(parse_scene_json(nested(limit - 1), "ok.json"));  // the scene object is one level
    for (std::size_t depth : {limit + 1, std::size_t(100000)}) {
        const std::string e = error_of([&] { parse_scene_json(nested(depth), "deep.json"); });
        INFO(e);
        CHECK(e.find("scene 'deep.json'") == 0);
        CHECK(e.find("deeper than " + std::to_string(limit)) != std::string::npos);
    }
    // The command line, with its memory capped at 1 GiB: 10^5 levels took 6.9 GB before the bound.
    const std::string file = write_scene("deep.json", nested(100000));
    const auto r = testing::run_shell("ulimit -v 1048576; " + std::string(BRDFBAKE_EXE) + " plan " + file);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("brdfbake: error: scene '" + file + "': arrays and objects nest deeper than 256", 0) == 0);
    CHECK(testing::count_lines(r.err) == 1);
    std::remove(file.c_str());
}

TEST_CASE("scene JSON with more values than the limit is refused", "[scene][quick]") {
    const std::size_t limit = scene_json::kMaxJsonValues;
    std::string many = "{\"comment\": [";
    for (std::size_t i = 0; i < limit; ++i) many += i ? ",0" : "0";
    many += "], \"materials\": [{\"name\": \"a\", \"model\": \"ggx\", \"roughness\": 0.5}]}";
    const std::string e = error_of([&] { parse_scene_json(many, "many.json"); });
    INFO(e);
    CHECK(e.find("scene 'many.json': more than " + std::to_string(limit) + " values") == 0);
}

TEST_CASE("planning 100,000 materials takes seconds and grows linearly", "[scene][quick]") {
    const double small = seconds_to_plan(many_materials(25000));
    const double large = seconds_to_plan(many_materials(100000));
    INFO("25,000 materials: " << small << " s; 100,000: " << large << " s");
    // Quadratic growth makes four times the materials sixteen times the time (61.5 s before).
    CHECK(large < 8 * small + 0.5);
    CHECK(large < 20.0);
}

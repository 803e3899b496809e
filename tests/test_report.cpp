// The bake report (DIR/index.html): self-contained (every picture it shows is a PNG in the folder,
// readable by libpng; no address outside the folder), a section per table of index.json, and the
// lobe checks' verdicts, which for GGX lobes with a real Fresnel term must pass (a single-scattering
// microfacet lobe with F <= 1 neither creates energy nor breaks reciprocity).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "image_readers.h"
#include "support.h"

namespace {

/// The repository's root: this file lives in its tests/ folder.
std::string source_dir() {
    const std::string here = __FILE__;
    return here.substr(0, here.find_last_of('/', here.find_last_of('/') - 1));
}

}  // namespace

TEST_CASE("bake report: a section and a readable preview per table, no outside address, GGX lobes pass",
          "[report][cli]") {
    namespace fs = std::filesystem;
    const std::string dir = "/tmp/brdfbake-report-" + std::to_string(::getpid());
    fs::remove_all(dir);
    REQUIRE(testing::run_cli("bake " + source_dir() + "/examples/scene.json" + " -o " + dir).status == 0);
    CHECK(fs::exists(dir + "/index.html"));  // bake writes its report
    const auto r = testing::run_cli("report " + dir);
    REQUIRE(r.status == 0);
    const std::string page = testing::slurp(dir + "/index.html");
    REQUIRE(!page.empty());
    CHECK(page.find("http:") == std::string::npos);
    CHECK(page.find("https:") == std::string::npos);
    CHECK(page.find("<script") == std::string::npos);
    const nlohmann::json index = nlohmann::json::parse(testing::slurp(dir + "/index.json"));
    for (const auto& t : index["tables"]) {
        const std::string file = t["file"];
        CHECK(page.find("<h2 id=\"" + file + "\">") != std::string::npos);
    }
    // Every image is a file in the folder that libpng reads.
    const std::regex img("<img src=\"([^\"]+)\"");
    int images = 0;
    for (auto it = std::sregex_iterator(page.begin(), page.end(), img); it != std::sregex_iterator(); ++it) {
        const std::string src = (*it)[1];
        CHECK(src.find("..") == std::string::npos);
        const testing::Png p = testing::read_png8(dir + "/" + src);
        CHECK(p.width > 100);
        ++images;
    }
    CHECK(images == int(index["tables"].size()));
    CHECK(page.find("class=\"pass\">PASS") != std::string::npos);
    CHECK(page.find("VIOLATION") == std::string::npos);
    // Not a bake folder: refused with exit 2, nothing written.
    const std::string empty = dir + "-empty";
    fs::create_directories(empty);
    CHECK(testing::run_cli("report " + empty).status == 2);
    CHECK(!fs::exists(empty + "/index.html"));
    fs::remove_all(dir);
    fs::remove_all(empty);
}

TEST_CASE("bake report: a deep 3D table's summary links its full-size picture, a PNG in the folder",
          "[report][cli]") {
    namespace fs = std::filesystem;
    const std::string dir = "/tmp/brdfbake-report-deep-" + std::to_string(::getpid());
    fs::remove_all(dir);
    fs::create_directories(dir);
    // Glasses from eta 1.3 to 1.6: a dielectric table with 7 eta slices (0.05 apart), more than a
    // summary shows.
    const std::string scene = dir + "-scene.json";
    std::ofstream(scene) << R"({"settings": {"samples": 256, "mu_texels": 8, "alpha_texels": 8},
 "materials": [{"name": "glass", "model": "ggx", "eta": [1.3, 1.6], "roughness": [0.2, 0.4]}]})";
    REQUIRE(testing::run_cli("bake " + scene + " -o " + dir + " --no-report").status == 0);
    const nlohmann::json index = nlohmann::json::parse(testing::slurp(dir + "/index.json"));
    REQUIRE(index["tables"].size() == 1);
    const auto& entry = index["tables"][0];
    REQUIRE(entry["axes"].size() == 3);
    CHECK(entry["axes"][2]["size"] == 7);
    REQUIRE(entry.contains("preview_full"));
    const std::string full = entry["preview_full"], summary = entry["preview"];
    REQUIRE(testing::run_cli("report " + dir).status == 0);
    const std::string page = testing::slurp(dir + "/index.html");
    // The summary is the thumbnail, and the link around it leads to the full-size picture.
    CHECK(page.find("<a href=\"" + full + "\"><img src=\"" + summary + "\"") != std::string::npos);
    const testing::Png big = testing::read_png8(dir + "/" + full), small = testing::read_png8(dir + "/" + summary);
    // All 7 slices side by side against the summary's 4, each panel at least as large.
    CHECK(big.width >= small.width * 7 / 4);
    CHECK(big.height >= small.height);
    for (const auto& e : fs::directory_iterator(dir + "/previews"))
        CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
    fs::remove_all(dir);
    fs::remove(scene);
}

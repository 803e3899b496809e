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

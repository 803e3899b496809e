// The bake report as a person sees it: DIR/index.html rendered by headless Chromium (Debian's
// `chromium`, installed by scripts/setup.sh). The browser, not our code, says whether each picture
// loads (an <img> whose file is missing or not an image has naturalWidth 0 once the page has
// loaded) and what the page looks like (its screenshot is not blank). A failed bake's report says
// it failed and links no file the folder lacks. Also: a lobe whose roughness range starts at 0 is
// checked (at the floor) rather than "not checked", numbers read as written (16384, not
// 1.638e+04), and warnings shared by materials are one line.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "image_readers.h"
#include "support.h"

namespace {

namespace fs = std::filesystem;

std::string source_dir() { return BRDFBAKE_SOURCE_DIR; }  // the repository (CMake defines it)

const char* const kChromium = "chromium --headless --no-sandbox --disable-gpu --hide-scrollbars "
                              "--virtual-time-budget=10000 --user-data-dir=";

/// The page with a probe appended: once loaded, the count of images and of broken ones (not
/// complete, or naturalWidth 0) written into the DOM, which Chromium's --dump-dom prints.
std::pair<int, int> images_and_broken(const std::string& dir) {
    std::string page = testing::slurp(dir + "/index.html");
    const size_t end = page.rfind("</body>");
    REQUIRE(end != std::string::npos);
    page.insert(end,
                "<script>window.addEventListener('load',function(){var n=0,b=0;"
                "for(const i of document.images){++n;if(!i.complete||i.naturalWidth===0)++b;}"
                "document.body.setAttribute('data-probe','images='+n+' broken='+b);});</script>");
    std::ofstream(dir + "/probe.html") << page;
    const auto r = testing::run_shell(std::string(kChromium) + dir + "/chrome-profile --dump-dom file://" + dir +
                                      "/probe.html");
    fs::remove(dir + "/probe.html");
    REQUIRE(r.status == 0);
    std::smatch m;
    REQUIRE(std::regex_search(r.out, m, std::regex("data-probe=\"images=([0-9]+) broken=([0-9]+)\"")));
    return {std::stoi(m[1]), std::stoi(m[2])};
}

bool have_chromium() { return testing::run_shell("command -v chromium").status == 0; }

}  // namespace

TEST_CASE("bake report in a browser: every picture loads, the page is not blank", "[report][browser][cli]") {
    INFO("headless Chromium is needed: scripts/setup.sh installs Debian's chromium");
    REQUIRE(have_chromium());
    const std::string dir = "/tmp/brdfbake-browser-" + std::to_string(::getpid());
    fs::remove_all(dir);
    REQUIRE(testing::run_cli("bake " + source_dir() + "/tests/data/materials.gltf --samples 4096 -o " + dir).status == 0);
    const std::string page = testing::slurp(dir + "/index.html");
    const nlohmann::json index = nlohmann::json::parse(testing::slurp(dir + "/index.json"));

    const auto [images, broken] = images_and_broken(dir);
    CHECK(images == int(index["tables"].size()));  // a preview per table
    CHECK(broken == 0);

    // The screenshot: a page of text, tables and pictures, not a white (or black) rectangle.
    const std::string shot = dir + "/shot.png";
    REQUIRE(testing::run_shell(std::string(kChromium) + dir + "/chrome-profile --window-size=1100,1400 --screenshot=" +
                               shot + " file://" + dir + "/index.html")
                .status == 0);
    const testing::Png p = testing::read_png8(shot);
    CHECK(p.width == 1100);
    size_t inked = 0, pixels = 0;
    for (size_t k = 0; k + 3 <= p.samples.size(); k += size_t(p.channels), ++pixels)
        inked += p.samples[k] + p.samples[k + 1] + p.samples[k + 2] < 600;  // not near white
    CHECK(inked > pixels / 50);                // more than 2% of the page is drawn on
    CHECK(inked < pixels * 9 / 10);            // and it is not one dark rectangle
    CHECK(testing::png_colours(shot) > 200);   // text, tables and coloured previews

    // The user's terms: numbers as written, no lobe left "not checked" for its roughness 0.
    CHECK(page.find("e+0") == std::string::npos);
    CHECK(page.find("needs alpha=VALUE") == std::string::npos);
    CHECK(page.find("<td>samples</td><td>4096</td>") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("bake report of a failed bake: says it failed, names what was not written, links nothing missing",
          "[report][browser][cli]") {
    INFO("headless Chromium is needed: scripts/setup.sh installs Debian's chromium");
    REQUIRE(have_chromium());
    const std::string dir = "/tmp/brdfbake-browser-failed-" + std::to_string(::getpid());
    fs::remove_all(dir);
    const std::string scene = source_dir() + "/tests/data/small_bake.json";
    const auto plan = testing::run_cli("plan " + scene + " --format json");
    REQUIRE(plan.status == 0);
    const nlohmann::json planned = nlohmann::json::parse(plan.out);
    REQUIRE(planned["tables"].size() >= 2);
    // The last table cannot be written: a non-empty folder stands where its file goes.
    const std::string blocked = planned["tables"].back()["file"];
    fs::create_directories(dir + "/" + blocked + "/in-the-way");
    const auto bake = testing::run_cli("bake " + scene + " -o " + dir);
    CHECK(bake.status != 0);
    const std::string page = testing::slurp(dir + "/index.html");
    REQUIRE(!page.empty());
    CHECK(page.find("This bake failed") != std::string::npos);
    CHECK(page.find("Not written: " + blocked) != std::string::npos);
    const auto [images, broken] = images_and_broken(dir);
    CHECK(images >= 1);  // the tables written before the failure keep their previews
    CHECK(broken == 0);
    fs::remove_all(dir);
}

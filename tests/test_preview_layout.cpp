// Previews that cost less than the integration they show (issue 32): a deep 3D table's `lut` (and
// `bake`) preview is a summary of kSummarySlices slices per channel, with no second picture; `show
// --plot` draws the slices full size (kMaxSlices of them, wider than the summary) on demand.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "image_readers.h"
#include "plot/plot.h"
#include "support.h"

TEST_CASE("previews: a deep 3D table's lut preview is a summary, show --plot draws its slices", "[pictures][cli]") {
    const std::string base = "/tmp/brdfbake-preview-layout-" + std::to_string(::getpid());
    const std::string table = base + ".exr", preview = base + ".exr.png", full = base + "-full.png";
    // 12 eta slices, deeper than a summary shows.
    const auto lut = testing::run_cli("lut dielectric --model ggx --size 8x8x12 --samples 64 -o " + table +
                                      " --preview " + preview);
    INFO(lut.err);
    REQUIRE(lut.status == 0);
    CHECK(lut.err.find("shows 4 of 12 slices") != std::string::npos);
    CHECK(lut.err.find("brdfbake show " + table + " --plot") != std::string::npos);
    CHECK(!std::ifstream(brdfbake::full_preview_path(preview)).good());  // no second picture
    const testing::Png summary = testing::read_png8(preview);
    CHECK(summary.width <= brdfbake::kSummaryWidth);
    const auto show = testing::run_cli("show " + table + " --plot " + full);
    INFO(show.err);
    REQUIRE(show.status == 0);
    const testing::Png all = testing::read_png8(full);
    CHECK(all.width > summary.width);  // 8 slices side by side, full size, against the summary's 4
    CHECK(testing::png_colours(full) > 100);
    for (const std::string& f : {table, preview, full}) std::remove(f.c_str());
}

// Pictures read back pixel by pixel with libpng (nothing of brdfbake's): the furnace picture's
// environment has a colour of its own, distinct from a sphere that conserves energy (white), and a
// rough sphere, which loses energy to single scattering, is darker.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "brdfbake/table.h"
#include "image_readers.h"
#include "plot/plot.h"
#include "support.h"

namespace {

std::string scratch(const std::string& name) {
    return "/tmp/brdfbake-pictures-" + std::to_string(::getpid()) + "-" + name;
}

/// The mean of channel c over a 5 x 5 block centred at (x, y) (y from the top).
double block_mean(const testing::Png& p, int x, int y, int c) {
    double sum = 0;
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) sum += p.samples[(size_t(y + dy) * size_t(p.width) + size_t(x + dx)) * size_t(p.channels) + size_t(c)];
    return sum / 25.0;
}

/// Pixels of a colour: |R - r|, |G - g|, |B - b| each at most `tol` (8-bit samples).
size_t count_colour(const testing::Png& p, int r, int g, int b, int tol, int row_lo = 0, int row_hi = -1) {
    size_t n = 0;
    if (row_hi < 0) row_hi = p.height;
    for (int y = row_lo; y < row_hi; ++y)
        for (int x = 0; x < p.width; ++x) {
            const unsigned* s = &p.samples[(size_t(y) * size_t(p.width) + size_t(x)) * size_t(p.channels)];
            if (std::abs(int(s[0]) - r) <= tol && std::abs(int(s[1]) - g) <= tol && std::abs(int(s[2]) - b) <= tol) ++n;
        }
    return n;
}

/// True if every pixel of the rectangle is white (no text or line reaches it).
bool all_white(const testing::Png& p, int x0, int x1, int y0, int y1) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c)
                if (p.samples[(size_t(y) * size_t(p.width) + size_t(x)) * size_t(p.channels) + size_t(c)] < 250) return false;
    return true;
}

/// A table of `channels` channels over mu x alpha (x eta with depth > 1): value = mu (0 to 1).
brdfbake::Table ramp_table(int width, int height, int depth, int channels) {
    using namespace brdfbake;
    Table t;
    t.kind = "albedo";
    t.x = make_axis("mu", "mu = u", 0.0, 1.0, width, Texels::Centre);
    t.x.parameter = t.x.coordinate;
    t.y = make_axis("alpha", "alpha = a", 0.0, 1.0, height, Texels::Centre);
    t.y.parameter = t.y.coordinate;
    t.z = make_axis("eta", "eta = e", 1.0, 3.0, depth, depth > 1 ? Texels::Edge : Texels::Centre);
    t.z.parameter = t.z.coordinate;
    for (int c = 0; c < channels; ++c) t.channels.push_back("E" + std::to_string(c));
    t.values.assign(size_t(channels), {});
    for (int c = 0; c < channels; ++c)
        for (int z = 0; z < depth; ++z)
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) t.values[size_t(c)].push_back(t.x.coordinate[size_t(x)]);
    t.error.assign(t.values[0].size(), 1e-6);
    return t;
}

}  // namespace

TEST_CASE("a table preview's colours are not squashed by one outlier texel, which is drawn red", "[pictures][quick]") {
    // A ramp from 0 to 1 along mu with one texel at E = 11.4 (as a sheen table's grazing texel):
    // coloured over [0, 11.4] the ramp would be dark purple everywhere; clipped at the 99.5th
    // percentile it spans viridis from purple (#440154) to yellow (#FDE725), and the outlier shows
    // in red (#E41A1C), a colour viridis does not hold.
    brdfbake::Table t = ramp_table(32, 32, 1, 1);
    t.values[0][5 * 32 + 31] = 11.4;
    const std::string png = scratch("outlier.png");
    brdfbake::write_table_preview(t, png);
    const testing::Png p = testing::read_png8(png);
    std::remove(png.c_str());
    const size_t yellow = count_colour(p, 0xFD, 0xE7, 0x25, 40), purple = count_colour(p, 0x44, 0x01, 0x54, 30);
    const size_t red = count_colour(p, 0xE4, 0x1A, 0x1C, 30);
    INFO("yellow " << yellow << ", purple " << purple << ", red " << red);
    CHECK(yellow > 2000);  // the top of the ramp (excluding the colour bar's few hundred pixels)
    CHECK(purple > 2000);
    CHECK(red > 50);       // the outlier's cell, about 15 x 13 pixels
    CHECK(red < 2000);
}

TEST_CASE("a deep 3D table is previewed as a summary at most 1600 pixels wide, every slice beside it",
          "[pictures][quick]") {
    // lut dielectric --size 32x32x16: 4 channels of 16 slices.
    brdfbake::Table t = ramp_table(32, 32, 16, 4);
    t.kind = "gen-schlick-ior";  // a long title: "E0 (gen-schlick-ior), eta = 1.933 ..."
    const std::string png = scratch("deep.png"), full = brdfbake::full_preview_path(png);
    CHECK(full == scratch("deep.full.png"));
    brdfbake::write_table_preview(t, png);
    const testing::Png summary = testing::read_png8(png), all = testing::read_png8(full);
    std::remove(png.c_str());
    std::remove(full.c_str());
    CHECK(summary.width <= brdfbake::kSummaryWidth);
    CHECK(summary.width >= 1000);  // panels large enough to read as a thumbnail
    CHECK(all.width > summary.width);  // more slices side by side
    // Titles sized to their panels: no text reaches the picture's edges.
    CHECK(all_white(summary, 0, 3, 0, summary.height));
    CHECK(all_white(summary, summary.width - 3, summary.width, 0, summary.height));
    CHECK(all_white(summary, 0, summary.width, 0, 3));
    // A table of 4 slices or fewer is its own full-size picture: no second file.
    const std::string shallow = scratch("shallow.png");
    brdfbake::write_table_preview(ramp_table(8, 8, 4, 1), shallow);
    CHECK(testing::read_png8(shallow).width <= brdfbake::kSummaryWidth);
    std::remove(shallow.c_str());
    CHECK(!std::ifstream(brdfbake::full_preview_path(shallow)).good());
}

TEST_CASE("titles are shortened and wrapped to fit their panels", "[pictures][quick]") {
    CHECK(brdfbake::short_numbers("dielectric:eta=1.3300000000000001") == "dielectric:eta=1.33");
    CHECK(brdfbake::short_numbers("metal:Al at 550 nm: n = 1.0152 + 6.6273 i") == "metal:Al at 550 nm: n = 1.015 + 6.627 i");
    CHECK(brdfbake::short_numbers("F_0 = 0.04, alpha_x=0.1, 2e-07") == "F_0 = 0.04, alpha_x=0.1, 2e-07");
    CHECK(brdfbake::wrap_at_commas("ggx:alpha_x=0.1,alpha_y=0.5,shadowing=correlated", 30) ==
          "ggx:alpha_x=0.1,alpha_y=0.5,\nshadowing=correlated");
}

TEST_CASE("lobe pictures: 3D panel titles do not run into each other, the plane's axes fit the lobe",
          "[pictures][cli]") {
    const std::string png = scratch("lobe3d.png");
    auto r = testing::run_cli("lobe --model ggx:alpha_x=0.1,alpha_y=0.5 --model ggx:alpha_x=0.5,alpha_y=0.1 "
                              "--theta-i 45 --view 3d -o " + png);
    REQUIRE(r.status == 0);
    testing::Png p = testing::read_png8(png);
    REQUIRE(p.width == 1400);  // two panels of 700 pixels
    // The titles' band (the top fifth): nothing crosses the border between the panels.
    CHECK(all_white(p, 690, 710, 0, p.height / 5));
    CHECK(all_white(p, 0, p.width, 0, 3));  // nor the picture's top edge
    std::remove(png.c_str());

    // The plane of incidence: GGX at 60 degrees peaks at f cos(theta_i) of about 0.8 near theta_o = 60
    // degrees (y ~ 0.4); with the range fitted to the lobe its curve (blue) reaches the upper part of
    // the box, not the bottom fifth of a box as tall as the lobe is wide.
    r = testing::run_cli("lobe --model ggx:alpha=0.3 --theta-i 60 -o " + png);
    REQUIRE(r.status == 0);
    p = testing::read_png8(png);
    std::remove(png.c_str());
    const size_t upper = count_colour(p, 0, 0, 255, 60, int(p.height * 0.28), int(p.height * 0.5));
    CHECK(upper > 20);
    CHECK(all_white(p, 0, p.width, 0, 3));
    CHECK(all_white(p, 0, 3, 0, p.height));
}

TEST_CASE("the Fresnel plot's title is short and inside the picture", "[pictures][cli]") {
    const std::string png = scratch("fresnel.png");
    const auto r = testing::run_cli("fresnel --fresnel conductor:eta=0.2000000000000001,k=3.9000000000000004 --plot " + png);
    REQUIRE(r.status == 0);
    const testing::Png p = testing::read_png8(png);
    std::remove(png.c_str());
    CHECK(all_white(p, 0, p.width, 0, 3));
    CHECK(all_white(p, 0, 3, 0, p.height));
    CHECK(all_white(p, p.width - 3, p.width, 0, p.height));
}

TEST_CASE("furnace picture: the environment has its own colour, a smooth sphere is white, a rough one darker",
          "[pictures][cli]") {
    const std::string png = scratch("furnace.png");
    // Two spheres of 64 pixels: panels of 128 x 140 pixels (square spheres), then the colour bar.
    const auto r = testing::run_cli("furnace --model ggx --roughness 0.05,1 --pixels 64 --nodes 16 --samples 4096 -o " + png);
    REQUIRE(r.status == 0);
    const testing::Png p = testing::read_png8(png);
    REQUIRE(p.channels >= 3);
    const int panel = 128, height = p.height;
    CHECK(p.width > 2 * panel);  // the colour bar's strip
    // A corner of the first panel: the environment, which the README says is drawn in light blue:
    // blue well above red (not a grey of the spheres' scale, nor white), and light.
    const int cx = 8, cy = height - 8;
    const double red = block_mean(p, cx, cy, 0), green = block_mean(p, cx, cy, 1), blue = block_mean(p, cx, cy, 2);
    INFO("environment " << red << ", " << green << ", " << blue);
    CHECK(blue >= red + 40);
    CHECK(blue >= green);
    CHECK(blue >= 160);
    CHECK(red < 245);  // not white
    // The sphere's centre (mu = 1): sheenless GGX at roughness 0.05 (alpha 0.0025) reflects all the
    // energy it receives at normal incidence (E -> 1 as alpha -> 0), so it is white; at
    // roughness 1 single scattering loses a large part of it, so the sphere is clearly grey.
    const int centre_y = int(height * 0.55);
    const double smooth = block_mean(p, panel / 2, centre_y, 0), rough = block_mean(p, panel + panel / 2, centre_y, 0);
    CHECK(smooth > 245);
    CHECK(rough < smooth - 60);
    std::remove(png.c_str());
}

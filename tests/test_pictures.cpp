// Pictures read back pixel by pixel with libpng (nothing of brdfbake's): the furnace picture's
// environment has a colour of its own, distinct from a sphere that conserves energy (white), and a
// rough sphere, which loses energy to single scattering, is darker.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>

#include "image_readers.h"
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

}  // namespace

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

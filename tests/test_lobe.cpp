// `brdfbake lobe`: the numbers behind the picture are the model's values at those angles (the
// textbook formulas of benchmarks/reference, evaluated here), a Lambert lobe is a circle, a
// delta lobe is its reflectance along the mirror direction.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <sstream>

#include "image_readers.h"
#include "reference/reference.h"
#include "support.h"

using testing::run_cli;

namespace {

struct Row {
    std::string model;
    double theta_i, theta_o, f, f_cos;
    bool has_f;
};

std::vector<Row> parse(const std::string& csv) {
    std::vector<Row> rows;
    std::istringstream in(csv);
    std::string line;
    bool header = false;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (!header) {
            header = true;
            REQUIRE(line == "model,theta_i_deg,theta_o_deg,f,f_cos_theta_i");
            continue;
        }
        const size_t close = line.find('"', 1);
        Row r;
        r.model = line.substr(1, close - 1);
        std::istringstream fields(line.substr(close + 2));
        std::string f[4];
        for (auto& x : f) std::getline(fields, x, ',');
        r.theta_i = std::stod(f[0]);
        r.theta_o = std::stod(f[1]);
        r.has_f = !f[2].empty();
        r.f = r.has_f ? std::stod(f[2]) : 0.0;
        r.f_cos = std::stod(f[3]);
        rows.push_back(r);
    }
    return rows;
}

}  // namespace

TEST_CASE("lobe: a Lambert lobe is a circle of radius rho/pi cos(theta_i)", "[cli][lobe]") {
    const auto r = run_cli("lobe --model lambert:rho=0.8 --theta-i 0,30,75 --resolution 37 --data -");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto rows = parse(r.out);
    REQUIRE(rows.size() == 3 * 37);
    for (const Row& row : rows) {
        const double expect = 0.8 / M_PI * std::cos(row.theta_i * M_PI / 180);
        if (std::fabs(row.theta_o) >= 90.0) continue;  // the horizon itself holds no direction
        CHECK(std::fabs(row.f_cos - expect) <= 1e-12 * expect);
    }
}

TEST_CASE("lobe: the data are GGX's textbook values at those angles", "[cli][lobe]") {
    const auto r = run_cli("lobe --model ggx:alpha_x=0.2,alpha_y=0.5 --theta-i 60 --phi-i 30 --resolution 61 --data -");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto rows = parse(r.out);
    REQUIRE(rows.size() == 61);
    const double phi = 30 * M_PI / 180;
    // The incident direction sits at theta_i on the far side of the plane of azimuth 30 degrees;
    // a positive theta_o lies on the mirror side.
    const ref::Dir wi = ref::dir(60 * M_PI / 180, phi + M_PI);
    double peak = 0;
    for (const Row& row : rows) {
        if (std::fabs(row.theta_o) >= 90.0) continue;
        const double t = row.theta_o * M_PI / 180;
        const ref::Dir wo = ref::dir(std::fabs(t), t >= 0 ? phi : phi + M_PI);
        const double expect = double(ref::ggx_f(wo, wi, 0.2, 0.5, true));
        INFO("theta_o " << row.theta_o);
        CHECK(std::fabs(row.f - expect) <= 1e-10 * std::max(1.0, expect));
        CHECK(std::fabs(row.f_cos - expect * 0.5) <= 1e-10 * std::max(1.0, expect));
        if (row.f > peak) peak = row.f;
    }
    CHECK(peak > 0.5);  // a real lobe, not zeros
}

TEST_CASE("lobe: a delta lobe is its reflectance along the mirror direction", "[cli][lobe]") {
    const auto r = run_cli("lobe --model mirror --fresnel dielectric:eta=1.5 --theta-i 45 --data -");
    REQUIRE(r.status == 0);
    const auto rows = parse(r.out);
    REQUIRE(rows.size() == 1);
    CHECK_FALSE(rows[0].has_f);
    CHECK(rows[0].theta_o == 45.0);
    // Fresnel at 45 degrees for eta = 1.5, unpolarised, written out here.
    const double c = std::cos(M_PI / 4), s = std::sqrt(1.5 * 1.5 - 1 + c * c);
    const double rs = std::pow((c - s) / (c + s), 2), rp = std::pow((2.25 * c - s) / (2.25 * c + s), 2);
    CHECK(std::fabs(rows[0].f_cos - 0.5 * (rs + rp)) <= 1e-12);
}

TEST_CASE("lobe: pictures are written, bad input refused with nothing written", "[cli][lobe]") {
    const std::string png = "/tmp/brdfbake-lobe-" + std::to_string(::getpid()) + ".png";
    REQUIRE(run_cli("lobe --model ggx:alpha=0.3 --model beckmann:alpha=0.3 --model phong:n=20 --theta-i 60 --log -o " +
                    png).status == 0);
    CHECK(testing::png_colours(png) > 16);  // a readable PNG with its curves, not a blank picture
    std::remove(png.c_str());
    // The 3D view: a rough lobe's wireframe and a delta lobe's arrow.
    REQUIRE(run_cli("lobe --model ggx:alpha_x=0.1,alpha_y=0.5 --model mirror --theta-i 45 --view 3d -o " + png).status == 0);
    CHECK(testing::png_colours(png) > 16);
    std::remove(png.c_str());
    for (const std::string args : {"--theta-i 95", "--theta-i -1", "--resolution 2", "--phi-i nan", "--view sideways",
                                   "--view 3d --data /tmp/brdfbake-lobe-3d.csv"}) {
        const auto bad = run_cli("lobe --model ggx:alpha=0.3 " + args + " -o " + png);
        INFO(args);
        CHECK(bad.status == 2);
        CHECK(testing::count_lines(bad.err) == 1);
        CHECK(::access(png.c_str(), F_OK) != 0);
    }
}

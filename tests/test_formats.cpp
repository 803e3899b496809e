// Table formats read back by independent readers: 16-bit PNG through libpng, .npy through numpy
// (/usr/bin/python3), EXR through OpenEXR's generic RGBA reader (Imf::RgbaInputFile) for every
// table kind. Each value must come back within half a unit in the last place of the format.
#include <catch2/catch.hpp>

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <nlohmann/json.hpp>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "brdfbake/lut.h"
#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"
#include "image_readers.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

using testing::Png;
using testing::read_png;

namespace {

std::string tmp_path(const std::string& name) { return "/tmp/brdfbake-formats-" + std::to_string(::getpid()) + "-" + name; }

/// A table of `channels` value channels over a w x h (x d) grid with values spread over [0, 1]
/// (and exactly 0 and 1 at the corners) that no rounding rule would produce by accident.
Table synthetic(int channels, int w, int h, int d = 1) {
    Table t;
    t.kind = "albedo";
    t.quantity = "test values";
    t.x = testing::identity_axis("mu", "mu = u", 0, 1, w);
    t.y = testing::identity_axis("alpha", "alpha = v", 0, 1, h);
    t.z = testing::identity_axis("eta", "eta = w", 1, 2, d);
    const size_t n = size_t(w) * h * d;
    const char* names[] = {"E", "T", "R_inside", "T_inside"};
    for (int c = 0; c < channels; ++c) {
        t.channels.push_back(names[c]);
        std::vector<double> v(n);
        for (size_t k = 0; k < n; ++k) v[k] = std::fmod(0.1234567891 * (k + 1) * (c + 1) + 0.3 * c, 1.0);
        v[0] = c == 0 ? 0.0 : 1.0;
        v[n - 1] = c == 0 ? 1.0 : 0.0;
        t.values.push_back(v);
    }
    t.error.assign(n, 1e-6);
    return t;
}

bool have_numpy() { return std::system("/usr/bin/python3 -c 'import numpy' >/dev/null 2>&1") == 0; }

/// The README's RGBA view of n value channels (section "Table formats", .exr): which value channel R,
/// G, B and A hold (-1: none). One channel in R, G and B; two in R, G with B = 0; three in R,
/// G, B; four in R, G, B, A.
const int kReadmeRgbaView[4][4] = {{0, 0, 0, -1}, {0, 1, -1, -1}, {0, 1, 2, -1}, {0, 1, 2, 3}};

}  // namespace

TEST_CASE("16-bit PNG round-trips through libpng within half a unit of 1/65535, R, G, B as documented",
          "[formats][quick]") {
    for (int channels : {1, 2, 3, 4}) {
        INFO(channels << " value channels");
        const Table t = synthetic(channels, 7, 5);
        const std::string path = tmp_path("t.png");
        write_table(t, path);
        const Png p = read_png(path);
        std::remove(path.c_str());
        REQUIRE(p.width == 7);
        REQUIRE(p.height == 5);
        REQUIRE(p.bit_depth == 16);
        REQUIRE(p.channels == (channels == 4 ? 4 : 3));
        double worst = 0;
        for (size_t k = 0; k < 35; ++k)
            for (int s = 0; s < p.channels; ++s) {
                const double got = p.samples[k * p.channels + s] / 65535.0;
                const int c = kReadmeRgbaView[channels - 1][s];
                const double want = c < 0 ? 0.0 : t.values[size_t(c)][k];
                worst = std::max(worst, std::fabs(got - want));
            }
        CHECK(worst <= 0.5 / 65535 + 1e-12);
        CHECK(p.text.at("brdfbake:kind") == "albedo");
        CHECK(p.text.count("brdfbake:rgba_view") == 1);
        CHECK(p.text.count("brdfbake:png_encoding") == 1);
    }
}

TEST_CASE("PNG: values outside [0, 1] beyond their error are refused and nothing is written, within it, clamped",
          "[formats][quick]") {
    Table t = synthetic(1, 3, 2);
    t.values[0][2] = 1.0 + 5e-7;  // within its error (1e-6): stored as 65535
    t.values[0][3] = -5e-7;       // within its error: stored as 0
    const std::string path = tmp_path("clamp.png");
    write_table(t, path);
    const Png p = read_png(path);
    std::remove(path.c_str());
    CHECK(p.samples[2 * 3] == 65535u);
    CHECK(p.samples[3 * 3] == 0u);
    t.values[0][4] = 1.5;
    CHECK_THROWS_WITH(write_table(t, path), Catch::Contains("16-bit PNG holds values in [0, 1]"));
    CHECK(::access(path.c_str(), F_OK) != 0);
}

TEST_CASE(".npy round-trips through numpy exactly (float64), shape and sidecar as documented", "[formats][quick]") {
    // A missing test dependency fails the test (it does not skip it silently).
    INFO("numpy is not installed for /usr/bin/python3 (scripts/setup.sh installs python3-numpy)");
    REQUIRE(have_numpy());
    for (int depth : {1, 3}) {
        INFO("depth " << depth);
        const Table t = synthetic(2, 4, 3, depth);
        const std::string path = tmp_path("t.npy");
        write_table(t, path);
        // numpy reads the file; every value printed with 17 significant digits (exact for float64).
        const std::string out = tmp_path("numpy.txt");
        const std::string cmd = "/usr/bin/python3 -c \"import numpy as np; a = np.load('" + path +
                                "'); print(a.dtype.str, a.shape, a.flags['C_CONTIGUOUS']); "
                                "print(' '.join(repr(float(v)) for v in a.ravel()))\" > " + out;
        REQUIRE(std::system(cmd.c_str()) == 0);
        std::ifstream in(out);
        std::string dtype, line;
        std::getline(in, line);
        const std::string shape = depth == 1 ? "(3, 4, 3)" : "(3, 3, 4, 3)";
        CHECK(line == "<f8 " + shape + " True");
        std::vector<double> values;
        double v;
        while (in >> v) values.push_back(v);
        const size_t n = size_t(4) * 3 * depth;
        REQUIRE(values.size() == n * 3);
        for (size_t k = 0; k < n; ++k) {
            CHECK(values[k * 3] == t.values[0][k]);
            CHECK(values[k * 3 + 1] == t.values[1][k]);
            CHECK(values[k * 3 + 2] == t.error[k]);
        }
        const nlohmann::json j = nlohmann::json::parse(testing::slurp(path + ".json"));
        CHECK(j["channels"] == std::vector<std::string>{"E", "T", "error"});
        CHECK(j["axes"].back()["name"] == "mu");
        CHECK(j["axes"].back()["coordinate"].get<std::vector<double>>() == t.x.coordinate);
        CHECK(j["description"]["kind"] == "albedo");
        std::remove(path.c_str());
        std::remove((path + ".json").c_str());
        std::remove(out.c_str());
    }
}

TEST_CASE("EXR through Imf::RgbaInputFile: every table kind shows non-zero, documented R, G, B, the header keeps "
          "every brdfbake attribute and the error channel",
          "[formats][device]") {
    for (const TableKind* k : table_kinds()) {
        LutRequest r;
        r.kind = k->name;
        r.model = "ggx";
        r.width = 3;
        r.height = k->one_dimensional ? 1 : 2;
        r.depth = 2;
        r.samples = 1024;
        if (!k->example_fresnel.empty()) r.fresnel = k->example_fresnel;
        if (!k->required_model.empty()) r.model = k->required_model;  // a kind of one model only (sheen)
        INFO(k->name);
        const Table t = compute_lut(testing::engine(), r);
        if (t.channels.size() > 4) {  // no RGBA view (ltc's 8 channels): read by name in tests/test_ltc.cpp
            CHECK(rgba_view(t).empty());
            continue;
        }
        for (bool half : {false, true}) {
            const std::string path = tmp_path(k->name + ".exr");
            write_table(t, path, half);
            Imf::RgbaInputFile file(path.c_str());
            const Imath::Box2i dw = file.dataWindow();
            const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
            REQUIRE(w == t.width());
            REQUIRE(h == t.image_height());
            Imf::Array2D<Imf::Rgba> px(h, w);
            file.setFrameBuffer(&px[0][0] - dw.min.x - dw.min.y * w, 1, size_t(w));
            file.readPixels(dw.min.y, dw.max.y);
            REQUIRE(t.channels.size() >= 1);
            REQUIRE(t.channels.size() <= 4);
            const int* view = kReadmeRgbaView[t.channels.size() - 1];
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t i = size_t(y) * w + x;
                    const Imf::Rgba& p = px[y][x];
                    const float rgba[4] = {float(p.r), float(p.g), float(p.b), float(p.a)};
                    for (int s = 0; s < 4; ++s) {
                        if (s == 3 && view[3] < 0) {
                            CHECK(rgba[3] == 1.0f);  // no A channel: the reader's default
                            continue;
                        }
                        const double want = view[size_t(s)] < 0 ? 0.0 : t.values[size_t(view[size_t(s)])][i];
                        // Half a unit in the last place of half (11 significant bits), which the
                        // RGBA reader converts every channel to, and never finer than half's
                        // subnormal spacing 2^-24 (a gen-schlick s of 1e-8 reads back as 0).
                        const double ulp = want == 0 ? 0 : std::max(std::ldexp(1.0, std::ilogb(want) - 10), 0x1p-24);
                        CHECK(std::fabs(rgba[s] - want) <= 0.5 * ulp * (half ? 1.0 : 1.0 + 1e-3) + 1e-30);
                    }
                    if (view[0] >= 0) CHECK(rgba[0] != 0.0f);
                }
            // The header: every description key as a brdfbake: attribute, and the error channel.
            const Imf::Header& header = file.header();
            for (const auto& kv : table_description(t)) {
                const auto* a = header.findTypedAttribute<Imf::StringAttribute>(("brdfbake:" + kv.first).c_str());
                CHECK(a != nullptr);
            }
            CHECK(header.channels().findChannel("error") != nullptr);
            // No value channel hides under an RGBA name that the view leaves empty (dfg's A and B
            // are under dfg.A and dfg.B).
            if (view[2] < 0) CHECK(header.channels().findChannel("B") == nullptr);
            if (view[3] < 0) CHECK(header.channels().findChannel("A") == nullptr);
            std::remove(path.c_str());
        }
    }
}

// `brdfbake show`: statistics that agree with an independent read of the file (OpenEXR directly),
// conversions between every table format that come back within the format's precision, and
// bad input refused before anything is written.
#include <catch2/catch.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "image_readers.h"
#include "support.h"

using testing::run_cli;

namespace {

std::string scratch(const std::string& name) { return "/tmp/brdfbake-show-" + std::to_string(::getpid()) + "-" + name; }

/// One channel of an EXR file, read with OpenEXR and nothing of brdfbake's.
std::vector<float> exr_channel(const std::string& path, const std::string& name) {
    int w = 0, h = 0;
    return testing::exr_channel(path, name, w, h);
}

/// The float64 data of a .npy written by brdfbake ('<f8', C order), read from its header's length.
std::vector<double> npy_data(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.compare(0, 6, "\x93NUMPY") == 0);
    const size_t len = size_t(static_cast<unsigned char>(bytes[8])) | size_t(static_cast<unsigned char>(bytes[9])) << 8;
    std::vector<double> v((bytes.size() - 10 - len) / 8);
    std::memcpy(v.data(), bytes.data() + 10 + len, v.size() * 8);
    return v;
}

}  // namespace

TEST_CASE("show: statistics agree with OpenEXR's read of the file", "[cli][show]") {
    const std::string exr = scratch("dfg.exr");
    REQUIRE(run_cli("lut dfg --model ggx --size 8x6 --samples 1024 --no-preview -o " + exr).status == 0);
    const auto r = run_cli("show " + exr + " --format json");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j.at("kind") == "dfg");
    REQUIRE(j.at("channels").size() == 2);
    for (const auto& c : j.at("channels")) {
        const std::vector<float> v = exr_channel(exr, "dfg." + c.at("name").get<std::string>());
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        CHECK(c.at("min").get<double>() == double(*lo));
        CHECK(c.at("max").get<double>() == double(*hi));
    }
    const std::vector<float> e = exr_channel(exr, "error");
    CHECK(j.at("max_error").get<double>() == double(*std::max_element(e.begin(), e.end())));
    CHECK(j.at("axes").at(0).at("name") == "mu");
    std::remove(exr.c_str());
}

TEST_CASE("show -o converts between the table formats within their precision", "[cli][show]") {
    const std::string exr = scratch("d.exr"), npy = scratch("d.npy"), csv = scratch("d.csv"), back = scratch("back.exr");
    REQUIRE(run_cli("lut dielectric --model ggx --size 4x3x2 --samples 1024 --no-preview -o " + exr).status == 0);
    REQUIRE(run_cli("show " + exr + " -o " + npy).status == 0);
    REQUIRE(run_cli("show " + npy + " -o " + csv).status == 0);
    REQUIRE(run_cli("show " + csv + " -o " + back).status == 0);
    // EXR -> npy is exact (float32 in float64); npy -> csv keeps 9 significant digits, which
    // float32 values survive exactly; csv -> EXR rounds them back to the same float32.
    const auto info = nlohmann::json::parse(run_cli("show " + exr + " --format json").out);
    std::vector<std::string> channels;
    for (const auto& c : info.at("channels")) channels.push_back(c.at("name"));
    const std::vector<double> data = npy_data(npy);
    const size_t n_channels = channels.size() + 1, texels = 4 * 3 * 2;
    REQUIRE(data.size() == texels * n_channels);
    for (size_t c = 0; c < channels.size(); ++c) {
        INFO(channels[c]);
        const std::vector<float> a = exr_channel(exr, channels[c]), b = exr_channel(back, channels[c]);
        REQUIRE(a.size() == texels);
        for (size_t k = 0; k < texels; ++k) {
            CHECK(data[k * n_channels + c] == double(a[k]));
            CHECK(b[k] == a[k]);
        }
    }
    for (const auto& p : {exr, npy, npy + ".json", csv, back}) std::remove(p.c_str());
}

TEST_CASE("show: a slice or file it cannot show is refused with nothing written", "[cli][show]") {
    const std::string exr = scratch("s.exr"), png = scratch("s.png");
    REQUIRE(run_cli("lut dielectric --model ggx --size 4x3x2 --samples 1024 --no-preview -o " + exr).status == 0);
    auto r = run_cli("show " + exr + " --slice 2 --plot " + png);
    CHECK(r.status == 2);
    CHECK(r.err.find("0 to 1") != std::string::npos);
    CHECK(::access(png.c_str(), F_OK) != 0);
    r = run_cli("show " + exr + " --slice 1 --plot " + png);
    REQUIRE(r.status == 0);
    CHECK(testing::png_colours(png) > 16);  // a readable heatmap, not a blank picture
    std::remove(png.c_str());
    // Curves across the eta axis of the 3D table; refused on a bad axis, or without --curves.
    r = run_cli("show " + exr + " --curves 0.2,0.8 --along z --at 0.5 --plot " + png);
    REQUIRE(r.status == 0);
    CHECK(testing::png_colours(png) > 16);
    std::remove(png.c_str());
    for (const std::string args : {" --curves 0.5 --along y", " --along z"}) {
        r = run_cli("show " + exr + args + " --plot " + png);
        INFO(args);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(::access(png.c_str(), F_OK) != 0);
    }
    r = run_cli("show /nonexistent.exr");
    CHECK(r.status == 2);
    CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
    for (const auto& p : {exr, png}) std::remove(p.c_str());
}

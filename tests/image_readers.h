// Readers of the project's image outputs that use only the libraries' own APIs (libpng,
// OpenEXR), nothing of brdfbake's: the independent side of the format tests.
#pragma once

#include <catch2/catch.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <png.h>

#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace testing {

struct Png {
    int width = 0, height = 0, channels = 0, bit_depth = 0;
    std::vector<unsigned> samples;  // 16-bit samples, row-major, channels interleaved
    std::map<std::string, std::string> text;
};

/// Reads a PNG with libpng's own reader: `transforms` are libpng's PNG_TRANSFORM_* flags.
inline Png read_png_with(const std::string& path, int transforms) {
    Png p;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    REQUIRE(f != nullptr);
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    REQUIRE(setjmp(png_jmpbuf(png)) == 0);
    png_init_io(png, f);
    png_read_png(png, info, transforms, nullptr);
    p.width = int(png_get_image_width(png, info));
    p.height = int(png_get_image_height(png, info));
    p.channels = png_get_channels(png, info);
    p.bit_depth = png_get_bit_depth(png, info);
    png_bytepp rows = png_get_rows(png, info);
    const int bytes = p.bit_depth == 16 ? 2 : 1;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width * p.channels; ++x)
            p.samples.push_back(bytes == 2 ? unsigned(rows[y][2 * x]) << 8 | rows[y][2 * x + 1] : rows[y][x]);
    png_textp text = nullptr;
    const int n = png_get_text(png, info, &text, nullptr);
    for (int i = 0; i < n; ++i) p.text[text[i].key] = std::string(text[i].text, text[i].text_length);
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    return p;
}

/// Reads a 16-bit PNG (the tables brdfbake writes) with no transformations.
inline Png read_png(const std::string& path) {
    Png p = read_png_with(path, PNG_TRANSFORM_IDENTITY);
    REQUIRE(p.bit_depth == 16);
    return p;
}

/// An 8-bit RGB(A) picture (MathGL's): samples 0..255, row-major from the top, channels interleaved.
inline Png read_png8(const std::string& path) { return read_png_with(path, PNG_TRANSFORM_STRIP_16 | PNG_TRANSFORM_EXPAND); }

/// The number of distinct colours of a PNG read with libpng (8 bits a sample): a blank picture
/// has one or two, a figure with curves or a heatmap many.
inline size_t png_colours(const std::string& path) {
    const Png p = read_png8(path);
    std::set<std::vector<unsigned>> colours;
    for (size_t k = 0; k + size_t(p.channels) <= p.samples.size(); k += size_t(p.channels))
        colours.insert(std::vector<unsigned>(p.samples.begin() + long(k), p.samples.begin() + long(k + size_t(p.channels))));
    return colours.size();
}

/// One channel of an EXR file as float, with OpenEXR's reader; sets the image's width and height.
inline std::vector<float> exr_channel(const std::string& path, const std::string& name, int& w, int& h) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    w = dw.max.x - dw.min.x + 1;
    h = dw.max.y - dw.min.y + 1;
    REQUIRE(file.header().channels().findChannel(name.c_str()) != nullptr);
    std::vector<float> v(size_t(w) * h);
    Imf::FrameBuffer fb;
    char* base = reinterpret_cast<char*>(v.data()) - (size_t(dw.min.y) * w + dw.min.x) * sizeof(float);
    fb.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), size_t(w) * sizeof(float)));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return v;
}

}  // namespace testing

// Texture images for texture-driven ranges (texture_image.h): PNG through libpng, data URIs
// through Boost's base64 iterators.
#include "scene/texture_image.h"

#include <png.h>
// libjpeg's header needs FILE and size_t declared before it.
#include <cstdio>
#include <jpeglib.h>

#include <boost/archive/iterators/binary_from_base64.hpp>
#include <boost/archive/iterators/transform_width.hpp>

#include <algorithm>
#include <csetjmp>
#include <cstring>
#include <vector>

#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "io/png_memory.h"

namespace brdfbake {

std::string image_format(const std::string& b) {
    if (b.size() >= 8 && std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "png";
    if (b.size() >= 3 && std::memcmp(b.data(), "\xff\xd8\xff", 3) == 0) return "jpeg";
    if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 && std::memcmp(b.data() + 8, "WEBP", 4) == 0)
        return "webp";
    if (b.size() >= 12 && std::memcmp(b.data(), "\xabKTX 20\xbb", 8) == 0) return "ktx2";
    return "";
}

namespace {

}  // namespace

ChannelRanges png_channel_ranges(const std::string& bytes, const std::string& what) {
    // Decoded a row at a time: the memory is one row whatever the image's size, which the IHDR
    // gives before a pixel is decoded (a 1 MB file may hold a 20000 x 20000 image).
    std::string message;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &message, png_error_to_message, png_warning_ignored);
    if (!png) throw Error(what + ": cannot start the PNG reader");
    png_infop info = png_create_info_struct(png);
    PngMemorySource reader{&bytes};
    std::vector<png_byte> row;
    ChannelRanges out;
    std::array<unsigned, 4> lo{~0u, ~0u, ~0u, ~0u}, hi{0, 0, 0, 0};
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw Error(what + " is not a readable PNG: " + message);
    }
    png_set_read_fn(png, &reader, read_png_from_memory);
    png_read_info(png, info);
    const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    const bool interlaced = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE;
    // Raw sample values: no gamma or colour-space handling, palette and low bit depths expanded.
    png_set_palette_to_rgb(png);
    png_set_expand_gray_1_2_4_to_8(png);
    png_set_tRNS_to_alpha(png);
    png_set_gray_to_rgb(png);
    const int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    const int depth = png_get_bit_depth(png, info), channels = png_get_channels(png, info);
    const std::size_t row_bytes = png_get_rowbytes(png, info);
    try {
        check_memory(double(row_bytes), what + " (one decoded row of " + std::to_string(w) + "x" + std::to_string(h) + ")");
    } catch (const Error&) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw;
    }
    row.resize(row_bytes);
    // An interlaced image comes in passes, each row once per pass holding only that pass's
    // pixels (libpng's "sparkle" rows): the others are left as they were and skipped here.
    for (int pass = 0; pass < passes; ++pass)
        for (png_uint_32 y = 0; y < h; ++y) {
            png_read_row(png, row.data(), nullptr);
            if (interlaced && !PNG_ROW_IN_INTERLACE_PASS(y, pass)) continue;
            for (png_uint_32 x = 0; x < w; ++x) {
                if (interlaced && !PNG_COL_IN_INTERLACE_PASS(x, pass)) continue;
                for (int c = 0; c < channels; ++c) {
                    const std::size_t i = std::size_t(x) * std::size_t(channels) + std::size_t(c);
                    const unsigned v = depth == 16 ? (unsigned(row[2 * i]) << 8) | row[2 * i + 1] : row[i];
                    lo[size_t(c)] = std::min(lo[size_t(c)], v);
                    hi[size_t(c)] = std::max(hi[size_t(c)], v);
                }
            }
        }
    png_destroy_read_struct(&png, &info, nullptr);

    const double max_value = depth == 16 ? 65535.0 : 255.0;
    out.width = int(w);
    out.height = int(h);
    for (int c = 0; c < 4; ++c) {
        if (c < channels) {
            out.lo[size_t(c)] = lo[size_t(c)] / max_value;
            out.hi[size_t(c)] = hi[size_t(c)] / max_value;
        } else {
            out.lo[size_t(c)] = out.hi[size_t(c)] = 1.0;  // no alpha channel: opaque
        }
    }
    return out;
}

namespace {

struct JpegFailure {
    jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

void on_jpeg_error(j_common_ptr info) {
    JpegFailure* f = reinterpret_cast<JpegFailure*>(info->err);
    (*info->err->format_message)(info, f->message);
    std::longjmp(f->jump, 1);
}

void on_jpeg_message(j_common_ptr, int) {}  // warnings of a damaged but decodable file: the values decide

}  // namespace

ChannelRanges jpeg_channel_ranges(const std::string& bytes, const std::string& what) {
    // The decoded values, as a renderer samples them: JPEG is lossy, so the range is that of the
    // image the renderer sees, compression noise included. Grey images read as R = G = B.
    jpeg_decompress_struct info {};
    JpegFailure failure {};
    info.err = jpeg_std_error(&failure.manager);
    failure.manager.error_exit = on_jpeg_error;
    failure.manager.emit_message = on_jpeg_message;
    std::vector<unsigned char> row;
    ChannelRanges out;
    std::array<unsigned, 4> lo{255, 255, 255, 255}, hi{0, 0, 0, 0};
    if (setjmp(failure.jump)) {
        jpeg_destroy_decompress(&info);
        throw Error(what + " is not a readable JPEG: " + failure.message);
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&info, TRUE);
    info.out_color_space = JCS_RGB;  // YCbCr and grey both come out as RGB samples
    // A progressive JPEG keeps every coefficient of the image until its last scan (2 bytes per
    // sample): judged from the header's dimensions before decoding. A baseline one needs a row.
    if (jpeg_has_multiple_scans(&info)) {
        try {
            check_memory(2.0 * info.image_width * info.image_height * info.num_components,
                         what + " (a progressive " + std::to_string(info.image_width) + "x" +
                             std::to_string(info.image_height) + " JPEG)");
        } catch (const Error&) {
            jpeg_destroy_decompress(&info);
            throw;
        }
    }
    jpeg_start_decompress(&info);
    const unsigned w = info.output_width, h = info.output_height, channels = unsigned(info.output_components);
    // One row at a time: the memory is a row, whatever the image's size (only its pixel count is read).
    row.resize(std::size_t(w) * channels);
    while (info.output_scanline < h) {
        unsigned char* rows[1] = {row.data()};
        jpeg_read_scanlines(&info, rows, 1);
        for (std::size_t p = 0; p < w; ++p)
            for (unsigned c = 0; c < channels && c < 3; ++c) {
                const unsigned v = row[p * channels + c];
                lo[c] = std::min(lo[c], v);
                hi[c] = std::max(hi[c], v);
            }
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    out.width = int(w);
    out.height = int(h);
    for (size_t c = 0; c < 3; ++c) {
        out.lo[c] = lo[c] / 255.0;
        out.hi[c] = hi[c] / 255.0;
    }
    out.lo[3] = out.hi[3] = 1.0;  // JPEG has no alpha: opaque
    return out;
}

std::optional<std::string> base64_decode(const std::string& text) {
    using namespace boost::archive::iterators;
    using Decoder = transform_width<binary_from_base64<std::string::const_iterator>, 8, 6>;
    std::string s;
    for (char c : text)
        if (!std::isspace(static_cast<unsigned char>(c))) s += c;
    // Whole groups of four; the '=' padding decodes as zero bits that are dropped again.
    if (s.empty() || s.size() % 4 != 0) return std::nullopt;
    std::size_t pad = 0;
    while (pad < s.size() && s[s.size() - 1 - pad] == '=') ++pad;
    if (pad > 2) return std::nullopt;
    for (std::size_t i = 0; i < pad; ++i) s[s.size() - 1 - i] = 'A';
    try {
        std::string out(Decoder(s.begin()), Decoder(s.end()));
        out.resize(s.size() / 4 * 3 - pad);
        return out;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

std::string percent_decode(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace brdfbake

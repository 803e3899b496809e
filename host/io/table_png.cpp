// 16-bit PNG tables (libpng): the RGB(A) view of the value channels (rgba_view in
// brdfbake/table.h), linear, each value v stored as round(v * 65535), as the real-time viewers'
// LUTs (the glTF sample viewer's lut_ggx.png) are. The description goes into tEXt chunks. No
// colour-space chunk (gAMA, sRGB, iCCP, cHRM): a browser converts the samples of a PNG that
// declares a gamma other than its display's (a gAMA 1.0 table uploaded by WebGL in Chromium
// turned texels 211 into 234 and 5 into 39); one without any is uploaded as stored.
#include <png.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/table.h"

namespace brdfbake {
namespace {

constexpr double kPngMax = 65535.0;

/// The 16-bit sample of value v of a texel whose error estimate is `error`: [0, 1] maps to
/// [0, 65535]; a value outside [0, 1] by no more than its error is clamped (the clamp moves it
/// less than its uncertainty), one further out has no PNG sample (Error).
png_uint_16 quantise(double v, double error, const Table& t, size_t channel, size_t texel) {
    if (v < -error || v > 1.0 + error) {
        char b[256];
        std::snprintf(b, sizeof b,
                      "a 16-bit PNG holds values in [0, 1]: channel %s of the %s table is %.6g at texel (%zu, %zu); "
                      "write .exr or .npy instead",
                      t.channels[channel].c_str(), t.kind.c_str(), v, texel % size_t(t.width()), texel / size_t(t.width()));
        throw Error(b);
    }
    const double c = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    return png_uint_16(std::lround(c * kPngMax));
}

void on_png_error(png_structp png, png_const_charp message) {
    const int err = errno;  // libpng's "Write Error" of a failed fwrite: the reason is in errno
    auto* text = static_cast<std::string*>(png_get_error_ptr(png));
    *text = message;
    if (err) *text += std::string(" (") + std::strerror(err) + ")";
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

/// Encodes the rows into `file`; false with libpng's message on failure (libpng's own write
/// function reports a failed fwrite through png_error, which lands here). Kept apart so that no
/// local of the caller lives across libpng's longjmp.
bool encode(std::FILE* file, png_uint_32 w, png_uint_32 h, int depth, int color_type, png_bytep* rows, png_text* text,
            int n_text, double gamma, std::string* message) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, message, on_png_error, on_png_warning);
    if (!png) {
        *message = "libpng could not start";
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        if (!info) *message = "libpng could not start";
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, w, h, depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (gamma > 0.0) png_set_gAMA(png, info, gamma);
    if (n_text > 0) png_set_text(png, info, text, n_text);
    png_set_rows(png, info, rows);
    png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

void check_png_table(const Table& t) {
    if (t.channels.size() > 4)
        throw Error("a PNG holds at most four channels; the " + t.kind + " table has " +
                    std::to_string(t.channels.size()) + ": write .exr or .npy");
}

void write_png16(const Table& t, const std::string& path) {
    check_png_table(t);
    const std::vector<int> view = rgba_view(t);
    const int w = t.width(), h = t.image_height();
    const int samples = view[3] >= 0 ? 4 : 3;
    // Quantise everything first, so that a refused value leaves no file behind.
    std::vector<png_byte> image(size_t(w) * h * samples * 2);
    for (size_t k = 0; k < size_t(w) * h; ++k)
        for (int s = 0; s < samples; ++s) {
            const png_uint_16 q = view[s] < 0 ? 0 : quantise(t.values[size_t(view[s])][k], t.error[k], t, size_t(view[s]), k);
            image[(k * samples + s) * 2] = png_byte(q >> 8);  // PNG samples are big-endian
            image[(k * samples + s) * 2 + 1] = png_byte(q & 0xff);
        }
    std::vector<std::pair<std::string, std::string>> text = table_description(t);
    text.emplace_back("png_encoding", "16-bit unsigned samples, linear data (no gAMA, sRGB or iCCP chunk, no transfer "
                                      "function): value = sample / 65535, "
                                      "sample = round(value * 65535); values outside [0, 1] by at most their error "
                                      "estimate were clamped; the error channel is not stored (see max_error)");
    write_png_file(path, w, h, 16, samples, image, text);
}

void write_png_file(const std::string& path, int w, int h, int depth, int channels, const std::vector<unsigned char>& bytes,
                    const std::vector<std::pair<std::string, std::string>>& text, double gamma) {
    const int color_type = channels == 4   ? PNG_COLOR_TYPE_RGB_ALPHA
                           : channels == 3 ? PNG_COLOR_TYPE_RGB
                           : channels == 1 ? PNG_COLOR_TYPE_GRAY
                                           : -1;
    const size_t row_bytes = size_t(w) * size_t(channels) * size_t(depth / 8);
    if (color_type < 0 || (depth != 8 && depth != 16) || bytes.size() != row_bytes * size_t(h))
        throw Error("internal error: a PNG of " + std::to_string(channels) + " channels at " + std::to_string(depth) +
                    " bits does not match its " + std::to_string(bytes.size()) + " bytes");
    std::vector<std::string> keys;
    for (const auto& kv : text) keys.push_back("brdfbake:" + kv.first);
    std::vector<png_text> chunks(text.size());
    for (size_t i = 0; i < text.size(); ++i) {
        chunks[i].compression = PNG_TEXT_COMPRESSION_NONE;
        chunks[i].key = const_cast<char*>(keys[i].c_str());
        chunks[i].text = const_cast<char*>(text[i].second.c_str());
        chunks[i].text_length = text[i].second.size();
    }
    std::vector<png_bytep> rows(static_cast<size_t>(h));
    for (int y = 0; y < h; ++y) rows[size_t(y)] = const_cast<png_bytep>(bytes.data()) + size_t(y) * row_bytes;
    const OutputFile out = prepare_output(path);
    std::FILE* file = std::fopen(out.temporary.c_str(), "wb");
    if (!file) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    std::string message;
    errno = 0;
    const bool encoded = encode(file, png_uint_32(w), png_uint_32(h), depth, color_type, rows.data(), chunks.data(),
                                int(chunks.size()), gamma, &message);
    errno = 0;
    const bool closed = std::fclose(file) == 0;  // the buffer's last write: a full disk may show only here
    if (!encoded || !closed) {
        const std::string why = encoded ? (errno ? std::strerror(errno) : "write failed") : message;
        std::remove(out.temporary.c_str());
        throw Error("cannot write '" + path + "': " + why);
    }
    commit_output(out, path);
}

}  // namespace brdfbake

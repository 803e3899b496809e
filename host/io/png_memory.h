// Reading a PNG held in memory with libpng: the read callback and the error callbacks that the
// table reader (io/table_read.cpp) and the glTF texture reader (scene/texture_image.cpp) share.
// libpng reports errors by calling the error function, which must not return: it records the
// message in the std::string given as the error pointer and longjmps back to the caller's setjmp.
#pragma once

#include <png.h>

#include <cstring>
#include <string>

namespace brdfbake {

/// The bytes a PNG is read from and how far libpng has read.
struct PngMemorySource {
    const std::string* bytes;
    std::size_t pos = 0;
};

/// png_set_read_fn's callback over a PngMemorySource; a read past the end is libpng's error.
inline void read_png_from_memory(png_structp png, png_bytep out, png_size_t n) {
    auto* source = static_cast<PngMemorySource*>(png_get_io_ptr(png));
    if (source->pos + n > source->bytes->size()) png_error(png, "the PNG data is cut short");
    std::memcpy(out, source->bytes->data() + source->pos, n);
    source->pos += n;
}

/// The error function: the message into the std::string error pointer, then back to setjmp.
inline void png_error_to_message(png_structp png, png_const_charp message) {
    *static_cast<std::string*>(png_get_error_ptr(png)) = message;
    png_longjmp(png, 1);
}

/// The warning function: warnings (unknown chunks, odd but readable files) are not errors.
inline void png_warning_ignored(png_structp, png_const_charp) {}

}  // namespace brdfbake

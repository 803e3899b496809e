// The texel values of a glTF texture image, for the ranges a material's textures actually hold
// (docs/scenes.md, "Texture-driven ranges"). Only what the ranges need: the raw channel values,
// no colour conversion (metallic-roughness, clearcoat, sheen-roughness, transmission and
// specular textures hold linear data; glTF 2.0 section 3.9).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace brdfbake {

/// Per channel (R, G, B, A) the smallest and largest value of an image, scaled to [0, 1]. A
/// grey image's R, G and B are its grey value; an image without alpha has A = 1.
struct ChannelRanges {
    int width = 0, height = 0;
    std::array<double, 4> lo{}, hi{};
};

/// What the image's bytes are, from their signature: "png", "jpeg", "webp", "ktx2", or "".
std::string image_format(const std::string& bytes);

/// Decodes a PNG held in `bytes` (libpng, 1 to 16 bits, grey, palette, RGB, with or without
/// alpha) and returns its channel ranges. Throws Error naming `what` for a corrupt or too large
/// image (check_memory guards the decoded size).
ChannelRanges png_channel_ranges(const std::string& bytes, const std::string& what);

/// Decodes a baseline or progressive JPEG held in `bytes` (libjpeg) and returns the ranges of its
/// decoded R, G, B values (A = 1). Throws Error naming `what` for a corrupt image.
ChannelRanges jpeg_channel_ranges(const std::string& bytes, const std::string& what);

/// RFC 4648 base64 (the payload of a data: URI), through Boost's base64 iterators; nullopt for
/// text that is not base64.
std::optional<std::string> base64_decode(const std::string& text);

/// RFC 3986 percent-decoding of a URI path ("my%20file.png" -> "my file.png").
std::string percent_decode(const std::string& uri);

}  // namespace brdfbake

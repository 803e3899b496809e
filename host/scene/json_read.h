// JSON as scene files and glTF documents are read: a key given twice in one object is an error
// (RFC 8259 leaves it to the reader; nlohmann-json would keep the last one silently), and a bad
// document is one message naming the file.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>

namespace brdfbake {
namespace scene_json {

/// The bounds of a document (README, "Limits"): how deep arrays and objects nest, and how many
/// values it holds (a number, a string, an array or an object each count one). Together with the
/// file size they bound the memory the parser takes (about 100 bytes a value).
constexpr std::size_t kMaxJsonDepth = 256;
constexpr std::size_t kMaxJsonValues = std::size_t(1) << 22;

/// Parses `text`. Past kMaxJsonDepth or kMaxJsonValues throws Error "<label>: ...", naming the bound. Throws Error "<label>: ..." for invalid JSON, and for a key given twice in one
/// object, naming the key, where it is (materials[2].pbrMetallicRoughness) and the name of the
/// nearest enclosing object that has one (the material). `label` is e.g. "scene 'a.json'".
nlohmann::json parse_strict(const std::string& text, const std::string& label);

}  // namespace scene_json
}  // namespace brdfbake

// The glTF extensions brdfbake knows: those whose effect on the tables is modelled
// (gltf_scene.cpp maps them), those that change no table, and material extensions that would need
// tables brdfbake does not compute. docs/scenes.md lists them.
#pragma once

#include <string>

namespace brdfbake {
namespace gltf_extensions {

/// Whether the extension's effect on the tables is modelled.
bool modelled(const std::string& name);

/// What follows "E is not modelled" in a warning about an extension that is not: why, and for a
/// material's extension (`in_material`) that its other lobes are planned.
std::string unmodelled_text(const std::string& name, bool in_material);

}  // namespace gltf_extensions
}  // namespace brdfbake

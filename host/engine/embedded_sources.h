// Kernel sources and shared BRDF headers, embedded into the binary at build time
// (cmake/embed_sources.cmake generates the definition).
#pragma once

#include <string>
#include <vector>

namespace brdfbake {

/// The text of an embedded file ("kernels/albedo.cl", "brdfbake/brdf/ggx.h"), or nullptr.
const char* embedded_source(const std::string& name);

/// Names of every embedded file.
std::vector<std::string> embedded_source_names();

}  // namespace brdfbake

// FNV-1a, 64 bits (Fowler, Noll and Vo; offset basis 14695981039346656037, prime 1099511628211):
// the one content hash of the program's keys (a texel's random stream, a bake's cache name).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace brdfbake {

struct Fnv1a {
    std::uint64_t h = 1469598103934665603ull;
    Fnv1a& bytes(const void* data, std::size_t n) {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
        return *this;
    }
    /// The bytes of a trivially copyable value, as they lie in memory.
    template <typename T>
    Fnv1a& add(const T& v) {
        return bytes(&v, sizeof v);
    }
    Fnv1a& add(const std::string& s) { return bytes(s.data(), s.size()); }
};

inline std::uint64_t fnv1a(const std::string& s) { return Fnv1a().add(s).h; }

}  // namespace brdfbake

// What the baselines' loops (baseline_impl.h, baseline_plain_impl.h) share: the bit reversal of
// the Hammersley points' radical inverse. Integer arithmetic only, so that every flavour's flags
// (-ffast-math or not) compile it alike.
#pragma once

#include <cstdint>

namespace brdfbake {
namespace baseline {

inline std::uint32_t reverse_bits(std::uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

}  // namespace baseline
}  // namespace brdfbake

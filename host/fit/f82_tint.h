// F82-tint parameters of a Fresnel term in linear sRGB: the f0 and tint that OpenPBR's metal and the
// Adobe Standard Material take, derived from a measured (or any) spectral Fresnel term.
#pragma once

#include <array>
#include <string>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace brdfbake {
namespace fit {

/// Per linear-sRGB channel: F82-tint's f0 = F(0 deg) and tint = F(mu_bar) / F_schlick(mu_bar; f0)
/// at mu_bar = 1/7 (about 82 deg), the definition of Kutz et al. 2021 (F82-tint reproduces F at
/// both angles exactly), F being the spectral colour of fresnel_rgb_on_device; and how far the
/// F82-tint curve strays from F elsewhere: the largest |F82(mu) - F(mu)| over theta in [0, 90] deg
/// on a 0.25 deg grid, and where. `colour_error` is the spectral sum's own error (1 nm against 2 nm).
struct F82TintFit {
    std::array<double, 3> f0{}, tint{}, max_error{}, max_error_theta_deg{}, colour_error{};
};

F82TintFit fit_f82_tint(Engine& engine, const std::string& fresnel_spec, Precision precision);

}  // namespace fit
}  // namespace brdfbake

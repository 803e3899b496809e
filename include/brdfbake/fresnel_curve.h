// A Fresnel term evaluated on the device (kernels/fresnel.cl) at a list of cosines: the
// reflectance F and its two polarisations, the values `brdfbake fresnel` prints and plots.
#pragma once

#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace brdfbake {

struct FresnelCurves {
    std::vector<double> f, rs, rp;  // per cosine: unpolarised, s- and p-polarised reflectance
};

/// F, Rs and Rp of `fresnel` at each cos(theta) in [0, 1], computed by the Fresnel kernel in
/// `precision`. Throws Error for a cosine outside [0, 1] or a non-finite value from the kernel.
FresnelCurves fresnel_on_device(Engine& engine, const FresnelConfig& fresnel, Precision precision,
                                const std::vector<double>& cosines);

}  // namespace brdfbake

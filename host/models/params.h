// The host's parameter blocks as the shared BRDF headers take them.
#pragma once

#include "brdfbake/brdf/params.h"
#include "brdfbake/spec.h"

namespace brdfbake {

static_assert(std::tuple_size<ParamBlock>::value == BB_MAX_PARAMS, "ParamBlock holds BB_MAX_PARAMS slots");

/// A model's or a Fresnel term's parameters (ModelConfig::params, FresnelConfig::params,
/// AlbedoCell::params) as a bb_params.
inline bb_params to_bb_params(const ParamBlock& block) {
    bb_params p;
    for (int k = 0; k < BB_MAX_PARAMS; ++k) p.v[k] = block[k];
    return p;
}

}  // namespace brdfbake

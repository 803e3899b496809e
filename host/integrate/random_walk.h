// The directional albedo of the multiple-scattering Smith microsurface (ggx and beckmann with
// scattering=multiple) by random walks (brdf/random_walk.h, kernels/random_walk.cl): the albedo,
// its single-scattering part and the energy the bounce limit cut off, each with its error estimate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"

namespace brdfbake {

/// One cell's walk estimates: E (every order up to the limit), its first order, and the weight
/// still inside the microsurface when the bounce limit stopped the walks (E + cutoff is what an
/// unlimited walk would carry out, up to the noise).
struct WalkAlbedo {
    AlbedoValue energy, single, cutoff;
};

struct WalkResult {
    std::vector<WalkAlbedo> values;  // one per cell of the request
    std::uint64_t walks_per_cell = 0;
    double kernel_seconds = 0.0;
    std::string method;  // in words
};

/// The walks of `req` (a ggx or beckmann request whose cells' parameters ask for multiple
/// scattering): req.samples walks per cell, split over req.replicas replicas, in req.precision,
/// Philox keyed by req.seed and each cell's identity. Throws NonFiniteError if a walk met NaN.
WalkResult walk_albedo(Engine& engine, const AlbedoRequest& req);

}  // namespace brdfbake

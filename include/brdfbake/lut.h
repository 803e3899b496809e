// Lookup tables computed on the device: directional albedo, average albedo and the split-sum
// terms, over (mu_o, alpha).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/engine.h"
#include "brdfbake/table.h"

namespace brdfbake {

struct LutRequest {
    std::string kind;             // a TableKind's name (brdfbake/table_kinds.h): albedo, eavg, dfg, ...
    std::string model;            // model spec without the swept alpha, e.g. "ggx:shadowing=correlated"
    std::string fresnel = "none"; // albedo and eavg only
    double wavelength_nm = 0.0;   // conductor with a measured metal: 0 gives R, G, B at 650, 550, 450 nm
    int width = 32;               // mu texels (albedo, dfg) or alpha texels (eavg)
    int height = 32;              // alpha texels (albedo, dfg); 1 for eavg
    std::string mu_map = "linear";      // linear: mu = u; sqrt: u = sqrt(mu), mu = u^2
    std::string alpha_map = "alpha";    // alpha: alpha = v; roughness: v = sqrt(alpha), alpha = v^2
    double alpha_lo = 0.0, alpha_hi = 1.0;  // range of the roughness-axis coordinate
    int depth = 16;               // eta texels (dielectric)
    double eta_lo = 1.0, eta_hi = 3.0;  // eta axis range (dielectric); texel centres inside
    std::uint64_t samples = 1u << 18;   // per texel (per mu node for eavg)
    Method method = Method::Importance; // with a fixed sample count; the dielectric table: importance only
    ToleranceRequest tolerance;         // tolerance.tolerance > 0: refine every texel to it instead
    Precision precision = Precision::Float;
};

/// Sets width, height and depth from 1 to 3 sizes as `--size` reads them: N is NxN (N for a
/// 1D kind), WxH, and WxHxD for a kind with an eta axis (depth H when not given). Throws Error
/// for too many sizes or a 1D kind given a height. request.kind must be set first.
void set_lut_size(LutRequest& request, const std::vector<int>& sizes);

/// Checks a request without touching the device (kind, model, ranges, sizes, and the kind's own
/// checks in its registry entry, brdfbake/table_kinds.h); throws Error.
void validate_lut(const LutRequest& request);

/// Computes the table. Throws Error for bad input or non-finite results.
Table compute_lut(Engine& engine, const LutRequest& request);

}  // namespace brdfbake

// Validation of a BRDF: the white furnace (directional albedo <= 1 within its error estimate),
// reciprocity f(wo, wi) = f(wi, wo) over a dense grid of direction pairs, and a scan for NaN,
// Inf and negative values. Both scans run on the OpenCL device over the whole grid at once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace brdfbake {

/// The reciprocity and value scan over (theta_i, theta_o) pairs, worst over the azimuths.
struct ReciprocityMap {
    int n_theta = 0;
    int n_phi = 0;    // azimuth differences per pair
    int n_phi_o = 0;  // outgoing azimuths per pair (> 1 for anisotropic models)
    std::vector<double> theta;         // texel centres in (0, pi/2), radians
    std::vector<double> max_rel;       // [o * n_theta + i]: worst relative error
    std::vector<double> dphi_at_max;   // phi_i - phi_o of the worst pair (radians)
    std::vector<double> min_value;     // smallest finite f
    std::uint64_t nonfinite = 0;       // NaN or Inf values over the whole scan
    std::uint64_t evaluations = 0;
    Precision precision = Precision::Double;
};

/// Scans f over theta_i, theta_o at `n_theta` texel centres of (0, 90 deg) and `n_phi` azimuth
/// differences (and as many outgoing azimuths for anisotropic models).
ReciprocityMap scan_reciprocity(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                int n_theta, int n_phi, Precision precision);

struct CheckOptions {
    int directions = 48;            // furnace: theta_o texel centres over (0, 90 deg)
    int phis = 8;                   // furnace: phi_o values over [0, 180 deg) for anisotropic models
    std::uint64_t samples = 1 << 16;  // furnace: samples per direction
    Precision precision = Precision::Float;  // furnace
    double energy_tolerance = 1e-4;          // allowed E - 1 beyond the error estimate
    int resolution = 32;                     // reciprocity: theta texels
    int phi_resolution = 32;                 // reciprocity: azimuth differences
    double reciprocity_tolerance = 1e-6;     // allowed relative error (double), 1e-3 in float
};

struct CheckReport {
    std::string model, fresnel;
    // white furnace
    double max_albedo = 0.0, max_albedo_error = 0.0, max_albedo_mu = 0.0, max_albedo_phi = 0.0;
    bool energy_violation = false;
    std::uint64_t furnace_samples = 0;  // 0 with furnace_analytic (delta lobes)
    bool furnace_analytic = false;
    int furnace_directions = 0;
    // reciprocity
    double max_rel = 0.0, max_rel_theta_i = 0.0, max_rel_theta_o = 0.0, max_rel_dphi = 0.0;
    bool reciprocity_violation = false;
    double reciprocity_tolerance = 0.0;
    /// A simulated model's (scattering=multiple): f(a, b) and f(b, a) are walk estimates, and the
    /// worst difference is also given in standard errors of the two (reciprocity_sigmas).
    bool reciprocity_noise = false;
    double reciprocity_sigmas = 0.0;
    std::string reciprocity_of = "|f(wo,wi) - f(wi,wo)|";  // the quantities compared (a layer's: band fluxes)
    std::uint64_t pairs = 0;
    std::uint64_t scan_nonfinite = 0;  // NaN or Inf values met by the scan: reciprocity is then unknown
    // values
    std::uint64_t nonfinite = 0;
    double min_value = 0.0;
    bool value_violation = false;
    std::string nonfinite_where;  // where the furnace met non-finite samples, if it did
    CheckOptions options;

    bool passed() const { return !energy_violation && !reciprocity_violation && !value_violation; }
};

/// Runs the three checks. Violations are findings, not errors: only bad input throws.
CheckReport run_check(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel, const CheckOptions& o);

/// The report as text: one line per check (energy, reciprocity, values) with its numbers, then
/// "verdict: PASS" or "verdict: VIOLATION" (what `brdfbake check` prints, and the bake report shows).
std::string check_report_text(const CheckReport& r);

}  // namespace brdfbake

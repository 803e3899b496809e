// The one-call C++ API, mirroring the Python module's functions: the model given once, as a spec,
// and every option with the default `brdfbake albedo` / `brdfbake lut` and Python use.
//
//   const brdfbake::AlbedoValues e = brdfbake::albedo("ggx:alpha=0.5", {0.25, 0.5, 1.0});
//   // e.albedo[i] +- e.error[i]
//   brdfbake::AlbedoOptions to_1e6;
//   to_1e6.tolerance = 1e-6;
//   const brdfbake::AlbedoValue v = brdfbake::albedo("ggx:alpha=0.5", 0.5, to_1e6);  // v.value +- v.error
//   brdfbake::LutOptions dfg;
//   dfg.model = "ggx";
//   dfg.size = {32, 32};
//   const brdfbake::Table t = brdfbake::lut("dfg", dfg);  // t.values[channel][y * width + x]
//
// Both call the functions the command line and Python call (resolve_model, resolve_fresnel,
// choose_method, albedo_of_model; lut_preset, set_lut_size, validate_lut, compute_lut) on one
// Engine per device selector, created on first use and kept (its kernel programs stay built).
// Bad input throws brdfbake::Error naming the mistake, before the device is touched.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/spec.h"
#include "brdfbake/table.h"

namespace brdfbake {

/// The options of albedo(), as `brdfbake albedo` and Python's brdfbake.albedo name them.
struct AlbedoOptions {
    std::vector<double> phi_deg;  // azimuth of the view in degrees: empty (0), one value, or one per mu
    std::string fresnel = "none";
    double wavelength = 0.0;  // nm, for measured metals (fresnel = "metal:Al")
    double samples = double(1 << 18);
    double tolerance = 0.0;  // > 0: refine every direction to this absolute error instead of `samples`
    std::string method = "auto";  // auto, importance, qmc, mc, quadrature
    double max_samples = double(1 << 26);
    std::string precision = "float";  // float or double
    std::string device;  // OpenCL device selector; empty: the default
};

/// albedo() over several mu: the values and their error estimates (one per mu, in order), what
/// was run and how long it took.
struct AlbedoValues {
    std::vector<double> albedo, error;
    std::string model, fresnel, method, device;  // the canonical specs, the method, the device's name
    std::uint64_t samples = 0;  // per direction (the most, with a tolerance)
    double seconds = 0.0;
};

/// The directional albedo E(mu) = integral of f cos(theta_i) over the hemisphere of the model
/// `model` (a spec: "ggx:alpha=0.5") at each mu = cos(theta_o) in (0, 1].
AlbedoValues albedo(const std::string& model, const std::vector<double>& mu, const AlbedoOptions& options = {});

/// What albedo() returns, from a computed result (the Python module's albedo() shapes it into arrays).
AlbedoValues albedo_values(const AlbedoResult& result, const ModelConfig& model, const FresnelConfig& fresnel,
                           const std::string& device, double seconds);

/// The same at one mu: the value and its error estimate.
AlbedoValue albedo(const std::string& model, double mu, const AlbedoOptions& options = {});

/// The options of lut(), as `brdfbake lut` and Python's brdfbake.lut name them: a preset (if
/// given) sets the request for its kind, then every option given overrides it; the rest are the
/// defaults of `brdfbake lut`.
struct LutOptions {
    std::optional<std::string> model, preset, estimator, fresnel, mu_map, alpha_map, eta_map, texels, method, precision;
    std::vector<int> size;  // {N}, {W, H} or {W, H, D}; empty: the kind's (or preset's) size
    std::optional<double> wavelength, mu_floor, samples, tolerance, max_samples;
    std::optional<std::pair<double, double>> alpha_range, mu_range, eta_range;
    std::optional<std::vector<std::string>> axes, flip;
    std::string device;
};

/// A lookup table of kind `kind` ("dfg", "albedo", "dielectric", ...; empty: the preset's first
/// kind), as `brdfbake lut KIND` computes it. Table::values holds one vector per channel, x fastest.
Table lut(const std::string& kind, const LutOptions& options);

}  // namespace brdfbake

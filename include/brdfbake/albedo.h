// Directional albedo E(wo) = integral of f(wo, wi) cos(theta_i) dwi, computed in a kernel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"

namespace brdfbake {

/// One outgoing direction (and, for table sweeps, the model parameters at that cell).
struct AlbedoCell {
    double mu = 1.0;   // cos(theta_o), in (0, 1]
    double phi = 0.0;  // phi_o in radians (matters for anisotropic models only)
    ParamBlock params{};
};

struct AlbedoRequest {
    int model = 0;  // BB_MODEL_*
    FresnelConfig fresnel;
    std::vector<AlbedoCell> cells;
    std::uint64_t samples = 1u << 18;  // per cell, split over the replicas
    unsigned replicas = 16;            // randomised replicas for the error estimate
    Precision precision = Precision::Float;
    std::uint64_t seed = 0x62726466u;  // "brdf": results are reproducible by default
    /// Lanes of the kernel's vector path: 0 the device's choice (Engine::vector_width), 1 the
    /// scalar kernel. The vector path needs a model whose sample is tabulated (GGX) and points
    /// per replica (samples / replicas) divisible by the lanes; otherwise the scalar kernel runs.
    unsigned vector_width = 0;
};

struct AlbedoValue {
    double value = 0.0;
    double error = 0.0;  // estimated absolute error: 3 standard errors + floating-point bound
};

/// Thrown when a kernel produced NaN or Inf sample weights: nothing is reported for such a run.
class NonFiniteError : public Error {
public:
    NonFiniteError(const std::string& message, size_t cell, std::uint64_t count)
        : Error(message), cell(cell), count(count) {}
    size_t cell;          // the first cell with non-finite samples
    std::uint64_t count;  // how many of its samples were non-finite
};

struct AlbedoResult {
    std::vector<AlbedoValue> values;  // one per cell
    std::uint64_t samples_per_cell = 0;
    std::string method;               // what the estimator did, in words
    double kernel_seconds = 0.0;      // device time of the integration
    unsigned vector_width = 1;        // lanes of the kernel that ran (1: scalar)
};

/// Runs the albedo kernel over every cell. Throws Error if the device produced non-finite
/// sample weights (the cell and count are named), or for an invalid request.
AlbedoResult compute_albedo(Engine& engine, const AlbedoRequest& request);

/// One cell of a rough dielectric interface (GGX, isotropic): wo at cos(theta) = mu on the
/// near side, eta the far side's index relative to the near side (eta < 1: seen from inside).
struct DielectricCell {
    double mu = 1.0;
    double alpha = 0.5;
    double eta = 1.5;
};

struct DielectricRequest {
    std::vector<DielectricCell> cells;
    bool correlated = true;  // height-correlated G2 (reflection and transmission); else separable
    std::uint64_t samples = 1u << 18;
    unsigned replicas = 16;
    Precision precision = Precision::Float;
    std::uint64_t seed = 0x62726466u;
};

struct DielectricResult {
    std::vector<AlbedoValue> reflected;    // energy fraction reflected, per cell
    std::vector<AlbedoValue> transmitted;  // energy fraction transmitted, per cell
    std::uint64_t samples_per_cell = 0;
    std::string method;
    double kernel_seconds = 0.0;
};

/// Reflected and transmitted energy fractions of a rough dielectric (kernels/dielectric.cl).
DielectricResult compute_dielectric(Engine& engine, const DielectricRequest& request);

/// The cells for a list of mu values at one azimuth, all with the same model parameters.
std::vector<AlbedoCell> cells_for(const std::vector<double>& mus, double phi, const ParamBlock& params);

}  // namespace brdfbake

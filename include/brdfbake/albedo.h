// Directional albedo E(wo) = integral of f(wo, wi) cos(theta_i) dwi, computed in a kernel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"

namespace brdfbake {

/// How an albedo integral is computed (--method; docs/accuracy.md).
enum class Method {
    Importance,       // the model's importance sampler, randomised Hammersley points ("importance")
    QuasiMonteCarlo,  // uniform hemisphere sampling, randomised Hammersley points ("qmc")
    MonteCarlo,       // uniform hemisphere sampling, Philox pseudo-random points ("mc")
    Quadrature,       // Gauss-Legendre product rule, in half-vector space for microfacet lobes ("quadrature")
};

/// The method's name on the command line.
const char* method_name(Method m);
/// The method for a command-line name (not "auto", which the caller resolves). Throws Error.
Method parse_method(const std::string& name);

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
    Method method = Method::Importance;
    /// Per cell: the sample count, split over the replicas; for quadrature the nodes of the fine
    /// rule (n^2 per azimuth piece: 4 pieces, 2 for mirror-symmetric lobes, 8 for anisotropic lobes
    /// off their axes; n = the even number nearest sqrt(samples / 4)).
    std::uint64_t samples = 1u << 18;
    unsigned replicas = 16;            // randomised replicas for the error estimate (sampling methods)
    Precision precision = Precision::Float;
    std::uint64_t seed = 0x62726466u;  // "brdf": results are reproducible by default
    /// Lanes of the kernel's vector path: 0 the device's choice (Engine::vector_width), 1 the
    /// scalar kernel. The vector path needs a model whose sample is tabulated (GGX) and points
    /// per replica (samples / replicas) divisible by the lanes; otherwise the scalar kernel runs.
    /// Quadrature has one for the half-vector rule (ggx, beckmann, torrance-sparrow, blinn-phong).
    unsigned vector_width = 0;
};

struct AlbedoValue {
    double value = 0.0;
    /// Estimated absolute error: 3 standard errors of the replicas (sampling methods) or the
    /// difference between the n- and n/2-node rules (quadrature), plus a floating-point bound.
    double error = 0.0;
    std::uint64_t samples = 0;  // integrand evaluations spent on this cell (all rounds)
    Method method = Method::Importance;  // the method of the reported value
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
    std::uint64_t samples_per_cell = 0;  // the largest per-cell count (AlbedoValue::samples)
    std::string method;               // what the estimator did, in words
    double kernel_seconds = 0.0;      // device time of the integration
    unsigned vector_width = 1;        // lanes of the kernel that ran (1: scalar)
    std::uint64_t total_samples = 0;  // over all cells and rounds
    double tolerance = 0.0;           // the tolerance met by every cell (0: a fixed sample count)
    unsigned rounds = 1;              // kernel launches (tolerance mode refines in rounds)
};

/// phi reduced to [0, 2 pi) exactly (fmod in double), as compute_albedo does before a cell
/// reaches a kernel: results are the same for phi and phi + 2 pi k. Throws Error if not finite.
double reduce_azimuth(double phi);

/// An azimuth in degrees (any finite number) as radians in [0, 2 pi): reduced exactly in degrees
/// first (fmod is exact), so that phi and phi + 360 k give one cell. Throws Error if not finite.
double azimuth_from_degrees(double degrees);

/// Runs the albedo kernel over every cell (phi reduced by reduce_azimuth). Throws Error if the device produced non-finite
/// sample weights (the cell and count are named), or for an invalid request.
AlbedoResult compute_albedo(Engine& engine, const AlbedoRequest& request);

/// Tolerance mode (--tolerance): every cell refined until its error estimate is at most
/// `tolerance`. With auto_method the engine starts each cell with Gauss-Legendre quadrature and
/// moves on to importance sampling where the rule does not converge; otherwise only
/// request.method is refined. Work per cell grows geometrically up to max_samples; cells that
/// still miss the tolerance make it throw Error with exit status 1, naming the worst cell.
struct ToleranceRequest {
    double tolerance = 0.0;  // absolute; 0: none (a fixed sample count)
    bool auto_method = true;
    std::uint64_t max_samples = std::uint64_t(1) << 26;
};

AlbedoResult compute_albedo_to_tolerance(Engine& engine, const AlbedoRequest& request,
                                         const ToleranceRequest& tolerance);

/// The sample count, method and tolerance a user asks for: "auto" with a sample count is the
/// default method (importance sampling); with a tolerance, auto lets the engine choose per cell.
struct MethodChoice {
    std::uint64_t samples = 0;
    Method method = Method::Importance;
    ToleranceRequest tolerance;  // tolerance.tolerance == 0: a fixed sample count
};

/// `method` is "auto" or a method name; `tolerance` 0 means a fixed sample count. Throws Error
/// (naming the command-line option) for a sample count, tolerance or max_samples that is not
/// positive, or an unknown method.
MethodChoice choose_method(const std::string& method, double samples, double tolerance, double max_samples);

/// Refuses a method the model cannot be integrated with: quadrature for a stochastic model (its
/// value an estimate, ModelTraits::stochastic), whose rule would read noise as the integrand.
/// Throws Error naming the model and the methods it takes.
void check_method_for_model(const ModelTraits& model, Method method);

/// The smallest tolerance a precision can honour: the floating-point bound of the error
/// estimate at an albedo of 1.
double tolerance_floor(Precision precision);

/// One cell of a rough dielectric interface (GGX, isotropic): wo at cos(theta) = mu on the
/// near side, eta the far side's index relative to the near side (eta < 1: seen from inside).
struct DielectricCell {
    double mu = 1.0;
    double alpha = 0.5;
    double eta = 1.5;
};

/// The Smith G2 a model's `shadowing` names (brdf/microfacet.h's BB_SHADOWING_*, the same values):
/// separable G1(wo) G1(wi), height-correlated 1/(1 + L_o + L_i) (Heitz 2014 eq. 98, 99), or the
/// masking term G1(wo) alone.
enum class Shadowing { Separable = 0, Correlated = 1, Masking = 2 };

/// The rough dielectric's transmitted G2 under correlated shadowing (the ggx key
/// `transmission_shadowing`; brdf/rough_dielectric.h's BB_TRANSMISSION_SHADOWING_*, the same
/// values): the Beta function of Heitz 2014 eq. 100, or 1/(1 + L_o + L_t) as Blender Cycles does.
enum class TransmissionShadowing { Beta = 0, Cycles = 1 };

struct DielectricRequest {
    std::vector<DielectricCell> cells;
    /// Both lobes' G2: Separable or Correlated (there is no masking-only dielectric).
    Shadowing shadowing = Shadowing::Correlated;
    /// The transmitted lobe's G2 with Shadowing::Correlated (separable shadowing has one form).
    TransmissionShadowing transmission_shadowing = TransmissionShadowing::Beta;
    /// Importance (visible-normal sampling, replicas) or Quadrature (the half-vector rule of
    /// brdf/dielectric_quadrature.h, n = sqrt(samples / 4) as for the albedo, per azimuth piece
    /// and row segment: up to n = 32, a Gauss-Kronrod rule of 15 to 61 (at most 2n - 1) points,
    /// its error from the embedded Gauss rule; beyond, the Gauss-Legendre rule of n nodes, its
    /// error from the n/2- and n/4-node rules). Other methods are refused.
    Method method = Method::Importance;
    std::uint64_t samples = 1u << 18;
    unsigned replicas = 16;
    Precision precision = Precision::Float;
    std::uint64_t seed = 0x62726466u;
    // Samples per kernel step: 0 the device's choice (vectors on CPUs, as AlbedoRequest), 1 the
    // scalar kernel, 2/4/8/16 a vector kernel of that width.
    unsigned vector_width = 0;
};

struct DielectricResult {
    std::vector<AlbedoValue> reflected;    // energy fraction reflected, per cell
    std::vector<AlbedoValue> transmitted;  // energy fraction transmitted, per cell
    std::uint64_t samples_per_cell = 0;
    std::string method;
    double kernel_seconds = 0.0;
    unsigned vector_width = 1;  // samples per kernel step (1: the scalar kernel)
};

/// Reflected and transmitted energy fractions of a rough dielectric (kernels/dielectric.cl).
/// Each cell's value depends only on the cell and the request's other fields, never on which
/// other cells share the request.
DielectricResult compute_dielectric(Engine& engine, const DielectricRequest& request);

/// The same to a tolerance: the plan of tolerance_steps (quadrature first for the auto method
/// or --method quadrature, then importance sampling for the cells the rule cannot certify),
/// every round over the cells still above it. Throws Error (exit status 1) naming the worst cell
/// when cells remain above it.
DielectricResult compute_dielectric_to_tolerance(Engine& engine, const DielectricRequest& request,
                                                 const ToleranceRequest& tolerance);

/// The cells for a list of mu values at one azimuth, all with the same model parameters.
std::vector<AlbedoCell> cells_for(const std::vector<double>& mus, double phi, const ParamBlock& params);

}  // namespace brdfbake

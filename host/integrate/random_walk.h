// The directional albedo of the multiple-scattering Smith microsurface (ggx and beckmann with
// scattering=multiple) by random walks (brdf/random_walk.h, kernels/random_walk.cl): the albedo,
// its single-scattering part and the energy the bounce limit cut off, each with its error estimate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/check.h"
#include "brdfbake/evaluate.h"

namespace brdfbake {

/// One cell's walk estimates: E (every order up to the limit), its first order, and the weight
/// still inside the microsurface when the bounce limit stopped the walks (E + cutoff is what an
/// unlimited walk would carry out, up to the noise). The rough dielectric's walk (a cell whose
/// BB_SMITH_WALK_ETA is > 0) splits what escapes: `energy` and `single` are its reflected R and
/// R's first order, `transmitted` and `single_t` T and T's first order, `total` R + T (each
/// estimated on its own replicas: its error is not the sum of theirs). For a conductor
/// `transmitted` and `single_t` are 0 and `total` is `energy`.
struct WalkAlbedo {
    AlbedoValue energy, single, cutoff, transmitted, single_t, total;
};

struct WalkResult {
    std::vector<WalkAlbedo> values;  // one per cell of the request
    std::uint64_t walks_per_cell = 0;
    double kernel_seconds = 0.0;
    std::string method;  // in words
    unsigned rounds = 1;             // walk_albedo_to_tolerance's rounds
    std::uint64_t total_walks = 0;   // over every cell and round
};

/// The walks of `req` (a ggx or beckmann request whose cells' parameters ask for multiple
/// scattering): req.samples walks per cell, split over req.replicas replicas, in req.precision,
/// Philox keyed by req.seed and each cell's identity. Throws NonFiniteError if a walk met NaN.
WalkResult walk_albedo(Engine& engine, const AlbedoRequest& req);

/// The same to a tolerance (integrate/refine.cpp): rounds of 2^14 walks and up, 4x per round, up
/// to tolerance.max_samples, over the cells whose values are not all within it. Throws
/// ToleranceNotMet (exit status 1) naming the worst cell when cells remain above it.
WalkResult walk_albedo_to_tolerance(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tolerance);

/// One value of f to estimate by the walks: f(wo, wi) with the parameters `params` (a ggx or beckmann
/// block asking for multiple scattering), wo and wi unit vectors: f is 0 where wo lies at or below
/// the horizon, or wi does for a conductor; a dielectric walk's wi below gives its transmitted f_t.
struct WalkEvalPair {
    Vec3 wo{0.0, 0.0, 1.0}, wi{0.0, 0.0, 1.0};
    ParamBlock params{};
};

struct WalkEvalRequest {
    int model = 0;  // BB_MODEL_GGX or BB_MODEL_BECKMANN
    FresnelConfig fresnel;
    std::vector<WalkEvalPair> pairs;
    std::uint64_t samples = 1u << 14;  // walks per pair, split over the replicas
    unsigned replicas = 16;
    Precision precision = Precision::Float;
    std::uint64_t seed = 0x62726466u;
};

struct WalkEvalResult {
    std::vector<AlbedoValue> f;       // per pair: f(wo, wi), every order up to the bounce limit
    std::vector<AlbedoValue> single;  // its first order (the height-correlated Smith lobe's f)
    std::uint64_t walks_per_pair = 0;
    double kernel_seconds = 0.0;
    std::string method;  // in words
};

/// f(wo, wi) of the multiple-scattering microsurface by the next-event estimation of [HHdD16]
/// (brdf/random_walk.h, kernels/random_walk.cl walk_eval): walks from wo, at every intersection the
/// phase function towards wi times the masking of wi from that height; each value with its error
/// (3 standard errors of the replicas). Throws NonFiniteError if a walk met NaN.
WalkEvalResult walk_eval(Engine& engine, const WalkEvalRequest& req);

/// `check` of a simulated model (integrate/check_walk.cpp; run_check calls it): the furnace by
/// walk_albedo, reciprocity by walk_eval from both ends of each pair (a violation: a difference above
/// kReciprocitySigmas standard errors plus the relative tolerance), the values over the same pairs.
constexpr double kReciprocitySigmas = 6.0;
/// The white furnace's directions of `check` (check.cpp; both checks): o.directions theta_o texel
/// centres, times o.phis azimuths for an anisotropic model, o.samples each.
AlbedoRequest furnace_request(const ModelConfig& model, const FresnelConfig& fresnel, const CheckOptions& o);
/// The furnace's worst direction (the largest E less its error) of `values` (one per req.cells)
/// into r, and its verdict against r.options.energy_tolerance (check.cpp; both checks).
void record_furnace(CheckReport& r, const std::vector<AlbedoValue>& values, const AlbedoRequest& req);
CheckReport run_check_walk(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                           const CheckOptions& o);

/// walk_albedo, or walk_albedo_to_tolerance at `share` of tolerance.tolerance when that is > 0
/// (ToleranceNotMet names the user's tolerance).
WalkResult walk_albedo_at(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tolerance, double share);

/// The walks' albedo E of `req`'s cells as an AlbedoResult (lut albedo of a scattering=multiple
/// spec): walk_albedo, or walk_albedo_to_tolerance at `share` of tolerance.tolerance when that is > 0
/// (ToleranceNotMet names the user's tolerance). The energy the bounce limit cut off is added to
/// each value's error (it is not in E).
AlbedoResult walk_albedo_result(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tolerance,
                                double share);

}  // namespace brdfbake

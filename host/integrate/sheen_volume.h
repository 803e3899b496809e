// The volumetric sheen layer of Zeltner, Burley and Chiang 2022 by random walks
// (brdf/sheen_volume.h, kernels/sheen_volume.cl): its reflectance R(mu, alpha), the first order,
// the transmission and the share the bounce limit cut off, each with its error estimate, and the
// histogram of the reflected directions (the lobe the sheen LTC is fitted to).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/check.h"
#include "integrate/random_walk.h"

namespace brdfbake {

struct SheenVolumeCell {
    double mu = 1.0;     // cosine of the view
    double alpha = 0.5;  // roughness; the fibers' cross-section sigma = alpha^2
    int bounces = 1000;  // the walk's scattering limit
};

struct SheenVolumeRequest {
    std::vector<SheenVolumeCell> cells;
    std::uint64_t walks = 1u << 20;  // per cell, split over the replicas
    unsigned replicas = 16;
    std::uint64_t seed = 1;
    Precision precision = Precision::Float;
    bool lobe = false;  // also the reflected directions' histogram
    /// The histogram's estimator: true, the next-flight tallies (every scattering after the first
    /// that turns up adds its probability of leaving the top unscattered, brdf/sheen_volume.h
    /// bb_sheen_next_flight); false, the analog counts of the actual exits (the same expectation).
    bool next_flight = true;
};

/// The bins of the lobe: theta_o uniform over [0, pi/2] (rows), |phi_o| uniform over [0, pi]
/// (columns), phi_o measured from the view's azimuth; the lobe is symmetric about phi_o = 0.
struct SheenLobeBins {
    static int theta();
    static int phi();
    /// Solid angle of one bin on one side of phi = 0.
    static double solid_angle(int row);
};

struct SheenVolumeValue {
    AlbedoValue reflectance;    // R: the share of walks leaving through the top
    AlbedoValue single;         // the part of R after exactly one scattering
    AlbedoValue transmittance;  // T: leaving through the bottom
    AlbedoValue direct;         // the part of T without scattering
    AlbedoValue cutoff;         // still inside after `bounces` scatterings (R + T + cutoff = 1)
    /// With SheenVolumeRequest::lobe: per bin (row-major, SheenLobeBins), the mean over the bin
    /// of the reflected density f cos(theta_o) per solid angle (over both sides of phi = 0) of the
    /// walks that scattered two or more times (by SheenVolumeRequest::next_flight's estimator), and
    /// its error (3 standard errors of the replicas).
    /// The first order's density is sheen_single_density (closed form, no noise).
    std::vector<double> lobe, lobe_error;
    double flights = 0.0;  // the mean free flights a walk (its cost)
};

/// The first scattering order's reflected density per solid angle, f1 cos(theta_i), at the unit
/// exit direction (x, y, z), z > 0, the view at (sqrt(1 - mu^2), 0, mu), roughness alpha: the
/// specular microflake phase function D(h) / (4 sigma(wo)) [HDCD15 eq. 13] times the slab's depth
/// integral k_o (1 - exp(-(k_o + k))) / (k_o + k), k_o = sigma(wo)/mu, k = sigma(w)/z
/// (brdf/sheen_volume.h). Integrated over the hemisphere it is the walks' `single`.
double sheen_single_density(double mu, double alpha, double x, double y, double z);

struct SheenVolumeResult {
    std::vector<SheenVolumeValue> values;  // one per cell
    std::uint64_t walks_per_cell = 0;
    double kernel_seconds = 0.0;
    std::string method;  // in words
};

/// The walks of `req`: req.walks per cell over req.replicas replicas, in req.precision, Philox
/// keyed by req.seed and each cell's content. Throws NonFiniteError if a walk met NaN.
SheenVolumeResult sheen_volume_walks(Engine& engine, const SheenVolumeRequest& req);

// ---- the layer as a model spec (sheen-volume:roughness=R, BB_TRAIT_LAYER_WALK) ------------------

/// The walks of an albedo request of the sheen-volume model (walk_albedo routes it here by the
/// registry's layer_walk trait): per cell energy = R, single = R's first order, transmitted = T,
/// single_t = T without scattering, cutoff, and total = R + T (= 1 - cutoff per replica: the layer
/// absorbs nothing). The cells' parameters are the model's (BB_SHEEN_VOLUME_MODEL_*).
WalkResult sheen_layer_walk_albedo(Engine& engine, const AlbedoRequest& req);

/// f(wis[k], wos[k]) of the sheen-volume model `model` for `lobe`: light from wis[k] walks through
/// the layer (`walks` per distinct incident direction) and f is estimated per exit bin
/// (SheenLobeBins) as the orders >= 2's histogram over the bin's integral of cos theta_o, plus the
/// first order in closed form at wos[k] (sheen_single_density); *error gets the histogram's error
/// (3 standard errors) over the same integral.
std::vector<double> sheen_layer_lobe(Engine& engine, const ModelConfig& model, Precision precision,
                                     const std::vector<Vec3>& wos, const std::vector<Vec3>& wis, std::uint64_t walks,
                                     std::vector<double>* error);

/// check's reciprocity of the sheen-volume model: the histogram cannot evaluate f at a pair, so the
/// check compares integrals that reciprocity makes equal: the flux Q(A -> B) = integral over wo in the
/// theta band A of cos theta_o P(exit in B | wo), B a theta band and a |phi| range of the exits, against
/// Q(B's band -> A's band, same |phi| range); 4 bands x 4 azimuth ranges (SheenLobeBins grouped),
/// each band's integral by 3-point Gauss-Legendre in mu. Orders >= 2 (the histogram's); the first
/// order is reciprocal by its closed form (its f is symmetric in wo and wi).
void scan_layer_reciprocity(Engine& engine, const ModelConfig& model, const CheckOptions& o, CheckReport& r);

}  // namespace brdfbake

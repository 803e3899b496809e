// Refinement to a tolerance: integrate every cell with a sequence of (method, samples) steps,
// each step over only the cells whose error estimate is still above the tolerance. The albedo
// (compute_albedo_to_tolerance) and the rough dielectric table refine through this one driver.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/error.h"

namespace brdfbake {

/// One round of refinement: the method and the samples per cell it spends.
struct RefineStep {
    Method method = Method::Importance;
    std::uint64_t samples = 0;
};

/// What one round returns for the cells it was given, in their order: per cell one value per
/// channel (e.g. the dielectric's R and T). A cell's error is the largest of its channels'.
struct RefineRound {
    std::vector<std::vector<AlbedoValue>> values;  // [cell of the round][channel]
    std::string method;                            // what the round did, in words (for --verbose)
    double kernel_seconds = 0.0;
    unsigned vector_width = 1;
};

/// Integrates `cells` (indices into the caller's cell list) with `step`.
using RefineIntegrate = std::function<RefineRound(const RefineStep& step, const std::vector<size_t>& cells)>;

struct RefineOptions {
    double tolerance = 0.0;
    /// Keep each cell's estimate with the smallest error over the rounds (true), or the latest.
    bool keep_best = true;
    /// Log each round to stderr ("brdfbake: round N: ...").
    bool verbose = false;
    /// The progress stage's name ("rough dielectric of 4096 cells to tolerance 0.0001"); its
    /// units are cells certified, its steps the rounds (brdfbake/progress.h).
    std::string progress_what = "refinement";
};

struct RefineOutcome {
    std::vector<std::vector<AlbedoValue>> values;  // [cell][channel]: the kept estimate
    std::vector<std::uint64_t> spent;              // [cell]: samples of channel 0 over all rounds
    std::vector<size_t> missed;                    // cells still above the tolerance, ascending
    std::map<std::string, size_t> met_by;          // "quadrature (1024 points)" -> cells it finished
    unsigned rounds = 0;
    double kernel_seconds = 0.0;
    unsigned vector_width = 1;
    std::uint64_t total_samples = 0;     // channel 0's samples over all cells and rounds
    std::uint64_t last_step_samples = 0; // the samples of the last step that ran
};

/// The refusal of a tolerance run that missed its tolerance (exit status 1), in the user's terms:
/// the --tolerance the user gave (a table that adds several integrals gives each a share of it;
/// the share is named as such, never as the tolerance), where the cells lie (a table's slice),
/// the worst cell's coordinates and its error estimate.
class ToleranceNotMet : public Error {
public:
    struct Facts {
        double tolerance = 0.0;  // what this integral was held to
        double stated = 0.0;     // the user's --tolerance (0: `tolerance` itself)
        size_t missed = 0, cells = 0;
        std::string what;        // "cells", "dielectric cells"
        std::string where;       // "slice cycles_z = 0.99 (exponent 0.0505)"; empty: none
        std::string worst_cell;  // "mu = 0.5, alpha = 0.25"
        double worst_error = 0.0;
        std::uint64_t max_samples = 0;
        bool float_precision = false;
    };
    explicit ToleranceNotMet(const Facts& facts);
    const Facts& facts() const { return facts_; }
    /// The same refusal where the tolerance was a share of the user's `stated` (0: unchanged) and
    /// the cells lie `where` (empty: unchanged).
    ToleranceNotMet restated(double stated, const std::string& where) const;

private:
    Facts facts_;
};

/// The plan of a tolerance run, one place for every kind: with the auto method (or `method`
/// Quadrature) the quadrature rules of 16 to 512 nodes per axis first (samples 4 n^2, 4x the
/// work per step; their error falls exponentially for smooth integrands), then, with the auto
/// method or a sampling `method`, importance sampling (or that method) from 2^14 samples up to
/// tolerance.max_samples, 4x per step, for the cells the rule cannot certify. Throws Error when
/// max_samples leaves no step.
std::vector<RefineStep> tolerance_steps(const ToleranceRequest& tolerance, Method method);

/// The same with the quadrature rounds' budgets given (those up to tolerance.max_samples run):
/// the rough dielectric's rules differ from the albedo's.
std::vector<RefineStep> tolerance_steps(const ToleranceRequest& tolerance, Method method,
                                        const std::vector<std::uint64_t>& quadrature_samples);

/// The refusal of a tolerance below what `precision` can certify (twice tolerance_floor).
void check_tolerance(double tolerance, Precision precision);

/// Runs `steps` in order until every cell's error is at most options.tolerance or the steps
/// run out; never throws for missed cells (the caller words that error).
RefineOutcome refine_to_tolerance(size_t n_cells, const std::vector<RefineStep>& steps, const RefineOptions& options,
                                  const RefineIntegrate& integrate);

}  // namespace brdfbake

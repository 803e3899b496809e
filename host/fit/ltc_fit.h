// Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time Polygonal-Light
// Shading with Linearly Transformed Cosines", [HDHN16]) fitted to a model's lobe per cell
// (mu, parameters): the fitting layer's LTC objective, evaluated on the device (kernels/ltc.cl),
// minimised by the batched Nelder-Mead of nelder_mead.h. The frame: normal +z, viewer at
// wo = (sin theta_o, 0, cos theta_o); an isotropic lobe is symmetric in y, so that
// M = [[m00, 0, m02], [0, m11, 0], [m20, 0, m22]].
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"
#include "fit/nelder_mead.h"

namespace brdfbake {
namespace fit {

/// M of an isotropic LTC (row-major entries; the others are 0).
struct LtcMatrix {
    double m00 = 1, m02 = 0, m11 = 1, m20 = 0, m22 = 1;
};

/// The fit's free parameters q = (theta, ln a, b, ln c):
/// M = R_y(theta) [[a, 0, b], [0, c, 0], [0, 0, 1]], R_y(theta) taking +z to (sin theta, 0, cos theta).
/// D does not change with the scale of M, so four parameters span every such M of positive
/// determinant; a, c > 0 by construction. q = 0 is the identity (the clamped cosine).
LtcMatrix ltc_matrix(const std::array<double, 4>& q);

/// The LTC distribution at a unit direction w: D(w) = D_o(w_o) |det M^-1| / |M^-1 w|^3 with
/// w_o = M^-1 w / |M^-1 w| and D_o = max(0, z)/pi ([HDHN16] eq. 1 and the Jacobian of section 3.1).
double ltc_density(const LtcMatrix& m, const std::array<double, 3>& w);

/// integral of D over the upper hemisphere, in closed form: w lies above the horizon iff
/// (m20, 0, m22).w_o > 0, a hemisphere of w_o whose axis n = (m20, 0, m22)/|.| makes an angle
/// gamma with +z; the clamped cosine's mass in it is (1 + cos gamma)/2.
double ltc_upper_mass(const LtcMatrix& m);

struct LtcCell {
    double mu = 1.0;
    ParamBlock params{};
    double albedo = 0;  // E of the lobe, p = f cos / E in the reported distance; 0: the fit's points' E
};

struct LtcFitOptions {
    Precision precision = Precision::Float;
    int fit_side = 24;      // the objective's points per cell: fit_side^2 (the lobe's sampler)
    int fit_grade = 2;      // u1 = 1 - (1 - s)^fit_grade, s on the midpoint rule (graded_nodes, ltc_fit.cpp)
    int distance_grids = 16; // the reported distance: the mean over this many independent jittered
    int distance_side = 24;  // grids of distance_side^2 points; its error: distance_sigmas standard
    double distance_sigmas = 5;  // errors of that mean (the grids' spread)
    int max_evaluations = 300;       // per cell
    double value_tolerance = 1e-3;   // Nelder-Mead's convergence (nelder_mead.h), relative to the
                                     // start's distance, in coordinates scaled by the lobe's width
    /// The M that the table's stored values denote, given the fitted one (their float32 rounding);
    /// empty: the entries rounded to float32. The reported distance is that M's.
    std::function<LtcMatrix(const LtcMatrix&)> as_written;
    double size_tolerance = 1e-3;
    /// The polish of each fit on refine_side^2 points (0: none), from the fit_side^2 minimum with
    /// the simplex's steps times refine_step and at most refine_evaluations per cell (lazy steps,
    /// NelderMeadOptions::speculative false). 64^2 and 40 keep the 64x64 GGX table's distances by
    /// the independent reference (median, mean, 90th percentile within 0.5%) of 96^2 and 100 at
    /// about half the CPU (benchmarks/results/ltc-table-amd-epyc-2c.md, branch ltc3).
    int refine_side = 64;
    double refine_step = 0.3;
    int refine_evaluations = 40;
    /// A row of precision float with a lobe narrower than narrow_width (E_p[|x'/z'|] or E_p[|y'/z'|]
    /// about its average direction, about the LTC's a or c) is fitted in double, with Nelder-Mead's
    /// value and size tolerances narrow_tolerance. Float's directions and view cosine (1 - mu to
    /// 6e-8) move a lobe 2.5e-4 wide by a few percent of its width: the float fit of GGX at alpha
    /// 2.5e-4 lay 3e-4 from the true lobe by the numpy reference, 7e-6 in double. And a near-exact
    /// fit's distance grows as |dx|, not dx^2: the tolerances 1e-3 stopped up to 35% above the distance
    /// reached at 1e-6 (0.02: the 12 smoothest rows of 64 of the GGX table, alpha <= 0.03;
    /// benchmarks/results/ltc-compare-amd-epyc-2c.md, ltc6).
    double narrow_width = 0.02;
    double narrow_tolerance = 1e-6;
};

struct LtcFit {
    LtcMatrix m;
    std::array<double, 4> q{};  // the fitted parameters (ltc_matrix)
    std::array<double, 4> x{};  // the same with theta relative to the lobe's average direction
    double distance = 0;        // integral over the upper hemisphere of |p - D|, p = f cos / E, of m
    double distance_error = 0;  // m: the matrix as written (LtcFitOptions::as_written)
    double albedo = 0;          // the E of p (the cell's, or the fit's points' mean sample weight)
    int evaluations = 0;
};

/// Fits the rows in order. A row's cells are fitted together (one launch per Nelder-Mead round
/// for all of them), each started from the fit of the cell at the same index of the previous row
/// (as [HDHN16]'s fits start from the neighbouring texel; order the rows from rough to smooth),
/// the first row from the cosine turned to the lobe's average direction. `row_done(i)` is called
/// after each row (progress). The model must have an importance sampler whose weights are bounded.
std::vector<std::vector<LtcFit>> fit_ltc_rows(Engine& engine, const ModelConfig& model,
                                              const std::vector<std::vector<LtcCell>>& rows,
                                              const LtcFitOptions& options,
                                              const std::function<void(size_t)>& row_done = {});

}  // namespace fit
}  // namespace brdfbake

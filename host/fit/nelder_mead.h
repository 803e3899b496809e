// A deterministic Nelder-Mead simplex minimiser run on many problems in lockstep, so that one
// objective call (one kernel launch) evaluates a candidate set for every problem at once: the
// fitting layer's optimiser, shared by the LTC tables (ltc_fit.h) and any later fit of a model to
// data. Nelder and Mead 1965, "A simplex method for function minimization", with the standard
// coefficients (reflection 1, expansion 2, contractions 1/2, shrink 1/2; Lagarias et al. 1998,
// "Convergence properties of the Nelder-Mead simplex method in low dimensions", section 2).
#pragma once

#include <functional>
#include <vector>

namespace brdfbake {
namespace fit {

struct NelderMeadOptions {
    std::vector<double> steps;       // the initial simplex: the start plus each step along its axis
    int max_evaluations = 400;       // per problem, restarts included
    double value_tolerance = 1e-6;   // converged: the simplex's values span less than this ...
    double size_tolerance = 1e-5;    // ... and every vertex lies this close to the best (max norm)
    int restarts = 1;                // fresh simplices around the best after convergence
    /// true: a step asks for its four candidates at once (one round a step, 4 evaluations); false:
    /// the reflection first, then the one candidate it calls for (1-2 rounds, 1-2 evaluations). The
    /// same decisions either way; false spends half the evaluations where they, not rounds, cost.
    bool speculative = true;
};

struct Minimum {
    std::vector<double> x;
    double value = 0.0;
    int evaluations = 0;
    bool converged = true;  // false: max_evaluations stopped it before the simplex converged
};

/// Values of a batch of points: point i is a point of problem `problem[i]`.
using BatchObjective =
    std::function<std::vector<double>(const std::vector<size_t>& problem, const std::vector<std::vector<double>>& points)>;

/// Minimises every problem from its start. Each round asks the objective once for the points of
/// every unfinished problem: the n + 1 vertices of a new simplex, the four candidates of a step
/// (reflection, expansion, outside and inside contraction, evaluated together so that a step is
/// one round; with options.speculative false, the reflection and then the one candidate it calls
/// for) or the n vertices of a shrink. Deterministic: the same starts give the same minima.
std::vector<Minimum> minimize_batch(const std::vector<std::vector<double>>& starts, const NelderMeadOptions& options,
                                    const BatchObjective& objective);

}  // namespace fit
}  // namespace brdfbake

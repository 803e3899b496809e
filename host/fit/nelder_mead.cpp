#include "fit/nelder_mead.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "brdfbake/error.h"

namespace brdfbake {
namespace fit {
namespace {

using Point = std::vector<double>;

enum class Phase { NewSimplex, Step, Reflect, Follow, Shrink, Done };

struct Problem {
    std::vector<Point> simplex;
    std::vector<double> values;
    std::vector<Point> pending;  // the points asked for this round
    std::vector<Point> candidates;  // a lazy step's four candidates (ask_step) ...
    double reflected = 0;           // ... and the reflection's value
    int follow = 0;                 // the candidate asked after it
    Phase phase = Phase::NewSimplex;
    int evaluations = 0;
    int restarts_left = 0;
    bool out_of_budget = false;  // stopped by max_evaluations before converging
};

Point affine(const Point& a, const Point& b, double t) {  // a + t (b - a)
    Point r(a.size());
    for (size_t i = 0; i < a.size(); ++i) r[i] = a[i] + t * (b[i] - a[i]);
    return r;
}

void start_simplex(Problem& p, const Point& x, const std::vector<double>& steps) {
    p.simplex.assign(1, x);
    for (size_t i = 0; i < x.size(); ++i) {
        Point v = x;
        v[i] += steps[i];
        p.simplex.push_back(v);
    }
    p.pending = p.simplex;
    p.phase = Phase::NewSimplex;
}

void sort_simplex(Problem& p) {
    std::vector<size_t> order(p.simplex.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p.values[a] < p.values[b]; });
    std::vector<Point> s;
    std::vector<double> v;
    for (size_t i : order) {
        s.push_back(p.simplex[i]);
        v.push_back(p.values[i]);
    }
    p.simplex = s;
    p.values = v;
}

/// The four candidates of a step from the sorted simplex: x_c + t (x_c - x_worst) for t = 1
/// (reflection), 2 (expansion), 1/2 (outside contraction), -1/2 (inside contraction).
/// Lazily (options.speculative false) only the reflection is asked for.
void ask_step(Problem& p, bool speculative) {
    const size_t n = p.simplex.size() - 1;
    Point centroid(p.simplex[0].size(), 0.0);
    for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < centroid.size(); ++j) centroid[j] += p.simplex[i][j] / double(n);
    p.candidates.clear();
    for (double t : {1.0, 2.0, 0.5, -0.5}) p.candidates.push_back(affine(centroid, p.simplex[n], -t));
    p.pending = speculative ? p.candidates : std::vector<Point>{p.candidates[0]};
    p.phase = speculative ? Phase::Step : Phase::Reflect;
}

void ask_shrink(Problem& p) {
    p.pending.clear();
    for (size_t i = 1; i < p.simplex.size(); ++i) p.pending.push_back(affine(p.simplex[0], p.simplex[i], 0.5));
    p.phase = Phase::Shrink;
}

bool converged(const Problem& p, const NelderMeadOptions& o) {
    if (p.values.back() - p.values.front() > o.value_tolerance) return false;
    for (const Point& v : p.simplex)
        for (size_t j = 0; j < v.size(); ++j)
            if (std::abs(v[j] - p.simplex[0][j]) > o.size_tolerance) return false;
    return true;
}

/// Takes the step's candidate values and updates the simplex (Lagarias et al. 1998, section 2).
void take_step(Problem& p, const std::vector<double>& f, const std::vector<Point>& candidates) {
    const size_t n = p.simplex.size() - 1;
    const double best = p.values[0], second_worst = p.values[n - 1], worst = p.values[n];
    auto replace_worst = [&](size_t k) {
        p.simplex[n] = candidates[k];
        p.values[n] = f[k];
    };
    if (f[0] < best) {
        replace_worst(f[1] < f[0] ? 1 : 0);
    } else if (f[0] < second_worst) {
        replace_worst(0);
    } else if (f[0] < worst) {
        if (f[2] <= f[0]) replace_worst(2);
        else return ask_shrink(p);
    } else {
        if (f[3] < worst) replace_worst(3);
        else return ask_shrink(p);
    }
    p.phase = Phase::Step;
}

/// A lazy step: the reflection's value decides which one candidate take_step would read next
/// (expansion, outside or inside contraction); none when the reflection is taken as it is. Returns
/// false while that candidate is asked for.
bool lazy_step(Problem& p, double value) {
    const size_t n = p.simplex.size() - 1;
    const double inf = HUGE_VAL;
    if (p.phase == Phase::Reflect) {
        p.reflected = value;
        if (value < p.values[n - 1] && !(value < p.values[0])) {
            take_step(p, {value, inf, inf, inf}, p.candidates);
            return true;
        }
        p.follow = value < p.values[0] ? 1 : value < p.values[n] ? 2 : 3;
        p.pending = {p.candidates[size_t(p.follow)]};
        p.phase = Phase::Follow;
        return false;
    }
    std::vector<double> f = {p.reflected, inf, inf, inf};
    f[size_t(p.follow)] = value;
    take_step(p, f, p.candidates);
    return p.phase != Phase::Shrink;
}

void advance(Problem& p, const std::vector<double>& f, const NelderMeadOptions& o) {
    p.evaluations += int(f.size());
    if (p.phase == Phase::Reflect || p.phase == Phase::Follow) {
        if (!lazy_step(p, f[0])) return;
    } else if (p.phase == Phase::NewSimplex) {
        p.values = f;
    } else if (p.phase == Phase::Shrink) {
        for (size_t i = 1; i < p.simplex.size(); ++i) {
            p.simplex[i] = p.pending[i - 1];
            p.values[i] = f[i - 1];
        }
    } else {
        take_step(p, f, p.candidates);
        if (p.phase == Phase::Shrink) return;
    }
    sort_simplex(p);
    const bool out_of_budget = p.evaluations + 4 > o.max_evaluations;
    if (out_of_budget) {
        p.out_of_budget = !converged(p, o);
        p.phase = Phase::Done;
    } else if (converged(p, o)) {
        if (p.restarts_left-- > 0 && p.evaluations + int(p.simplex.size()) + 4 <= o.max_evaluations) {
            const Point best = p.simplex[0];
            start_simplex(p, best, o.steps);
        } else {
            p.phase = Phase::Done;
        }
    } else {
        ask_step(p, o.speculative);
    }
}

}  // namespace

std::vector<Minimum> minimize_batch(const std::vector<std::vector<double>>& starts, const NelderMeadOptions& options,
                                    const BatchObjective& objective) {
    std::vector<Problem> problems(starts.size());
    for (size_t i = 0; i < starts.size(); ++i) {
        if (starts[i].size() != options.steps.size())
            throw Error("internal error: a Nelder-Mead start needs one step per parameter");
        problems[i].restarts_left = options.restarts;
        start_simplex(problems[i], starts[i], options.steps);
    }
    for (;;) {
        std::vector<size_t> owner;
        std::vector<Point> points;
        for (size_t i = 0; i < problems.size(); ++i) {
            if (problems[i].phase == Phase::Done) continue;
            for (const Point& x : problems[i].pending) {
                owner.push_back(i);
                points.push_back(x);
            }
        }
        if (points.empty()) break;
        const std::vector<double> values = objective(owner, points);
        if (values.size() != points.size()) throw Error("internal error: the objective returned too few values");
        for (size_t at = 0; at < points.size();) {
            Problem& p = problems[owner[at]];
            const size_t count = p.pending.size();
            std::vector<double> f(values.begin() + long(at), values.begin() + long(at + count));
            for (double& v : f)
                if (!std::isfinite(v)) v = HUGE_VAL;  // a degenerate candidate is never taken
            advance(p, f, options);
            at += count;
        }
    }
    std::vector<Minimum> out;
    for (const Problem& p : problems) out.push_back({p.simplex[0], p.values[0], p.evaluations, !p.out_of_budget});
    return out;
}

}  // namespace fit
}  // namespace brdfbake

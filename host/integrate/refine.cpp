#include "integrate/refine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/progress.h"
#include "brdfbake/spec.h"
#include "integrate/random_walk.h"

namespace brdfbake {

namespace {

double cell_error(const std::vector<AlbedoValue>& channels) {
    double e = channels.front().error;
    for (const auto& v : channels) e = std::max(e, v.error);
    return e;
}

/// The missed cell (outcome.missed, not empty) whose largest error is the largest.
size_t worst_missed(const RefineOutcome& outcome) {
    size_t worst = outcome.missed.front();
    for (size_t c : outcome.missed)
        if (cell_error(outcome.values[c]) > cell_error(outcome.values[worst])) worst = c;
    return worst;
}

/// A walk's values as refine_to_tolerance's channels, in one order both ways.
constexpr AlbedoValue WalkAlbedo::*kWalkChannels[] = {&WalkAlbedo::energy,      &WalkAlbedo::single,
                                                      &WalkAlbedo::cutoff,      &WalkAlbedo::transmitted,
                                                      &WalkAlbedo::single_t,    &WalkAlbedo::total};

}  // namespace

namespace {

std::string not_met_text(const ToleranceNotMet::Facts& f) {
    const double stated = f.stated > 0.0 ? f.stated : f.tolerance;
    std::ostringstream e;
    e << "--tolerance " << stated << " not met at " << f.missed << " of " << f.cells << " " << f.what
      << (f.where.empty() ? "" : " (" + f.where + ")") << " within " << f.max_samples
      << " samples per cell; worst: " << f.worst_cell << ", error estimate " << f.worst_error;
    if (f.tolerance < stated) e << ", above the " << f.tolerance << " this integral may spend of the tolerance";
    e << ". Raise --max-samples, " << (f.float_precision ? "use --precision double, " : "") << "or loosen the tolerance";
    return e.str();
}

}  // namespace

ToleranceNotMet::ToleranceNotMet(const Facts& facts) : Error(not_met_text(facts), kExitViolation), facts_(facts) {}

ToleranceNotMet ToleranceNotMet::restated(double stated, const std::string& where) const {
    Facts f = facts_;
    if (stated > 0.0) f.stated = stated;
    if (!where.empty()) f.where = where;
    return ToleranceNotMet(f);
}

void check_tolerance(double tolerance, Precision precision) {
    if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw Error("--tolerance must be a positive number");
    const double floor = tolerance_floor(precision);
    if (tolerance < 2.0 * floor) {
        // The tolerance asked of each integral (a table that adds several gives each a share).
        char text[160];
        std::snprintf(text, sizeof text, "--tolerance: %.3g per integral is below what %s arithmetic can certify (about %.2g)",
                      tolerance, precision_name(precision), 2.0 * floor);
        throw Error(std::string(text) + (precision == Precision::Float ? "; use --precision double" : ""));
    }
}

std::vector<RefineStep> tolerance_steps(const ToleranceRequest& tol, Method method) {
    std::vector<std::uint64_t> quadrature;
    for (std::uint64_t s = 4 * 16 * 16; s <= 4ull * 512 * 512; s *= 4) quadrature.push_back(s);
    return tolerance_steps(tol, method, quadrature);
}

std::vector<RefineStep> tolerance_steps(const ToleranceRequest& tol, Method method,
                                        const std::vector<std::uint64_t>& quadrature_samples) {
    // (method, samples) steps, each a round over the cells still above the tolerance.
    // Quadrature first (auto): its error falls exponentially for smooth lobes; importance
    // sampling, whose error falls like N^-0.9 with randomised QMC, takes the cells where the
    // rule stalls (kinks such as Torrance-Sparrow's V-groove min()). Work grows 4x per step.
    std::vector<RefineStep> steps;
    if (tol.auto_method || method == Method::Quadrature)
        for (std::uint64_t s : quadrature_samples)
            if (s <= tol.max_samples) steps.push_back({Method::Quadrature, s});
    if (tol.auto_method || method != Method::Quadrature) {
        const Method sampler = tol.auto_method ? Method::Importance : method;
        for (std::uint64_t s = std::uint64_t(1) << 14; s <= tol.max_samples; s *= 4) steps.push_back({sampler, s});
    }
    if (steps.empty()) throw Error("--max-samples is too small for a first round");
    return steps;
}

RefineOutcome refine_to_tolerance(size_t n_cells, const std::vector<RefineStep>& steps, const RefineOptions& options,
                                  const RefineIntegrate& integrate) {
    RefineOutcome out;
    out.values.assign(n_cells, std::vector<AlbedoValue>{});
    out.spent.assign(n_cells, 0);
    std::vector<bool> done(n_cells, false);
    std::vector<double> best_error(n_cells, INFINITY);
    // Progress: cells certified of all cells, over the rounds; the rounds are its steps (their
    // launches report inside them). The later rounds' cost is unknown, so the time left shown is
    // the current round's.
    ProgressStage stage(options.progress_what, n_cells, "cells", "certified", false);
    for (const auto& step : steps) {
        std::vector<size_t> todo;
        for (size_t c = 0; c < n_cells; ++c)
            if (!done[c]) todo.push_back(c);
        if (todo.empty()) break;
        std::ostringstream round;
        round << "round " << out.rounds + 1 << ": " << method_name(step.method) << " (" << step.samples
              << " points) on " << todo.size() << (todo.size() == 1 ? " cell" : " cells");
        stage.update(n_cells - todo.size(), round.str());
        const RefineRound part = integrate(step, todo);
        if (part.values.size() != todo.size()) throw Error("internal error: a refinement round lost cells");
        if (options.verbose)
            std::cerr << "brdfbake: round " << out.rounds + 1 << ": " << todo.size() << " cells, " << part.method
                      << ", kernel " << part.kernel_seconds * 1e3 << " ms\n";
        out.rounds++;
        out.kernel_seconds += part.kernel_seconds;
        out.vector_width = std::max(out.vector_width, part.vector_width);
        out.last_step_samples = step.samples;
        for (size_t i = 0; i < todo.size(); ++i) {
            const size_t c = todo[i];
            const std::vector<AlbedoValue>& v = part.values[i];
            const double error = cell_error(v);
            out.spent[c] += v.front().samples;
            out.total_samples += v.front().samples;
            if (out.values[c].empty()) out.values[c].assign(v.size(), AlbedoValue{});
            // Keep the better estimate so far (or the latest); a cell is done when it meets the tolerance.
            if (!options.keep_best || error < best_error[c]) {
                best_error[c] = error;
                out.values[c] = v;
            }
            if (error <= options.tolerance) {
                done[c] = true;
                std::ostringstream key;
                key << method_name(step.method) << " (" << v.front().samples << " points)";
                out.met_by[key.str()]++;
            }
        }
    }
    for (size_t c = 0; c < n_cells; ++c)
        if (!done[c]) out.missed.push_back(c);
    stage.update(n_cells - out.missed.size());
    return out;
}

namespace {

// "tolerance 1e-4: 30 cells by quadrature (1024 points), ...; 3 rounds", from the outcome.
std::string tolerance_method_text(double tolerance, const RefineOutcome& o) {
    std::ostringstream m;
    m << "tolerance " << tolerance << ": ";
    bool first = true;
    for (const auto& kv : o.met_by) {
        m << (first ? "" : ", ") << kv.second << (kv.second == 1 ? " cell" : " cells") << " by " << kv.first;
        first = false;
    }
    m << "; " << o.rounds << (o.rounds == 1 ? " round" : " rounds");
    return m.str();
}

// "albedo of 4096 cells to tolerance 0.0001": a refinement's progress stage.
std::string progress_name(const std::string& integral, size_t cells, double tolerance) {
    std::ostringstream m;
    m << integral << " of " << cells << (cells == 1 ? " cell" : " cells") << " to tolerance " << tolerance;
    return m.str();
}

// The options of a tolerance run of `integral` over `cells` cells.
RefineOptions refine_options(const Engine& engine, const ToleranceRequest& tol, const std::string& integral,
                             size_t cells, bool keep_best) {
    RefineOptions options;
    options.tolerance = tol.tolerance;
    options.keep_best = keep_best;
    options.verbose = engine.verbose();
    options.progress_what = progress_name(integral, cells, tol.tolerance);
    return options;
}

// "mu = 0.5, alpha = 0.25" (both alphas where they differ): the cell's coordinates.
std::string cell_text(const AlbedoRequest& req, size_t c) {
    const ModelTraits& m = model_traits(req.model);
    std::ostringstream t;
    t << "mu = " << req.cells[c].mu;
    if (m.alpha_x_slot >= 0) {
        const double ax = req.cells[c].params[size_t(m.alpha_x_slot)];
        const double ay = m.alpha_y_slot >= 0 ? req.cells[c].params[size_t(m.alpha_y_slot)] : ax;
        t << ", alpha = " << ax;
        if (ay != ax) t << ", alpha_y = " << ay;
    }
    return t.str();
}

// One round's request: `req` with the step's method and samples, over the cells `todo` only.
template <typename Request>
Request round_request(const Request& req, const RefineStep& step, const std::vector<size_t>& todo) {
    Request r = req;
    r.method = step.method;
    r.samples = step.samples;
    r.cells.clear();
    for (size_t c : todo) r.cells.push_back(req.cells[c]);
    return r;
}

// One round's record of the integration that made it (its values are the caller's): what it did,
// its kernel time and its vector width (1 where the integrator has none).
RefineRound round_of(const std::string& method, double kernel_seconds, unsigned vector_width = 1) {
    RefineRound round;
    round.method = method;
    round.kernel_seconds = kernel_seconds;
    round.vector_width = vector_width;
    return round;
}

}  // namespace

AlbedoResult compute_albedo_to_tolerance(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tol) {
    check_tolerance(tol.tolerance, req.precision);
    if (req.cells.empty()) throw Error("no directions to integrate");

    // A stochastic model's plan has no quadrature rounds (check_method_for_model).
    check_method_for_model(model_traits(req.model), req.method);
    ToleranceRequest plan = tol;
    plan.auto_method = tol.auto_method && !model_traits(req.model).stochastic;
    const std::vector<RefineStep> steps = tolerance_steps(plan, req.method);

    const RefineOptions options = refine_options(engine, tol, "albedo", req.cells.size(), true);
    const RefineOutcome o =
        refine_to_tolerance(req.cells.size(), steps, options, [&](const RefineStep& step, const std::vector<size_t>& todo) {
            const AlbedoResult part = compute_albedo(engine, round_request(req, step, todo));
            RefineRound round = round_of(part.method, part.kernel_seconds, part.vector_width);
            for (const auto& v : part.values) round.values.push_back({v});
            return round;
        });

    AlbedoResult result;
    result.tolerance = tol.tolerance;
    result.rounds = o.rounds;
    result.kernel_seconds = o.kernel_seconds;
    result.vector_width = o.vector_width;
    result.total_samples = o.total_samples;
    result.values.assign(req.cells.size(), AlbedoValue{});
    for (size_t c = 0; c < req.cells.size(); ++c) {
        if (!o.values[c].empty()) result.values[c] = o.values[c].front();
        result.values[c].samples = o.spent[c];  // every round's samples, not just the kept one's
        result.samples_per_cell = std::max(result.samples_per_cell, o.spent[c]);
    }
    result.method = tolerance_method_text(tol.tolerance, o);

    if (!o.missed.empty()) {
        const size_t worst = worst_missed(o);
        throw ToleranceNotMet({tol.tolerance, 0.0, o.missed.size(), req.cells.size(), "cells", "", cell_text(req, worst),
                               result.values[worst].error, tol.max_samples, req.precision == Precision::Float});
    }
    return result;
}


DielectricResult compute_dielectric_to_tolerance(Engine& engine, const DielectricRequest& req, const ToleranceRequest& tol) {
    check_tolerance(tol.tolerance, req.precision);
    if (req.cells.empty()) throw Error("no cells to integrate");
    // The dielectric's rules (dielectric_rule in dielectric.cpp): Gauss-Kronrod of 21, 31 and 61
    // points, whose error estimates cost no extra node, then Gauss-Legendre of 128 to 512.
    const std::vector<RefineStep> steps = tolerance_steps(
        tol, req.method, {4 * 11 * 11, 4 * 16 * 16, 4 * 31 * 31, 4 * 128 * 128, 4 * 256 * 256, 4ull * 512 * 512});
    // Importance rounds alone replace each estimate by the next (their errors fall steadily);
    // with quadrature rounds in the plan a cell keeps its best estimate, as the albedo's does.
    const RefineOptions options = refine_options(engine, tol, "rough dielectric", req.cells.size(),
                                                 steps.front().method == Method::Quadrature);
    const RefineOutcome o =
        refine_to_tolerance(req.cells.size(), steps, options, [&](const RefineStep& step, const std::vector<size_t>& todo) {
            const DielectricResult part = compute_dielectric(engine, round_request(req, step, todo));
            RefineRound round = round_of(part.method, part.kernel_seconds, part.vector_width);
            for (size_t i = 0; i < todo.size(); ++i) round.values.push_back({part.reflected[i], part.transmitted[i]});
            return round;
        });
    DielectricResult out;
    out.kernel_seconds = o.kernel_seconds;
    out.vector_width = o.vector_width;
    for (size_t c = 0; c < req.cells.size(); ++c) {
        out.reflected.push_back(o.values[c][0]);
        out.transmitted.push_back(o.values[c][1]);
        out.samples_per_cell = std::max(out.samples_per_cell, o.spent[c]);
    }
    out.method = tolerance_method_text(tol.tolerance, o);
    if (!o.missed.empty()) {
        const size_t worst = worst_missed(o);
        const DielectricCell& w = req.cells[worst];
        std::ostringstream cell;
        cell << "mu = " << w.mu << ", alpha = " << w.alpha << ", eta = " << w.eta;
        throw ToleranceNotMet({tol.tolerance, 0.0, o.missed.size(), req.cells.size(), "dielectric cells", "", cell.str(),
                               cell_error(o.values[worst]), tol.max_samples, req.precision == Precision::Float});
    }
    return out;
}

// The random walks to a tolerance: Monte Carlo rounds of 2^14 walks and up, 4x per round, over the
// cells whose reported values (E or R + T, R, T, the first orders, the cut-off) are not all within
// it; each round's estimate replaces the last.
WalkResult walk_albedo_to_tolerance(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tol) {
    check_tolerance(tol.tolerance, req.precision);
    if (req.cells.empty()) throw Error("no directions to integrate");
    ToleranceRequest plan = tol;
    plan.auto_method = false;
    const std::vector<RefineStep> steps = tolerance_steps(plan, Method::MonteCarlo);
    const RefineOptions options = refine_options(engine, tol, "random walks", req.cells.size(), false);
    WalkResult out;
    const RefineOutcome o =
        refine_to_tolerance(req.cells.size(), steps, options, [&](const RefineStep& step, const std::vector<size_t>& todo) {
            const WalkResult part = walk_albedo(engine, round_request(req, step, todo));
            out.method = part.method;
            RefineRound round = round_of(part.method, part.kernel_seconds);
            for (const WalkAlbedo& w : part.values) {
                round.values.emplace_back();
                for (auto channel : kWalkChannels) round.values.back().push_back(w.*channel);
            }
            return round;
        });
    out.kernel_seconds = o.kernel_seconds;
    out.rounds = o.rounds;
    out.total_walks = o.total_samples;
    for (size_t c = 0; c < req.cells.size(); ++c) {
        WalkAlbedo w;
        for (size_t k = 0; k < std::size(kWalkChannels); ++k) w.*kWalkChannels[k] = o.values[c][k];
        out.values.push_back(w);
        out.walks_per_cell = std::max(out.walks_per_cell, o.spent[c]);
    }
    out.method = tolerance_method_text(tol.tolerance, o) + "; " + out.method;
    if (!o.missed.empty()) {
        const size_t worst = worst_missed(o);
        throw ToleranceNotMet({tol.tolerance, 0.0, o.missed.size(), req.cells.size(), "cells", "", cell_text(req, worst),
                               cell_error(o.values[worst]), tol.max_samples, req.precision == Precision::Float});
    }
    return out;
}

}  // namespace brdfbake

// brdfbake-tradeoff: speed against accuracy of the albedo methods (issue 7) and of the rough
// dielectric's R and T (issue 20; --dielectric-only runs those rows alone). For GGX, Beckmann,
// Torrance-Sparrow (GGX and Blinn distributions) and Oren-Nayar over easy and hard cells, every
// method (importance, qmc, mc, quadrature) in float and double across sample counts: the true
// error against independent host references (tradeoff_refs.h), the error estimate, whether the
// estimate was honest, and the kernel time; then the --tolerance mode (auto) on the same cells.
// Writes NAME.json (every run, every cell) and NAME.md (tables), and with --plot the
// error-against-time figure.
//   brdfbake-tradeoff --plot docs/images/tradeoff.png      full study, results into benchmarks/results
//   brdfbake-tradeoff --quick --out-dir D                  a small grid in seconds (what CI runs)
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "brdfbake/albedo.h"
#include "harness/bench.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "brdfbake/version.h"
#include "plot/plot.h"
#include "reference/tradeoff_refs.h"
#include "report_options.h"

namespace {

using namespace brdfbake;
using nlohmann::json;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// ------------------------------------------------------------------------------------------
// The study's grid.

/// One model family: how its parameter becomes a spec, an equivalent alpha and a reference.
struct Family {
    std::string key;    // short name in the outputs
    std::string label;  // for titles
    tradeoff_ref::Family ref;
    std::string spec_format;    // printf format of the spec with the parameter
    std::string param_name;     // alpha, n or sigma
    std::vector<double> params;
    /// The alpha of the lobe's width (Blinn n: sqrt(2 / (n + 2))); Oren-Nayar has no narrow
    /// lobe and counts as alpha = 1.
    double alpha_of(double p) const {
        if (ref == tradeoff_ref::Family::TsBlinn) return std::sqrt(2.0 / (p + 2.0));
        if (ref == tradeoff_ref::Family::OrenNayar) return 1.0;
        return p;
    }
    std::string spec(double p) const {
        char buf[160];
        std::snprintf(buf, sizeof buf, spec_format.c_str(), p);
        return buf;
    }
};

/// Families of the full study. Blinn exponents give alpha = sqrt(2 / (n + 2)) of about 0.014
/// (n = 1e4, the largest the model takes), 0.045, 0.1, 0.5 and 1.
std::vector<Family> full_families() {
    const std::vector<double> alphas = {1e-3, 1e-2, 0.1, 0.5, 1.0};
    using F = tradeoff_ref::Family;
    return {
        {"ggx", "GGX", F::Ggx, "ggx:alpha=%.15g", "alpha", alphas},
        {"beckmann", "Beckmann", F::Beckmann, "beckmann:alpha=%.15g", "alpha", alphas},
        {"ts-ggx", "Torrance-Sparrow, GGX D", F::TsGgx, "torrance-sparrow:d=ggx,alpha=%.15g", "alpha", alphas},
        {"ts-blinn", "Torrance-Sparrow, Blinn D", F::TsBlinn, "torrance-sparrow:d=blinn,n=%.15g", "n",
         {1e4, 1e3, 198, 6, 0}},
        {"oren-nayar", "Oren-Nayar (rho = 1)", F::OrenNayar, "oren-nayar:sigma=%.15g,rho=1", "sigma",
         {0.1, 0.5, 1.0, 1.5}},
    };
}

struct Options {
    bool quick = false;
    std::vector<Family> families;
    std::vector<double> mus;
    std::vector<std::uint64_t> samples;
    std::vector<Method> methods = {Method::Importance, Method::QuasiMonteCarlo, Method::MonteCarlo,
                                   Method::Quadrature};
    std::vector<Precision> precisions = {Precision::Float, Precision::Double};
    /// Tolerance-mode checks (auto method): (precision, tolerance).
    std::vector<std::pair<Precision, double>> tolerances = {{Precision::Float, 1e-5}, {Precision::Double, 1e-7}};
    std::uint64_t max_samples = std::uint64_t(1) << 24;
    double min_seconds = 0.3;  // repeat a timed run until it has taken this long ...
    int min_runs = 3, max_runs = 15;  // ... with at least / at most this many runs
    // The references: two tolerances, the finer one the value, their difference its uncertainty.
    double ref_tol_coarse = 1e-11, ref_tol_fine = 1e-13;
    double ref_unc_floor = 1e-14;   // below this the integrand's own rounding (long double -> double)
    double ref_unc_max = 1e-11;     // references less certain than this are dropped
};

Options full_options() {
    Options o;
    o.families = full_families();
    o.mus = {1e-4, 1e-2, 0.3, 1.0};
    for (int k = 8; k <= 20; k += 2) o.samples.push_back(std::uint64_t(1) << k);
    return o;
}

Options quick_options() {
    Options o;
    o.quick = true;
    std::vector<Family> all = full_families();
    o.families = {all[0], all[4]};
    o.families[0].params = {1e-2, 0.5};
    o.families[1].params = {1.0};
    o.mus = {1e-2, 1.0};
    o.samples = {std::uint64_t(1) << 8, std::uint64_t(1) << 12};
    o.tolerances = {{Precision::Float, 1e-4}};
    o.max_samples = std::uint64_t(1) << 20;
    o.min_seconds = 0.0;
    o.min_runs = o.max_runs = 1;
    return o;
}

/// One cell of the study with its reference.
struct Cell {
    size_t family = 0;
    double param = 0.0, alpha = 0.0, mu = 0.0;
    std::string spec;
    bool easy = false;
    double ref = NAN, ref_coarse = NAN, unc = NAN, ref_seconds = 0.0;
    bool certain = false;
};

/// Easy cells: a lobe at least as wide as alpha = 0.1, seen from mu >= 0.3.
bool is_easy(double alpha, double mu) { return alpha >= 0.1 && mu >= 0.3; }

std::vector<Cell> make_cells(const Options& o) {
    std::vector<Cell> cells;
    for (size_t f = 0; f < o.families.size(); ++f)
        for (double p : o.families[f].params)
            for (double mu : o.mus) {
                Cell c;
                c.family = f;
                c.param = p;
                c.alpha = o.families[f].alpha_of(p);
                c.mu = mu;
                c.spec = o.families[f].spec(p);
                c.easy = is_easy(c.alpha, mu);
                cells.push_back(c);
            }
    return cells;
}

/// Every reference at both tolerances, on all cores (the references are independent).
void compute_references(const Options& o, std::vector<Cell>& cells) {
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i = next++; i < cells.size(); i = next++) {
            Cell& c = cells[i];
            const auto fam = o.families[c.family].ref;
            const double t0 = now();
            c.ref_coarse = tradeoff_ref::albedo(fam, c.param, c.mu, o.ref_tol_coarse);
            c.ref = tradeoff_ref::albedo(fam, c.param, c.mu, o.ref_tol_fine);
            c.ref_seconds = now() - t0;
            c.unc = std::max(std::fabs(c.ref - c.ref_coarse), o.ref_unc_floor);
            c.certain = std::isfinite(c.ref) && c.unc <= o.ref_unc_max;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t) pool.emplace_back(work);
    for (auto& t : pool) t.join();
}

// ------------------------------------------------------------------------------------------
// Runs.

AlbedoRequest request_for(const Family& fam, const std::vector<const Cell*>& cells, Method m, Precision p,
                          std::uint64_t samples) {
    AlbedoRequest req;
    req.fresnel = resolve_fresnel("none");
    for (const Cell* c : cells) {
        const ModelConfig mc = resolve_model(c->spec);
        if (req.cells.empty()) req.model = mc.id;
        if (mc.id != req.model) throw Error("cells of one family resolve to different models: " + fam.key);
        AlbedoCell ac;
        ac.mu = c->mu;
        ac.params = mc.params;
        req.cells.push_back(ac);
    }
    req.method = m;
    req.precision = p;
    req.samples = samples;
    return req;
}

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The judgement of one estimate against its reference.
struct Verdict {
    double true_error;
    bool dishonest;  // the true error, less the reference's uncertainty, above 3x the estimate
};
Verdict judge(double value, double estimate, const Cell& c) {
    const double t = std::fabs(value - c.ref);
    return {t, t - c.unc > 3.0 * estimate};
}

/// One fixed-sample run of a family: a compute_albedo call over all its cells, timed.
json timed_run(Engine& engine, const Options& o, const Family& fam, const std::vector<const Cell*>& cells,
               Method m, Precision p, std::uint64_t samples) {
    json run = {{"family", fam.key}, {"method", method_name(m)}, {"precision", precision_name(p)},
                {"samples", samples}, {"cells", json::array()}};
    const AlbedoRequest req = request_for(fam, cells, m, p, samples);
    std::vector<double> kernel, wall;
    AlbedoResult first;
    double spent = 0.0;
    try {
        while (true) {
            const double t0 = now();
            AlbedoResult r = compute_albedo(engine, req);
            const double dt = now() - t0;
            if (kernel.empty()) first = std::move(r);
            kernel.push_back(kernel.empty() ? first.kernel_seconds : r.kernel_seconds);
            wall.push_back(dt);
            spent += dt;
            const int runs = int(kernel.size());
            if (runs >= o.max_runs) break;
            if (runs >= o.min_runs && spent >= o.min_seconds) break;
            if (runs >= 1 && spent > 2.0) break;  // long runs are their own warm-up
        }
    } catch (const Error& e) {
        run["failed"] = e.what();
        return run;
    }
    run["estimator"] = first.method;
    run["vector_width"] = first.vector_width;
    run["repeats"] = kernel.size();
    run["kernel_seconds"] = median(kernel);
    run["wall_seconds"] = median(wall);
    run["kernel_seconds_per_cell"] = median(kernel) / double(cells.size());
    run["wall_seconds_per_cell"] = median(wall) / double(cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
        const AlbedoValue& v = first.values[i];
        const Verdict j = judge(v.value, v.error, *cells[i]);
        run["cells"].push_back({{"spec", cells[i]->spec}, {"mu", cells[i]->mu}, {"easy", cells[i]->easy},
                                {"value", v.value}, {"estimate", v.error}, {"samples", v.samples},
                                {"reference", cells[i]->ref}, {"true_error", j.true_error},
                                {"dishonest", j.dishonest}});
    }
    return run;
}

/// The auto method to `tol` within the study's sample limit.
ToleranceRequest auto_tolerance(const Options& o, double tol) {
    ToleranceRequest t;
    t.tolerance = tol;
    t.auto_method = true;
    t.max_samples = o.max_samples;
    return t;
}

/// The --tolerance mode (auto: quadrature, then importance) on each cell alone, so that one
/// cell that cannot meet the tolerance does not hide the others.
json tolerance_run(Engine& engine, const Options& o, const Family& fam, const Cell& c, Precision p, double tol) {
    json out = {{"family", fam.key}, {"spec", c.spec}, {"mu", c.mu}, {"easy", c.easy},
                {"precision", precision_name(p)}, {"tolerance", tol}, {"reference", c.ref}};
    AlbedoRequest req = request_for(fam, {&c}, Method::Importance, p, 0);
    const ToleranceRequest t = auto_tolerance(o, tol);
    const double t0 = now();
    try {
        const AlbedoResult r = compute_albedo_to_tolerance(engine, req, t);
        const AlbedoValue& v = r.values[0];
        const Verdict j = judge(v.value, v.error, c);
        out["value"] = v.value;
        out["estimate"] = v.error;
        out["samples"] = v.samples;
        out["method"] = method_name(v.method);
        out["rounds"] = r.rounds;
        out["kernel_seconds"] = r.kernel_seconds;
        out["true_error"] = j.true_error;
        out["met"] = j.true_error <= tol;
    } catch (const Error& e) {
        out["failed"] = e.what();
    }
    out["wall_seconds"] = now() - t0;
    return out;
}

// ------------------------------------------------------------------------------------------
// The rough dielectric (issue 20): R and T of the GGX interface (height-correlated, Beta-form
// transmission shadowing) per method, against the Boost.Math reference of
// benchmarks/reference/reference.h (ref::rough_dielectric_rt), as the albedo rows are judged.

struct DielectricStudyCell {
    DielectricCell cell;
    double r = NAN, t = NAN, r_unc = NAN, t_unc = NAN, seconds = 0.0;
    bool certain = false;
};

/// The grid: alpha from a narrow to the widest lobe, mu from grazing to normal, light from
/// outside (eta = 1.5) and from inside (1/1.5, total internal reflection).
std::vector<DielectricStudyCell> dielectric_cells(bool quick) {
    const std::vector<double> alphas = quick ? std::vector<double>{0.1, 0.5} : std::vector<double>{0.01, 0.1, 0.5, 1.0};
    const std::vector<double> mus = quick ? std::vector<double>{0.3, 1.0} : std::vector<double>{0.02, 0.3, 1.0};
    const std::vector<double> etas = quick ? std::vector<double>{1.5} : std::vector<double>{1.5, 1 / 1.5};
    std::vector<DielectricStudyCell> cells;
    for (double eta : etas)
        for (double alpha : alphas)
            for (double mu : mus) {
                DielectricStudyCell c;
                c.cell = {mu, alpha, eta};
                cells.push_back(c);
            }
    return cells;
}

/// The references at two tolerances (the finer one the value, the difference its uncertainty),
/// on all cores.
void dielectric_references(std::vector<DielectricStudyCell>& cells, double coarse, double fine, double floor,
                           double max_unc) {
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i = next++; i < cells.size(); i = next++) {
            DielectricStudyCell& c = cells[i];
            const double t0 = now();
            double rc, tc;
            ref::rough_dielectric_rt(c.cell.mu, c.cell.alpha, c.cell.eta, ref::DielectricShadowing::Beta, rc, tc, coarse);
            ref::rough_dielectric_rt(c.cell.mu, c.cell.alpha, c.cell.eta, ref::DielectricShadowing::Beta, c.r, c.t, fine);
            c.seconds = now() - t0;
            // The reference's tolerance is relative: it cannot vouch for digits below fine x value,
            // even where the two tolerances agree.
            c.r_unc = std::max({std::fabs(c.r - rc), fine * std::fabs(c.r), floor});
            c.t_unc = std::max({std::fabs(c.t - tc), fine * std::fabs(c.t), floor});
            c.certain = std::isfinite(c.r) && std::isfinite(c.t) && std::max(c.r_unc, c.t_unc) <= max_unc;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t) pool.emplace_back(work);
    for (auto& t : pool) t.join();
}

/// The cells' R and T against their references: max true errors, and the dishonest channels
/// (true error less the reference's uncertainty above 3x the estimate).
void judge_dielectric(json& run, const DielectricResult& res, const std::vector<const DielectricStudyCell*>& cells) {
    double max_r = 0.0, max_t = 0.0, max_est = 0.0;
    int dishonest = 0;
    for (size_t i = 0; i < cells.size(); ++i) {
        const DielectricStudyCell& c = *cells[i];
        const double er = std::fabs(res.reflected[i].value - c.r), et = std::fabs(res.transmitted[i].value - c.t);
        max_r = std::max(max_r, er);
        max_t = std::max(max_t, et);
        max_est = std::max({max_est, res.reflected[i].error, res.transmitted[i].error});
        dishonest += (er - c.r_unc > 3.0 * res.reflected[i].error) + (et - c.t_unc > 3.0 * res.transmitted[i].error);
        run["cells"].push_back({{"mu", c.cell.mu}, {"alpha", c.cell.alpha}, {"eta", c.cell.eta},
                                {"R", res.reflected[i].value}, {"R_estimate", res.reflected[i].error},
                                {"R_reference", c.r}, {"R_true_error", er}, {"T", res.transmitted[i].value},
                                {"T_estimate", res.transmitted[i].error}, {"T_reference", c.t}, {"T_true_error", et}});
    }
    run["max_true_error_R"] = max_r;
    run["max_true_error_T"] = max_t;
    run["max_estimate"] = max_est;
    run["dishonest_channels"] = dishonest;
}

DielectricRequest dielectric_request(const std::vector<const DielectricStudyCell*>& cells, Method m, Precision p,
                                     std::uint64_t samples) {
    DielectricRequest r;
    for (const DielectricStudyCell* c : cells) r.cells.push_back(c->cell);
    r.method = m;
    r.precision = p;
    r.samples = samples;
    r.shadowing = Shadowing::Correlated;  // with Beta-form transmission shadowing
    r.transmission_shadowing = TransmissionShadowing::Beta;
    return r;
}

/// The dielectric study: fixed-sample runs of quadrature and importance sampling, then the auto
/// method to tolerances, each over every certain cell; results into j["dielectric"].
void dielectric_study(Engine& engine, const Options& o, json& j) {
    std::vector<DielectricStudyCell> cells = dielectric_cells(o.quick);
    const double coarse = 1e-8, fine = 1e-10, floor = 1e-13, max_unc = 1e-8;
    std::cerr << "brdfbake-tradeoff: " << cells.size() << " dielectric references\n";
    const double t_ref = now();
    dielectric_references(cells, coarse, fine, floor, max_unc);
    json d;
    d["reference_seconds"] = now() - t_ref;
    d["reference_tolerances"] = {coarse, fine};
    d["cells"] = json::array();
    std::vector<const DielectricStudyCell*> certain;
    for (const DielectricStudyCell& c : cells) {
        d["cells"].push_back({{"mu", c.cell.mu}, {"alpha", c.cell.alpha}, {"eta", c.cell.eta}, {"R", c.r}, {"T", c.t},
                              {"R_uncertainty", c.r_unc}, {"T_uncertainty", c.t_unc}, {"seconds", c.seconds},
                              {"certain", c.certain}});
        if (c.certain) certain.push_back(&c);
    }
    std::cerr << "brdfbake-tradeoff: dielectric references took " << d["reference_seconds"].get<double>() << " s\n";
    d["runs"] = json::array();
    if (!certain.empty()) {
        struct Plan {
            Method method;
            std::vector<std::uint64_t> samples;
        };
        const std::vector<Plan> plans = {
            // The budgets of the dielectric's rules (its tolerance plan): Gauss-Kronrod of 21, 31
            // and 61 points per axis, then Gauss-Legendre of 128 nodes.
            {Method::Quadrature, o.quick ? std::vector<std::uint64_t>{4 * 16 * 16}
                                         : std::vector<std::uint64_t>{4 * 11 * 11, 4 * 16 * 16, 4 * 31 * 31, 4 * 128 * 128}},
            {Method::Importance, o.quick ? std::vector<std::uint64_t>{1u << 12}
                                         : std::vector<std::uint64_t>{1u << 12, 1u << 14, 1u << 16, 1u << 18, 1u << 20}}};
        for (const Plan& plan : plans)
            for (Precision p : o.precisions) {
                try {
                    compute_dielectric(engine, dielectric_request(certain, plan.method, p, plan.samples.front()));  // the build
                } catch (const Error&) {
                }
                for (std::uint64_t s : plan.samples) {
                    json run = {{"method", method_name(plan.method)}, {"precision", precision_name(p)},
                                {"samples", s}, {"cells", json::array()}};
                    const DielectricRequest req = dielectric_request(certain, plan.method, p, s);
                    try {
                        std::vector<double> kernel, wall;
                        DielectricResult first;
                        double spent = 0.0;
                        while (true) {
                            const double t0 = now();
                            DielectricResult r = compute_dielectric(engine, req);
                            wall.push_back(now() - t0);
                            kernel.push_back(r.kernel_seconds);
                            if (kernel.size() == 1) first = std::move(r);
                            spent += wall.back();
                            const int runs = int(kernel.size());
                            if (runs >= o.max_runs || (runs >= o.min_runs && spent >= o.min_seconds) || spent > 2.0) break;
                        }
                        run["repeats"] = kernel.size();
                        run["kernel_seconds_per_cell"] = median(kernel) / double(certain.size());
                        run["wall_seconds_per_cell"] = median(wall) / double(certain.size());
                        judge_dielectric(run, first, certain);
                    } catch (const Error& e) {
                        run["failed"] = e.what();
                    }
                    std::cerr << "  dielectric " << method_name(plan.method) << " " << precision_name(p) << " " << s
                              << (run.contains("failed") ? ": failed" : "") << "\n";
                    d["runs"].push_back(run);
                }
            }
        // The auto method (quadrature, then importance for the cells the rule cannot certify).
        for (const auto& pt : o.tolerances) {
            if (std::find(o.precisions.begin(), o.precisions.end(), pt.first) == o.precisions.end()) continue;
            for (double tol : {1e-4, pt.second}) {
                if (tol == pt.second && tol == 1e-4 && d["runs"].back().value("tolerance", 0.0) == tol) continue;
                json run = {{"method", "auto"}, {"precision", precision_name(pt.first)}, {"tolerance", tol},
                            {"cells", json::array()}};
                const ToleranceRequest t = auto_tolerance(o, tol);
                const double t0 = now();
                try {
                    const DielectricResult r =
                        compute_dielectric_to_tolerance(engine, dielectric_request(certain, Method::Importance, pt.first, 0), t);
                    run["wall_seconds_per_cell"] = (now() - t0) / double(certain.size());
                    run["kernel_seconds_per_cell"] = r.kernel_seconds / double(certain.size());
                    run["estimator"] = r.method;
                    judge_dielectric(run, r, certain);
                    run["met"] = std::max(run["max_true_error_R"].get<double>(), run["max_true_error_T"].get<double>()) <= tol;
                } catch (const Error& e) {
                    run["failed"] = e.what();
                }
                std::cerr << "  dielectric auto " << precision_name(pt.first) << " " << tol << "\n";
                d["runs"].push_back(run);
            }
        }
    }
    j["dielectric"] = d;
}

// ------------------------------------------------------------------------------------------
// Machine facts (as benchmarks/results/<machine>.md states them).

std::string utc_date() {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
    return buf;
}

/// JSON text with one line per cell: arrays of objects get a line per element, objects holding
/// such arrays a line per member, everything else stays on one line.
std::string json_lines(const json& v, const std::string& indent = "") {
    auto object_array = [](const json& a) {
        return a.is_array() && !a.empty() && std::all_of(a.begin(), a.end(), [](const json& e) { return e.is_object(); });
    };
    const std::string in = indent + " ";
    std::string out;
    if (object_array(v)) {
        for (const auto& e : v) out += (out.empty() ? "[\n" : ",\n") + in + json_lines(e, in);
        return out + "\n" + indent + "]";
    }
    if (v.is_object() && std::any_of(v.begin(), v.end(), object_array)) {
        for (auto it = v.begin(); it != v.end(); ++it)
            out += (out.empty() ? "{\n" : ",\n") + in + json(it.key()).dump() + ": " + json_lines(it.value(), in);
        return out + "\n" + indent + "}";
    }
    return v.dump();
}

// ------------------------------------------------------------------------------------------
// Summaries of the runs: per (family, method, precision, samples) and class (easy/hard).

struct ClassStats {
    size_t cells = 0, dishonest = 0;
    double median_error = NAN, max_error = NAN;
};

ClassStats class_stats(const json& run, bool easy) {
    ClassStats s;
    std::vector<double> errors;
    for (const auto& c : run["cells"])
        if (c["easy"].get<bool>() == easy) {
            errors.push_back(c["true_error"].get<double>());
            s.dishonest += c["dishonest"].get<bool>();
        }
    s.cells = errors.size();
    if (!errors.empty()) {
        s.median_error = median(errors);
        s.max_error = *std::max_element(errors.begin(), errors.end());
    }
    return s;
}

std::string sci(double v, int digits = 1) {
    if (!std::isfinite(v)) return "–";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*e", digits, v);
    return buf;
}

/// A true error as text: below the references' uncertainty floor it cannot be told from 0.
std::string err_text(double v, double floor) { return std::isfinite(v) && v < floor ? "<" + sci(floor, 0) : sci(v); }

std::string fixed(double v, int digits) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

std::string label_of(const json& run) {
    return run["method"].get<std::string>() + " " + run["precision"].get<std::string>();
}

/// The best run (smallest max true error over a class) among those within a time budget per cell.
const json* best_within(const json& runs, const std::string& family, bool easy, double budget) {
    const json* best = nullptr;
    double best_err = INFINITY;
    for (const auto& r : runs) {
        if (r["family"] != family || r.contains("failed")) continue;
        if (r["kernel_seconds_per_cell"].get<double>() > budget) continue;
        const ClassStats s = class_stats(r, easy);
        if (s.cells > 0 && s.max_error < best_err) {
            best_err = s.max_error;
            best = &r;
        }
    }
    return best;
}

std::string dielectric_markdown(const json& d) {
    std::ostringstream md;
    md << "## The rough dielectric: R and T\n\n"
          "GGX interface, height-correlated reflection shadowing and Beta-form transmission shadowing (Heitz 2014 "
          "eq. 99-100), `compute_dielectric` over all certain cells in one call per row (the path of `brdfbake lut "
          "dielectric`); auto: `compute_dielectric_to_tolerance` (quadrature rounds, then importance sampling). "
          "Reference: `ref::rough_dielectric_rt` (benchmarks/reference/reference.h: adaptive Gauss-Kronrod in "
          "theta_h, tanh-sinh pieces in phi_h cut in closed form) at tolerance "
       << sci(d["reference_tolerances"][1].get<double>(), 0) << ", its uncertainty the difference from "
       << sci(d["reference_tolerances"][0].get<double>(), 0) << " and at least the tolerance times the value (cells less certain than 1e-8 dropped); "
       << fixed(d["reference_seconds"].get<double>(), 1) << " s wall. Time: the kernel's per cell (median of "
          "repeated runs after a warm-up); wall: the whole call per cell. *Beyond 3x*: channels (R or T of a cell) "
          "whose true error, less the reference's uncertainty, exceeds 3x the estimate.\n\n";
    size_t n_certain = 0;
    for (const auto& c : d["cells"]) n_certain += c["certain"].get<bool>();
    md << "Cells: " << n_certain << " of " << d["cells"].size()
       << " certain (alpha, mu and eta of each in the JSON).\n\n"
          "| method | precision | points or tolerance | kernel ms/cell | wall ms/cell | max true error R | max true "
          "error T | max estimate | beyond 3x |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : d["runs"]) {
        md << "| " << r["method"].get<std::string>() << " | " << r["precision"].get<std::string>() << " | "
           << (r.contains("tolerance") ? "tol " + sci(r["tolerance"].get<double>(), 0)
                                       : std::to_string(r["samples"].get<std::uint64_t>()))
           << " | ";
        if (r.contains("failed")) {
            md << "failed: " << r["failed"].get<std::string>() << " | | | | | |\n";
            continue;
        }
        md << sci(r["kernel_seconds_per_cell"].get<double>() * 1e3, 2) << " | "
           << sci(r["wall_seconds_per_cell"].get<double>() * 1e3, 2) << " | " << sci(r["max_true_error_R"].get<double>())
           << " | " << sci(r["max_true_error_T"].get<double>()) << " | " << sci(r["max_estimate"].get<double>()) << " | "
           << r["dishonest_channels"].get<int>() << " of " << 2 * r["cells"].size() << " |\n";
    }
    return md.str();
}

// The header (machine, run, method) and the cells with their references.
void markdown_head(std::ostringstream& md, const json& j, const Options& o) {
    const json& m = j["machine"];
    md << "# brdfbake speed against accuracy: " << j["name"].get<std::string>() << "\n\n";
    md << "Machine: " << m["cpu"].get<std::string>() << ", " << m["cores"].get<unsigned>() << " cores, "
       << m["pocl_version"].get<std::string>() << " (" << m["opencl_device"].get<std::string>() << "); "
       << m["date"].get<std::string>() << "; load average " << m["loadavg_start"].get<std::string>()
       << " at the start, " << m["loadavg_end"].get<std::string>()
       << " at the end (other work shared the two cores). brdfbake " << j["brdfbake_version"].get<std::string>()
       << ", `brdfbake-tradeoff" << (o.quick ? " --quick" : "") << "`; the whole run took "
       << fixed(j["seconds"].get<double>(), 0) << " s (references " << fixed(j["reference_seconds"].get<double>(), 1)
       << " s wall).\n\n";
    md << "Directional albedo E(mu), F = 1, phi = 0. Each row is one `compute_albedo` call over all the "
          "family's cells (16 replicas for the sampling methods; quadrature: n = sqrt(samples / 4) nodes per "
          "axis, n² points per azimuth piece (2 to 4 pieces here) for each of the n-, n/2- and n/4-node rules). **Time** is the kernel's device time (OpenCL "
          "event) per cell, the median of repeated runs after an untimed warm-up that builds the kernel; "
          "*wall* is the whole call per cell (buffers, host tables). **True error** is |value − reference|; "
          "the reference is the Gauss-Kronrod value of benchmarks/tradeoff_refs.h at tolerance "
       << sci(o.ref_tol_fine, 0) << ", its uncertainty the difference from the value at " << sci(o.ref_tol_coarse, 0)
       << " (at least " << sci(o.ref_unc_floor, 0)
       << "). **Dishonest**: cells whose true error, less the reference's uncertainty, exceeds 3× the "
          "reported estimate. Easy cells: alpha ≥ 0.1 and mu ≥ 0.3 (Blinn: alpha = sqrt(2/(n+2)); Oren-Nayar "
          "by mu alone); hard: the rest.\n\n";

    // The cells and their references.
    md << "## Cells and references\n\n";
    md << "| family | parameter | alpha | mu | class | reference | uncertainty | reference time (s) |\n";
    md << "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |\n";
    size_t dropped = 0;
    for (const auto& c : j["cells"]) {
        md << "| " << c["family"].get<std::string>() << " | " << c["param_name"].get<std::string>() << " = "
           << c["param"].get<double>() << " | " << fixed(c["alpha"].get<double>(), 4) << " | " << c["mu"].get<double>()
           << " | " << (c["easy"].get<bool>() ? "easy" : "hard") << " | " << fixed(c["reference"].get<double>(), 13)
           << " | " << sci(c["uncertainty"].get<double>()) << " | " << fixed(c["reference_seconds"].get<double>(), 2)
           << " |" << (c["certain"].get<bool>() ? "" : " **dropped: uncertain**") << "\n";
        dropped += !c["certain"].get<bool>();
    }
    md << "\n" << dropped << " cells dropped for an uncertain reference (uncertainty above "
       << sci(o.ref_unc_max, 0) << ").\n\n";

}

// The best run within each time budget.
void markdown_budgets(std::ostringstream& md, const json& j, const Options& o) {
    const json& runs = j["runs"];
    // Summary: the best run within a time budget.
    md << "## Best within a time budget\n\n";
    md << "The run with the smallest max true error over the class among runs whose kernel time per cell "
          "is within the budget (method, precision, samples per cell: max true error).\n\n";
    md << "| family | class | ≤ 0.1 ms/cell | ≤ 1 ms/cell | ≤ 10 ms/cell |\n| --- | --- | --- | --- | --- |\n";
    for (const Family& f : o.families)
        for (bool easy : {true, false}) {
            md << "| " << f.key << " | " << (easy ? "easy" : "hard");
            for (double budget : {1e-4, 1e-3, 1e-2}) {
                const json* b = best_within(runs, f.key, easy, budget);
                if (!b)
                    md << " | –";
                else
                    md << " | " << label_of(*b) << " " << (*b)["samples"].get<std::uint64_t>() << ": "
                       << err_text(class_stats(*b, easy).max_error, o.ref_unc_floor);
            }
            md << " |\n";
        }

}

// How often each method's error estimate is exceeded by the true error.
void markdown_honesty(std::ostringstream& md, const json& j, const Options& o) {
    const json& runs = j["runs"];
    // Honesty per method and precision, over every family.
    md << "\n## Honesty of the error estimates\n\n";
    md << "Cells (over all families and sample counts) whose true error exceeds 3× the estimate.\n\n";
    md << "| method | precision | dishonest / cells | fraction | worst true error / estimate |\n";
    md << "| --- | --- | ---: | ---: | --- |\n";
    for (Method me : o.methods)
        for (Precision p : o.precisions) {
            size_t n = 0, bad = 0;
            double worst = 0.0;
            std::string where;
            for (const auto& r : runs) {
                if (r["method"] != method_name(me) || r["precision"] != precision_name(p) || r.contains("failed"))
                    continue;
                for (const auto& c : r["cells"]) {
                    ++n;
                    bad += c["dishonest"].get<bool>();
                    const double ratio = c["true_error"].get<double>() / c["estimate"].get<double>();
                    if (c["dishonest"].get<bool>() && ratio > worst) {
                        worst = ratio;
                        where = c["spec"].get<std::string>() + ", mu = " + sci(c["mu"].get<double>(), 0) + ", " +
                                std::to_string(r["samples"].get<std::uint64_t>()) + " samples: " +
                                sci(c["true_error"].get<double>()) + " vs " + sci(c["estimate"].get<double>());
                    }
                }
            }
            md << "| " << method_name(me) << " | " << precision_name(p) << " | " << bad << " / " << n << " | "
               << fixed(n ? 100.0 * bad / n : 0.0, 2) << "% | " << (bad ? sci(worst) + "x at " + where : "–")
               << " |\n";
        }
    md << "\nThe same by samples per cell (dishonest / cells):\n\n| method | precision";
    for (std::uint64_t s : o.samples) md << " | " << s;
    md << " |\n| --- | ---";
    for (size_t k = 0; k < o.samples.size(); ++k) md << " | ---:";
    md << " |\n";
    for (Method me : o.methods)
        for (Precision p : o.precisions) {
            md << "| " << method_name(me) << " | " << precision_name(p);
            for (std::uint64_t s : o.samples) {
                size_t n = 0, bad = 0;
                for (const auto& r : runs)
                    if (r["method"] == method_name(me) && r["precision"] == precision_name(p) &&
                        r["samples"].get<std::uint64_t>() == s && !r.contains("failed"))
                        for (const auto& c : r["cells"]) {
                            ++n;
                            bad += c["dishonest"].get<bool>();
                        }
                md << " | " << bad << " / " << n;
            }
            md << " |\n";
        }

}

// The tolerance mode's runs.
void markdown_tolerance(std::ostringstream& md, const json& j, const Options& o) {
    // The tolerance mode.
    if (!j["tolerance_runs"].empty()) {
        md << "\n## `--tolerance` (auto: quadrature first, then importance sampling)\n\n";
        md << "Each cell alone through `compute_albedo_to_tolerance` (max " << o.max_samples
           << " samples per cell). *met*: true error within the tolerance; *by*: the method of the reported value.\n\n";
        md << "| family | precision | tolerance | cells met / run | failed (not certified) | by quadrature / importance "
              "| max true error | kernel time per cell: median, max (ms) |\n";
        md << "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
        for (const Family& f : o.families)
            for (const auto& pt : o.tolerances) {
                size_t n = 0, met = 0, failed = 0, quad = 0, imp = 0;
                double worst = 0.0;
                std::vector<double> times;
                for (const auto& t : j["tolerance_runs"]) {
                    if (t["family"] != f.key || t["precision"] != precision_name(pt.first) ||
                        t["tolerance"].get<double>() != pt.second)
                        continue;
                    ++n;
                    if (t.contains("failed")) {
                        ++failed;
                        continue;
                    }
                    met += t["met"].get<bool>();
                    (t["method"] == "quadrature" ? quad : imp)++;
                    worst = std::max(worst, t["true_error"].get<double>());
                    times.push_back(t["kernel_seconds"].get<double>() * 1e3);
                }
                md << "| " << f.key << " | " << precision_name(pt.first) << " | " << sci(pt.second, 0) << " | " << met
                   << " / " << n << " | " << failed << " | " << quad << " / " << imp << " | "
                   << err_text(worst, o.ref_unc_floor) << " | "
                   << (times.empty() ? "–"
                                     : fixed(median(times), 2) + ", " +
                                           fixed(*std::max_element(times.begin(), times.end()), 2))
                   << " |\n";
            }
        md << "\n";
        for (const auto& t : j["tolerance_runs"])
            if (t.contains("failed") || !t["met"].get<bool>())
                md << "- " << t["spec"].get<std::string>() << ", mu = " << t["mu"].get<double>() << ", "
                   << t["precision"].get<std::string>() << " tolerance " << sci(t["tolerance"].get<double>(), 0) << ": "
                   << (t.contains("failed") ? t["failed"].get<std::string>()
                                             : "true error " + sci(t["true_error"].get<double>()) + ", estimate " +
                                                   sci(t["estimate"].get<double>()))
                   << "\n";
    }

}

// Every run of every family.
void markdown_runs(std::ostringstream& md, const json& j, const Options& o) {
    const json& runs = j["runs"];
    // Every run.
    const double fl = o.ref_unc_floor;
    md << "\n## Every run\n\n";
    for (const Family& f : o.families) {
        md << "### " << f.label << " (`" << f.spec_format.substr(0, f.spec_format.find('%')) << "...`)\n\n";
        md << "| method | precision | samples | time/cell (ms) | wall/cell (ms) | easy: median | easy: max | hard: "
              "median | hard: max | dishonest |\n";
        md << "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
        for (const auto& r : runs) {
            if (r["family"] != f.key) continue;
            md << "| " << r["method"].get<std::string>() << " | " << r["precision"].get<std::string>() << " | "
               << r["samples"].get<std::uint64_t>() << " | ";
            if (r.contains("failed")) {
                md << "failed: " << r["failed"].get<std::string>() << " | | | | | | |\n";
                continue;
            }
            const ClassStats e = class_stats(r, true), h = class_stats(r, false);
            md << fixed(r["kernel_seconds_per_cell"].get<double>() * 1e3, 4) << " | "
               << fixed(r["wall_seconds_per_cell"].get<double>() * 1e3, 4) << " | " << err_text(e.median_error, fl)
               << " | " << err_text(e.max_error, fl) << " | " << err_text(h.median_error, fl) << " | "
               << err_text(h.max_error, fl) << " | "
               << e.dishonest + h.dishonest << " / " << e.cells + h.cells << " |\n";
        }
        md << "\n";
    }
}

std::string markdown(const json& j, const Options& o) {
    std::ostringstream md;
    markdown_head(md, j, o);
    markdown_budgets(md, j, o);
    markdown_honesty(md, j, o);
    markdown_tolerance(md, j, o);
    markdown_runs(md, j, o);
    return md.str();
}

// ------------------------------------------------------------------------------------------
// The figure: max true error against kernel time per cell, a panel per family and class.

void write_tradeoff_plot(const json& j, const Options& o, const std::string& path) {
    const std::map<std::string, std::string> colour = {
        {"importance", "b"}, {"qmc", "g"}, {"mc", "r"}, {"quadrature", "k"}};
    Figure fig;
    fig.columns = 2;
    fig.panel_width = 640;
    fig.panel_height = 470;
    const double floor = o.ref_unc_floor;  // errors the references cannot resolve are drawn here
    for (const Family& f : o.families)
        for (bool easy : {true, false}) {
            PlotSpec p;
            p.title = f.label + (easy ? ": easy cells" : ": hard cells");
            p.x.label = "log_{10} kernel seconds per cell";
            p.y.label = "log_{10} max true error";
            p.x.lo = -6.0;
            p.x.hi = 0.5;
            p.y.lo = -15.0;
            p.y.hi = 1.0;
            p.lines.push_back({'y', std::log10(floor), "reference resolution"});
            // One legend for the figure, where the hard panels leave room: fast and accurate.
            p.legend = !easy && fig.panels.size() == 1 ? LegendPlace::BottomLeft : LegendPlace::None;
            for (Method me : o.methods)
                for (Precision pr : o.precisions) {
                    Curve c;
                    c.label = std::string(method_name(me)) + " " + precision_name(pr);
                    c.style = colour.at(method_name(me)) + (pr == Precision::Float ? "-2o" : ";2s");
                    for (const auto& r : j["runs"]) {
                        if (r["family"] != f.key || r["method"] != method_name(me) ||
                            r["precision"] != precision_name(pr) || r.contains("failed"))
                            continue;
                        const ClassStats s = class_stats(r, easy);
                        if (s.cells == 0) continue;
                        c.x.push_back(std::log10(r["kernel_seconds_per_cell"].get<double>()));
                        c.y.push_back(std::log10(std::max(s.max_error, floor)));
                    }
                    if (!c.x.empty()) p.curves.push_back(c);
                }
            if (!p.curves.empty()) fig.panels.push_back(p);
        }
    write_figure(path, fig);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"brdfbake-tradeoff: error against time of every albedo method and precision (issue 7)"};
    ReportOptions report;
    std::string only;
    add_report_options(app, report, "a small grid, two sample counts, one run each (what CI runs)",
                       "file name stem (default: tradeoff-<machine>, -quick with --quick)",
                       "also draw max true error against time per cell (.png or .svg)");
    app.add_option("--families", only, "comma-separated family keys to run (ggx, beckmann, ts-ggx, ts-blinn, oren-nayar)");
    bool dielectric_only = false;
    app.add_flag("--dielectric-only", dielectric_only,
                 "only the rough dielectric rows (R and T per method), into tradeoff-dielectric-<machine>");
    return parse_and_run(app, argc, argv, "brdfbake-tradeoff", [&] {
        const bool quick = report.quick;
        std::string name = report.name;
        const std::string& out_dir = report.out_dir;
        const std::string& plot = report.plot;
        const double t_start = now();
        Options o = quick ? quick_options() : full_options();
        if (!only.empty()) {
            std::vector<Family> keep;
            std::stringstream ss(only);
            for (std::string k; std::getline(ss, k, ',');) {
                auto it = std::find_if(o.families.begin(), o.families.end(), [&](const Family& f) { return f.key == k; });
                if (it == o.families.end()) throw Error("unknown family '" + k + "'");
                keep.push_back(*it);
            }
            o.families = keep;
        }
        if (name.empty())
            name = std::string(dielectric_only ? "tradeoff-dielectric-" : "tradeoff-") + bench_machine_name() +
                   (quick ? "-quick" : "");

        json j;
        j["name"] = name;
        j["mode"] = quick ? "quick" : "full";
        j["brdfbake_version"] = BRDFBAKE_VERSION;
        Engine engine(report.device);
        const DeviceInfo& dev = engine.device();
        j["machine"] = {{"cpu", bench_cpu_model()},
                        {"cores", std::thread::hardware_concurrency()},
                        {"opencl_device", dev.name},
                        {"pocl_version", dev.driver},
                        {"date", utc_date()},
                        {"loadavg_start", bench_loadavg()}};
        if (!dev.fp64) o.precisions = {Precision::Float};
        j["machine"]["name"] = bench_machine_name();
        if (dielectric_only) {
            dielectric_study(engine, o, j);
            j["machine"]["loadavg_end"] = bench_loadavg();
            j["seconds"] = now() - t_start;
            const json& m = j["machine"];
            std::ostringstream md;
            md << "# brdfbake speed against accuracy, the rough dielectric: " << name << "\n\nMachine: "
               << m["name"].get<std::string>() << " (" << m["cpu"].get<std::string>() << ", "
               << m["cores"].get<unsigned>() << " cores, " << m["pocl_version"].get<std::string>() << "); "
               << m["date"].get<std::string>() << "; load average " << m["loadavg_start"].get<std::string>()
               << " at the start, " << m["loadavg_end"].get<std::string>() << " at the end. brdfbake "
               << j["brdfbake_version"].get<std::string>() << ", `brdfbake-tradeoff --dielectric-only"
               << (quick ? " --quick" : "") << "`; " << fixed(j["seconds"].get<double>(), 0) << " s.\n\n"
               << dielectric_markdown(j["dielectric"]);
            std::filesystem::create_directories(out_dir);
            write_file_atomically(out_dir + "/" + name + ".json", json_lines(j) + "\n");
            write_file_atomically(out_dir + "/" + name + ".md", md.str());
            std::cerr << "brdfbake-tradeoff: wrote " << out_dir << "/" << name << ".json and .md\n";
            return 0;
        }

        // References.
        std::vector<Cell> cells = make_cells(o);
        std::cerr << "brdfbake-tradeoff: " << cells.size() << " references at tolerances " << o.ref_tol_coarse
                  << " and " << o.ref_tol_fine << "\n";
        const double t_ref = now();
        compute_references(o, cells);
        j["reference_seconds"] = now() - t_ref;
        j["reference_tolerances"] = {o.ref_tol_coarse, o.ref_tol_fine};
        j["cells"] = json::array();
        for (const Cell& c : cells)
            j["cells"].push_back({{"family", o.families[c.family].key}, {"spec", c.spec},
                                  {"param_name", o.families[c.family].param_name}, {"param", c.param},
                                  {"alpha", c.alpha}, {"mu", c.mu}, {"easy", c.easy}, {"reference", c.ref},
                                  {"reference_coarse", c.ref_coarse}, {"uncertainty", c.unc},
                                  {"reference_seconds", c.ref_seconds}, {"certain", c.certain}});
        std::cerr << "brdfbake-tradeoff: references took " << j["reference_seconds"].get<double>() << " s\n";

        // Fixed-sample runs: per family, method and precision an untimed warm-up (the build),
        // then every sample count.
        j["runs"] = json::array();
        for (size_t f = 0; f < o.families.size(); ++f) {
            std::vector<const Cell*> fc;
            for (const Cell& c : cells)
                if (c.family == f && c.certain) fc.push_back(&c);
            if (fc.empty()) continue;
            for (Method me : o.methods)
                for (Precision p : o.precisions) {
                    try {
                        compute_albedo(engine, request_for(o.families[f], fc, me, p, o.samples.front()));
                    } catch (const Error&) {
                        // reported by the timed run
                    }
                    for (std::uint64_t s : o.samples) {
                        j["runs"].push_back(timed_run(engine, o, o.families[f], fc, me, p, s));
                        const json& r = j["runs"].back();
                        std::cerr << "  " << o.families[f].key << " " << method_name(me) << " " << precision_name(p)
                                  << " " << s << ": "
                                  << (r.contains("failed") ? "failed: " + r["failed"].get<std::string>()
                                                           : sci(r["kernel_seconds_per_cell"].get<double>() * 1e3, 2) +
                                                                 " ms/cell")
                                  << "\n";
                    }
                }
        }

        // The tolerance mode.
        j["tolerance_runs"] = json::array();
        for (const auto& pt : o.tolerances) {
            if (pt.first == Precision::Double && !dev.fp64) continue;
            for (const Cell& c : cells)
                if (c.certain)
                    j["tolerance_runs"].push_back(tolerance_run(engine, o, o.families[c.family], c, pt.first, pt.second));
            std::cerr << "  tolerance " << pt.second << " " << precision_name(pt.first) << " done\n";
        }

        dielectric_study(engine, o, j);

        j["machine"]["loadavg_end"] = bench_loadavg();
        j["seconds"] = now() - t_start;
        const std::string md = markdown(j, o) + "\n" + dielectric_markdown(j["dielectric"]);
        std::filesystem::create_directories(out_dir);
        write_file_atomically(out_dir + "/" + name + ".json", json_lines(j) + "\n");
        write_file_atomically(out_dir + "/" + name + ".md", md);
        if (!plot.empty()) write_tradeoff_plot(j, o, plot);
        std::cerr << "brdfbake-tradeoff: wrote " << out_dir << "/" << name << ".json and .md in "
                  << fixed(j["seconds"].get<double>(), 1) << " s\n";
        // A dishonest estimate (true error beyond 3x the estimate) fails the run (and CI's
        // tradeoff_quick), after the report that shows it is written.
        int dishonest = 0;
        for (const auto& r : j["runs"])
            for (const auto& c : r.value("cells", json::array())) dishonest += c.value("dishonest", false);
        if (j["dielectric"].is_object())
            for (const auto& r : j["dielectric"].value("runs", json::array())) dishonest += r.value("dishonest_channels", 0);
        if (dishonest > 0)
            std::cerr << "brdfbake-tradeoff: " << dishonest << " dishonest estimates (true error beyond 3x the estimate)\n";
        return dishonest > 0 ? 1 : 0;
    });
}

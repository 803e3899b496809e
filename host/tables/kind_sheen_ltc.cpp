// The volumetric sheen of Zeltner, Burley and Chiang 2022 ([ZBC22], "Practical Multiple-Scattering
// Sheen Using Linearly Transformed Cosines") as the LTC table renderers ship (Blender Cycles'
// table_sheen_ltc): per texel (mu, roughness r), the reflectance R of the fiber SGGX layer
// (brdf/sheen_volume.h, by random walks on the device: integrate/sheen_volume.h) and the LTC whose
// inverse matrix is M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]] in the frame where the viewer is at
// (sin theta_o, 0, cos theta_o) ([ZBC22] eq. 1: f cos(theta_i) = R D_o(M^-1 w / |M^-1 w|) |det M^-1| /
// |M^-1 w|^3, D_o = max(0, z)/pi, Heitz et al. 2016 eq. 1 and sec. 3.1), fitted by the fitting
// layer's Nelder-Mead (fit/nelder_mead.h) to the layer's reflected lobe: the first order in closed
// form (sheen_single_density) plus a histogram of the exits through the top after two or more
// scatterings. Channels a, b, R, distance (the L1 distance between the normalised lobe and the LTC
// at the fit's points), distance_error (the histogram's noise floor in it) and error (R's).
// --estimator cycles: the paper's precomputation and fit instead (sheen_bounces, paper_distance), the
// ones Cycles' table was made by (benchmarks/results/sheen-ltc-amd-epyc-2c.md, session 5).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/sheen_volume.h"
#include "brdfbake/error.h"
#include "brdfbake/progress.h"
#include "fit/nelder_mead.h"
#include "integrate/sheen_volume.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

/// [ZBC22]'s floors: mu and roughness at least 0.01 (sigma = 1e-4), the layer's walks below that
/// never turn back.
constexpr double kSheenFloor = 0.01;
/// The layer's roughness r of a texel is sqrt of the sheen axis' alpha: sigma = r^2 = alpha, so
/// that --alpha-map roughness puts r (Cycles' roughness) on the axis.
/// The higher orders' top exits a texel's histogram should be worth: a texel worth fewer, whose
/// higher orders are at least kMinShare of its R, is walked again with up to kRewalk times the walks
/// when that reaches kMinExits (walk_again; the first order is in closed form: a texel is fitted
/// whatever it reflects).
/// A histogram's worth in exits is (its integral / its standard error)^2 (higher_order_exits): the
/// count of the exits for analog counts, more for the next-flight tallies.
constexpr double kMinExits = 1000;
constexpr double kMinShare = 0.05;
constexpr std::uint64_t kRewalk = 16;
/// ... and when its walks are cheap: at most kMaxFlights free flights a walk. The grazing views of the
/// smoothest rows take ~1/mu flights a walk (102 at mu = roughness = 0.01, 4.3e8 flights for 16 times
/// 2^18 walks): the table that walked it again took 166 s of CPU, 135 s without it
/// (benchmarks/results/sheen-ltc-amd-epyc-2c.md, session 6).
constexpr double kMaxFlights = 10.0;
/// What the higher orders' histogram of a texel is worth in exits: (its integral / its standard
/// error)^2, the bins' errors (3 standard errors of the replicas) summed in quadrature.
double higher_order_exits(const SheenVolumeValue& v) {
    double total = 0.0, var = 0.0;
    for (size_t b = 0; b < v.lobe.size(); ++b) {
        const double mass = 2.0 * SheenLobeBins::solid_angle(int(b) / SheenLobeBins::phi());
        total += mass * v.lobe[b];
        var += std::pow(mass * v.lobe_error[b] / 3.0, 2);
    }
    return var > 0.0 ? total * total / var : 0.0;
}

/// Sub-points per bin side for the LTC's bin averages.
constexpr int kSub = 3;

/// The walks' scattering limit: --estimator cycles, the paper's precomputation (a negative limit:
/// brdf/sheen_volume.h), which Cycles' table_sheen_ltc was fitted to; otherwise to the end.
int sheen_bounces(const LutRequest& r) {
    return r.estimator == "cycles" ? -BB_SHEEN_VOLUME_PAPER_BOUNCES : BB_SHEEN_VOLUME_DEFAULT_BOUNCES;
}

std::vector<std::string> sheen_ltc_programs(const LutRequest&) { return {"sheen_volume"}; }

void validate_sheen_ltc(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    if (m.id != BB_MODEL_SHEEN)
        throw Error("the sheen-ltc table sweeps the roughness of the volumetric sheen layer: --model sheen (its alpha "
                    "is the layer's sigma = roughness^2), not '" + m.name + "'");
    if (r.tolerance.tolerance > 0.0)
        throw Error("the sheen-ltc table is a random-walk simulation of --samples walks a texel (default 2^18): drop "
                    "--tolerance");
    if (r.alpha_hi > 1.0) throw Error("--alpha-range of a sheen-ltc table must lie within [0, 1]");
    if (f.kind != BB_FRESNEL_NONE) throw Error("the sheen layer has no Fresnel term: drop --fresnel");
}

/// The LTC density of M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]] at the unit direction w.
double ltc_d(double a, double b, double x, double y, double z) {
    const double u = a * x + b * z, v = a * y;
    const double n = std::sqrt(u * u + v * v + z * z);
    return std::max(0.0, z / n) / M_PI * a * a / (n * n * n);
}

/// The sub-points of every bin (SheenLobeBins, one side of phi = 0), kSub x kSub each, with their
/// weights sin(theta) normalised per bin: computed once.
struct SubPoints {
    std::vector<std::array<double, 4>> p;  // x, y, z, weight; bin k's points at [k kSub^2, (k + 1) kSub^2)
};
const SubPoints& sub_points() {
    static const SubPoints pts = [] {
        SubPoints s;
        const int nt = SheenLobeBins::theta(), np = SheenLobeBins::phi();
        const double dt = 0.5 * M_PI / nt, dp = M_PI / np;
        for (int i = 0; i < nt; ++i)
            for (int j = 0; j < np; ++j) {
                const size_t first = s.p.size();
                double w = 0.0;
                for (int si = 0; si < kSub; ++si)
                    for (int sj = 0; sj < kSub; ++sj) {
                        const double th = (i + (si + 0.5) / kSub) * dt, ph = (j + (sj + 0.5) / kSub) * dp;
                        const double st = std::sin(th);
                        s.p.push_back({st * std::cos(ph), st * std::sin(ph), std::cos(th), st});
                        w += st;
                    }
                for (size_t k = first; k < s.p.size(); ++k) s.p[k][3] /= w;
            }
        return s;
    }();
    return pts;
}

/// The solid angle of sub-point k (both sides of phi = 0): its bin's times its weight.
double sub_solid_angle(size_t k) {
    const int bin = int(k / (kSub * kSub));
    return 2.0 * SheenLobeBins::solid_angle(bin / SheenLobeBins::phi()) * sub_points().p[k][3];
}

/// A texel's lobe normalised by its integral, at the sub-points: the first order in closed form
/// (sheen_single_density) plus the walks' histogram of the higher orders (constant over a bin).
/// Empty when nothing is reflected; `total` the integral before normalising.
std::vector<double> texel_target(const SheenVolumeCell& cell, const SheenVolumeValue& v, double& total) {
    const SubPoints& s = sub_points();
    std::vector<double> t(s.p.size());
    total = 0.0;
    for (size_t k = 0; k < s.p.size(); ++k) {
        const auto& q = s.p[k];
        t[k] = sheen_single_density(cell.mu, cell.alpha, q[0], q[1], q[2]) + v.lobe[k / (kSub * kSub)];
        total += sub_solid_angle(k) * t[k];
    }
    if (!(total > 0.0) || !std::isfinite(total)) return {};
    for (double& x : t) x /= total;
    return t;
}

/// integral over the upper hemisphere of |p - D| at the sub-points: p the normalised lobe.
double point_distance(const std::vector<double>& target, double a, double b) {
    const SubPoints& s = sub_points();
    double sum = 0.0;
    for (size_t k = 0; k < s.p.size(); ++k) {
        const auto& q = s.p[k];
        sum += sub_solid_angle(k) * std::abs(target[k] - ltc_d(a, b, q[0], q[1], q[2]));
    }
    return sum;
}

/// The paper's objective (--estimator cycles; Zeltner et al.'s public fitting code, which made
/// Cycles' table): the lobe tabulated in kPaperBins x kPaperBins bins of (theta, |phi|) as a
/// histogram (bin averages), the LTC taken at the bins' centres, summed |D - lobe|^3 (the paper's
/// L3 of R D against the lobe, over R^3: the same minimum, scale-free for the simplex's tolerance).
constexpr int kPaperBins = 32;
/// The paper's fit skips texels reflecting less than this (Cycles holds A = B = 0 there); here they
/// hold the cosine as the unfitted texels do (its L3 at R ~ 0 drives b off to -20 and beyond).
constexpr double kPaperMinR = 3e-6;

/// The paper's bins' values of a texel's normalised lobe: its histogram weighs each exit by
/// 1/sin(theta), so a bin holds the lobe's plain average over the bin's (theta, phi) rectangle, and
/// its first theta row is averaged over phi. Here the first order by kSub x kSub sub-points a bin,
/// the higher orders' histogram bin (SheenLobeBins) each sub-point falls in.
std::vector<double> paper_target(const SheenVolumeCell& cell, const SheenVolumeValue& v, double total) {
    std::vector<double> t(kPaperBins * kPaperBins, 0.0);
    const double dt = 0.5 * M_PI / kPaperBins, dp = M_PI / kPaperBins;
    for (int i = 0; i < kPaperBins; ++i)
        for (int j = 0; j < kPaperBins; ++j) {
            double sum = 0.0;
            for (int si = 0; si < kSub; ++si)
                for (int sj = 0; sj < kSub; ++sj) {
                    const double th = (i + (si + 0.5) / kSub) * dt, ph = (j + (sj + 0.5) / kSub) * dp;
                    const double st = std::sin(th);
                    const int bt = std::min(int(th / (0.5 * M_PI) * SheenLobeBins::theta()), SheenLobeBins::theta() - 1);
                    const int bp = std::min(int(ph / M_PI * SheenLobeBins::phi()), SheenLobeBins::phi() - 1);
                    sum += sheen_single_density(cell.mu, cell.alpha, st * std::cos(ph), st * std::sin(ph), std::cos(th)) +
                           v.lobe[bt * SheenLobeBins::phi() + bp];
                }
            t[i * kPaperBins + j] = sum / (kSub * kSub) / total;
        }
    double row0 = 0.0;
    for (int j = 0; j < kPaperBins; ++j) row0 += t[j] / kPaperBins;
    std::fill(t.begin(), t.begin() + kPaperBins, row0);
    return t;
}

/// The paper's objective at (a, b) for a target of paper_target.
double paper_distance(const std::vector<double>& target, double a, double b) {
    const double dt = 0.5 * M_PI / kPaperBins, dp = M_PI / kPaperBins;
    double sum = 0.0;
    for (int i = 0; i < kPaperBins; ++i)
        for (int j = 0; j < kPaperBins; ++j) {
            const double th = (i + 0.5) * dt, ph = (j + 0.5) * dp, st = std::sin(th);
            const double d = ltc_d(a, b, st * std::cos(ph), st * std::sin(ph), std::cos(th));
            sum += std::pow(std::abs(d - target[i * kPaperBins + j]), 3.0);
        }
    return sum;
}

struct TexelFit {
    double a = 1.0, b = 0.0, distance = 0.0, distance_error = 0.0;
    bool fitted = false;
};

/// The histogram's noise floor in a texel's distance: where the lobe equals D, a bin's |p - D|
/// averages sqrt(2/pi) of its standard error (lobe_error holds 3 of them); summed over the bins,
/// relative to the lobe's integral `total` (the first order, in closed form, adds no noise).
double noise_floor(const SheenVolumeValue& v, double total) {
    double sum = 0.0;
    for (size_t b = 0; b < v.lobe.size(); ++b)
        sum += 2.0 * SheenLobeBins::solid_angle(int(b) / SheenLobeBins::phi()) * std::sqrt(2.0 / M_PI) *
               v.lobe_error[b] / 3.0;
    return sum / total;
}

/// Fits the texels row by row from rough to smooth, each row's texels started from the row fitted
/// before (as [ZBC22]'s fit runs from high to low roughness), a row's texels in one batch.
std::vector<TexelFit> fit_texels(const MuAlphaGrid& g, const std::vector<SheenVolumeCell>& cells,
                                 const SheenVolumeResult& walks, bool paper) {
    const size_t w = g.table.x.parameter.size(), h = g.table.y.parameter.size();
    std::vector<size_t> order(h);
    for (size_t j = 0; j < h; ++j) order[j] = j;
    const std::vector<double>& rough = g.table.y.parameter;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return rough[x] > rough[y]; });
    std::vector<TexelFit> fits(w * h);
    std::vector<std::vector<double>> start(w, std::vector<double>{0.0, 0.0});  // (ln a, b)
    fit::NelderMeadOptions options;
    options.steps = {0.2, 0.05};
    options.max_evaluations = 400;
    options.value_tolerance = 1e-6;
    options.size_tolerance = 1e-5;
    ProgressStage stage("LTC fit of the sheen layer's lobes", h, "rows", "fitted");
    for (size_t k = 0; k < h; ++k) {
        const size_t j = order[k];
        std::vector<size_t> texels;
        std::vector<std::vector<double>> starts, targets, paper_targets;
        std::vector<double> totals;
        for (size_t i = 0; i < w; ++i) {
            double total = 0.0;
            if (paper && walks.values[j * w + i].reflectance.value < kPaperMinR) continue;
            std::vector<double> t = texel_target(cells[j * w + i], walks.values[j * w + i], total);
            if (t.empty()) continue;
            texels.push_back(j * w + i);
            totals.push_back(total);
            starts.push_back(start[i]);
            if (paper) paper_targets.push_back(paper_target(cells[j * w + i], walks.values[j * w + i], total));
            targets.push_back(std::move(t));
        }
        const auto objective = [&](const std::vector<size_t>& problem, const std::vector<std::vector<double>>& x) {
            std::vector<double> out(x.size());
            for (size_t p = 0; p < x.size(); ++p)
                out[p] = paper ? paper_distance(paper_targets[problem[p]], std::exp(x[p][0]), x[p][1])
                               : point_distance(targets[problem[p]], std::exp(x[p][0]), x[p][1]);
            return out;
        };
        const std::vector<fit::Minimum> mins = fit::minimize_batch(starts, options, objective);
        for (size_t t = 0; t < texels.size(); ++t) {
            const size_t c = texels[t];
            TexelFit& f = fits[c];
            f.a = double(float(std::exp(mins[t].x[0])));  // as written (float32)
            f.b = double(float(mins[t].x[1]));
            f.distance = point_distance(targets[t], f.a, f.b);
            f.distance_error = noise_floor(walks.values[c], totals[t]);
            f.fitted = true;
            start[c % w] = mins[t].x;
        }
        stage.update(k + 1);
    }
    return fits;
}

/// Walks again the texels whose higher orders' histogram is worth fewer than kMinExits exits
/// (smooth layers seen from above), when kRewalk times the walks gives them kMinExits, those orders
/// matter (kMinShare of R) and their walks are cheap (kMaxFlights), each with the least power of two
/// times the walks (2 to kRewalk) that does; the new walks replace the first. Returns how many.
/// The new walks draw from their own Philox key (the first pass's seed moved by the factor k): a
/// texel's streams depend on its content and walk index only, so with the same key its first walks
/// would come back as 1/k of the new ones, and those were chosen for being worth few exits (review6
/// measured the same-key re-walk 2.7% low in the higher orders at k = 2, a fresh key unbiased).
/// (Walking again those that reflect almost nothing, the smoothest row at grazing views, where a
/// walk scatters ~1/mu times before it crosses, took hours.)
size_t walk_again(Engine& engine, const SheenVolumeRequest& req, SheenVolumeResult& walks) {
    std::map<std::uint64_t, std::pair<SheenVolumeRequest, std::vector<size_t>>> groups;  // by the walks' factor
    size_t count = 0;
    for (size_t c = 0; c < req.cells.size(); ++c) {
        const SheenVolumeValue& v = walks.values[c];
        const double higher = v.reflectance.value - v.single.value, exits = higher_order_exits(v);
        if (!(exits < kMinExits && exits * double(kRewalk) >= kMinExits && higher >= kMinShare * v.reflectance.value &&
              v.flights <= kMaxFlights))
            continue;
        std::uint64_t k = 2;
        while (exits * double(k) < kMinExits) k *= 2;
        auto& group = groups[k];
        if (group.second.empty()) {
            group.first = req;
            group.first.cells.clear();
            group.first.walks = req.walks * k;
            group.first.seed = req.seed + 0x9E3779B97F4A7C15ull * k;  // independent of the first pass (above)
        }
        group.first.cells.push_back(req.cells[c]);
        group.second.push_back(c);
        ++count;
    }
    for (const auto& [k, group] : groups) {
        const SheenVolumeResult more = sheen_volume_walks(engine, group.first);
        for (size_t i = 0; i < group.second.size(); ++i) walks.values[group.second[i]] = more.values[i];
    }
    return count;
}

Table compute_sheen_ltc(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.quantity = "the volumetric sheen of Zeltner, Burley and Chiang 2022: reflectance R of a unit layer of fiber "
                 "SGGX microflakes (sigma = roughness^2, albedo 1) and the LTC M^-1 = [[a, 0, b], [0, a, 0], [0, 0, "
                 "1]] of its lobe, viewer at (sin theta_o, 0, cos theta_o)";
    SheenVolumeRequest req;
    req.walks = r.samples;
    req.precision = r.precision;
    req.lobe = true;
    const size_t w = t.x.parameter.size();
    for (size_t c = 0; c < g.cells.size(); ++c)
        req.cells.push_back({std::max(g.cells[c].mu, kSheenFloor), std::max(std::sqrt(t.y.parameter[c / w]), kSheenFloor),
                             sheen_bounces(r)});
    progress_next_pass();
    SheenVolumeResult walks = sheen_volume_walks(engine, req);
    const size_t rewalked = walk_again(engine, req, walks);
    const std::vector<TexelFit> fits = fit_texels(g, req.cells, walks, r.estimator == "cycles");
    const size_t n = g.cells.size();
    t.channels = {"a", "b", "R", "distance", "distance_error"};
    t.values.assign(t.channels.size(), std::vector<double>(n));
    t.error.assign(n, 0.0);
    std::vector<double> distance, distance_error, cutoff;
    size_t unfitted = 0;
    for (size_t c = 0; c < n; ++c) {
        const SheenVolumeValue& v = walks.values[c];
        const TexelFit& ft = fits[c];
        t.values[0][c] = ft.a;
        t.values[1][c] = ft.b;
        t.values[2][c] = v.reflectance.value;
        t.values[3][c] = ft.distance;
        t.values[4][c] = ft.distance_error;
        t.error[c] = v.reflectance.error;
        cutoff.push_back(v.cutoff.value);
        if (ft.fitted) {
            distance.push_back(ft.distance);
            distance_error.push_back(ft.distance_error);
        } else {
            ++unfitted;
        }
    }
    describe(t, r, m, f.canonical, walks.method, walks.walks_per_cell, g.clamped);
    t.attributes["model"] = table_kind(TableKindId::SheenLtc).table_model;
    t.attributes["floors"] = "mu and roughness below 0.01 are computed at 0.01 (Zeltner et al. 2022's fit)";
    t.attributes["distance"] = "integral over the upper hemisphere of |lobe / R - D_ltc| at " +
                               std::to_string(kSub) + " x " + std::to_string(kSub) + " points in each of " +
                               std::to_string(SheenLobeBins::theta()) + " x " + std::to_string(SheenLobeBins::phi()) +
                               " bins (theta, |phi|); the first order in closed form, the higher orders the walks' "
                               "histogram: " + min_median_max_text(distance);
    t.attributes["error_channel"] = "R's error: 3 standard errors of the replicas (--samples walks a texel; " +
                                    std::to_string(rewalked) + " texels whose higher orders' histogram was "
                                    "worth " + std::to_string(int(kMinExits) / int(kRewalk)) + " to " +
                                    std::to_string(int(kMinExits)) + " exits, at most " +
                                    std::to_string(int(kMaxFlights)) + " flights a walk, walked again with 2 to " +
                                    std::to_string(kRewalk) + " times as many, the least power of two worth " +
                                    std::to_string(int(kMinExits)) + ")";
    t.attributes["distance_error"] = "the higher orders' histogram's noise floor in the distance: sqrt(2/pi) "
                                     "standard errors per bin, summed: " + min_median_max_text(distance_error);
    t.attributes["unfitted"] = std::to_string(unfitted) + " texels that reflect nothing hold the cosine (a = 1, b = 0)";
    t.attributes["cutoff"] =
        r.estimator == "cycles"
            ? "--estimator cycles (the paper's precomputation, as Cycles' table): walks stopped after " +
                  std::to_string(BB_SHEEN_VOLUME_PAPER_BOUNCES) +
                  " scatterings, counted as reflected when their direction points up: share " +
                  min_median_max_text(cutoff)
            : "share of walks still inside after " + std::to_string(BB_SHEEN_VOLUME_DEFAULT_BOUNCES) +
                  " scatterings: " + min_median_max_text(cutoff);
    return std::move(g.table);
}

}  // namespace

TableKind sheen_ltc_kind() {
    TableKind k(TableKindId::SheenLtc, "sheen-ltc",
                "the volumetric sheen of Zeltner et al. 2022 per (mu, roughness): its LTC a, b (M^-1 = [[a,0,b],[0,a,0],"
                "[0,0,1]]), reflectance R and the fit's L1 distance (2D, random walks)",
                sheen_ltc_programs, compute_sheen_ltc);
    k.plan_fresnel = "none (the sheen layer has no Fresnel term)";
    k.validate = validate_sheen_ltc;
    k.value_channels = [](const LutRequest&) { return std::vector<std::string>{"a", "b", "R", "distance", "distance_error"}; };
    k.required_model = "sheen";
    k.table_model = "sheen-volume: the fiber SGGX layer of Zeltner et al. 2022, sigma = the axis' alpha (roughness^2 "
                    "with --alpha-map roughness)";
    k.lobe_requirement = "the sheen-ltc table needs a sheen lobe (model sheen, KHR_materials_sheen)";
    k.simulated = true;
    k.cycles_estimator = true;  // --estimator cycles: the paper's 16-scattering walks (sheen_bounces)
    // A walk costs several albedo samples (its flights); not measured for the planner yet.
    k.sample_cost = 8.0;
    return k;
}

}  // namespace tables
}  // namespace brdfbake

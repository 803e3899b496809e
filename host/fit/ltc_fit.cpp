#include "fit/ltc_fit.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/cancel.h"
#include "brdfbake/error.h"
#include "engine/device_buffer.h"
#include "integrate/launch.h"

namespace brdfbake {
namespace fit {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// A neighbour's fit restarts a cell's minimisation when it is this much (relative) better.
constexpr double kPolishGain = 1e-3;
/// The smallest distance the relative objective divides by.
constexpr double kValueFloor = 1e-7;

using Mat3 = std::array<double, 9>;  // row-major


/// M^-1 of the isotropic form (the y row decouples) and |det M^-1|.
Mat3 inverse(const LtcMatrix& m, double& abs_det_inverse) {
    const double det_xz = m.m00 * m.m22 - m.m02 * m.m20;
    abs_det_inverse = 1.0 / std::abs(det_xz * m.m11);
    return {m.m22 / det_xz, 0, -m.m02 / det_xz, 0, 1.0 / m.m11, 0, -m.m20 / det_xz, 0, m.m00 / det_xz};
}

/// A row's fixed lobe points on the device (kernels/ltc.cl, ltc_lobe_points) and on the host.
struct LobePoints {
    int side = 0;
    cl::Buffer buffer;
    std::vector<double> host;  // BB_LTC_POINT_VALUES per point, side^2 points per cell
};

struct CellSummary {
    double albedo = 0;         // mean weight: E on these points
    double average_theta = 0;  // the lobe's average direction (sin t, 0, cos t)
    double width_x = 1, width_y = 1;  // E_p[|x'/z'|], E_p[|y'/z'|] about that direction (below)
};

cl::Program& ltc_program(Engine& engine, const ModelConfig& model, Precision precision) {
    BuildRequest build;
    build.kernel_file = "ltc.cl";
    build.precision = precision;
    build.model = model.id;
    build.fresnel = BB_FRESNEL_NONE;
    return engine.program(build);
}

void run_range(Engine& engine, cl::Kernel& kernel, size_t n) {
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((n + kLocalSize - 1) / kLocalSize * kLocalSize),
                                        cl::NDRange(kLocalSize));
}

/// The graded nodes of the lobe points' u1 (kernels/ltc.cl, ltc_lobe_points): per column i of a
/// side x side grid, u1 = 1 - (1 - s)^grade at the midpoint s = (i + 1/2)/side, and the weight
/// side ((1 - s_lo)^grade - (1 - s_hi)^grade) of its cell's measure in u1 (s_lo = i/side, s_hi =
/// (i + 1)/side): the samplers send the lobe's tail to u1 near 1. Computed here in double, once,
/// so that the points' bits do not depend on how the device compiles powers (PoCL's pown went
/// through exp and log; a multiplication's rounding followed the build).
std::vector<double> graded_nodes(int side, int grade) {
    std::vector<double> nodes;
    for (int i = 0; i < side; ++i) {
        const double lo = double(i) / side, hi = double(i + 1) / side, mid = (i + 0.5) / side;
        nodes.push_back(1.0 - std::pow(1.0 - mid, grade));
        nodes.push_back((std::pow(1.0 - lo, grade) - std::pow(1.0 - hi, grade)) * side);
    }
    return nodes;
}

LobePoints lobe_points(Engine& engine, const ModelConfig& model, Precision precision, const std::vector<LtcCell>& cells,
                       int side, int grade) {
    RealBuffers bufs(engine, precision);
    std::vector<double> mu, params;
    for (const LtcCell& c : cells) {
        mu.push_back(c.mu);
        params.insert(params.end(), c.params.begin(), c.params.end());
    }
    const FresnelConfig none = resolve_fresnel("none");
    cl::Buffer b_mu = bufs.input(mu), b_p = bufs.input(params);
    cl::Buffer b_fp = bufs.input({none.params.begin(), none.params.end()});
    cl::Buffer b_data = model_data_buffer(bufs, model.id);
    cl::Buffer b_nodes = bufs.input(graded_nodes(side, grade));
    const size_t n = cells.size() * size_t(side) * size_t(side);
    LobePoints out;
    out.side = side;
    out.buffer = bufs.output(n * BB_LTC_POINT_VALUES);
    cl::Kernel k(ltc_program(engine, model, precision), BB_ENTRY_NAME(BB_ENTRY_LTC_LOBE_POINTS));
    set_args(k, 0, b_mu, b_p, b_fp, b_data, cl_uint(cells.size()), cl_uint(side), b_nodes, out.buffer);
    run_range(engine, k, n);
    out.host = bufs.read(out.buffer, n * BB_LTC_POINT_VALUES);
    for (double v : out.host)
        if (!std::isfinite(v)) throw Error("the lobe's sample points hold a non-finite value: the LTC fit stops");
    return out;
}

CellSummary summarise(const LobePoints& pts, size_t cell) {
    const size_t per = size_t(pts.side) * size_t(pts.side);
    const double* p = pts.host.data() + cell * per * BB_LTC_POINT_VALUES;
    double w = 0, ax = 0, az = 0;
    for (size_t k = 0; k < per; ++k, p += BB_LTC_POINT_VALUES) {
        w += p[3];
        ax += p[3] * p[0];
        az += p[3] * p[2];
    }
    CellSummary s;
    s.albedo = w / double(per);
    s.average_theta = (ax == 0 && az == 0) ? 0.0 : std::atan2(ax, az);
    // The lobe's widths about its average direction: for the LTC diag(a, c, 1) of the clamped
    // cosine, x'/z' = a tan(theta_c) cos(phi_c), and E[|tan theta_c cos phi_c|] = 1 under the
    // cosine (2/pi times integral of tan theta cos theta sin theta over theta, pi/2): E_p[|x'/z'|]
    // is a, E_p[|y'/z'|] is c, a start near the fit for narrow lobes (directions within 0.05 of
    // the frame's horizon are left out: their ratio is unbounded).
    const double ct = std::cos(s.average_theta), st = std::sin(s.average_theta);
    double wx = 0, wy = 0, wn = 0;
    p = pts.host.data() + cell * per * BB_LTC_POINT_VALUES;
    for (size_t k = 0; k < per; ++k, p += BB_LTC_POINT_VALUES) {
        const double xp = ct * p[0] - st * p[2], zp = st * p[0] + ct * p[2];
        if (p[3] <= 0 || zp < 0.05) continue;
        wx += p[3] * std::abs(xp) / zp;
        wy += p[3] * std::abs(p[1]) / zp;
        wn += p[3];
    }
    if (wn > 0 && wx > 0 && wy > 0) {
        s.width_x = wx / wn;
        s.width_y = wy / wn;
    }
    return s;
}

/// The L1 distances of candidate matrices, candidate i fitted to cell cell_of[i] of `pts`:
/// 1 + integral_H D - 2 S with S of ltc_objective (kernels/ltc.cl).
std::vector<double> distances(Engine& engine, cl::Kernel& kernel, Precision precision, const LobePoints& pts,
                              const cl::Buffer& inv_e, const std::vector<size_t>& cell_of,
                              const std::vector<LtcMatrix>& ms) {
    throw_if_cancelled();
    RealBuffers bufs(engine, precision);
    std::vector<double> cand;
    std::vector<cl_uint> cells;
    for (size_t i = 0; i < ms.size(); ++i) {
        double det = 0;
        const Mat3 inv = inverse(ms[i], det);
        cand.insert(cand.end(), inv.begin(), inv.end());
        cand.push_back(det);
        cells.push_back(cl_uint(cell_of[i]));
    }
    cl::Buffer b_cand = bufs.input(cand);
    cl::Buffer b_cells(engine.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, cells.size() * sizeof(cl_uint),
                       cells.data());
    cl::Buffer b_out = bufs.output(ms.size());
    set_args(kernel, 0, pts.buffer, cl_uint(pts.side * pts.side), b_cells, b_cand, inv_e, cl_uint(ms.size()), b_out);
    run_range(engine, kernel, ms.size());
    std::vector<double> s = bufs.read(b_out, ms.size());
    for (size_t i = 0; i < s.size(); ++i) s[i] = 1.0 + ltc_upper_mass(ms[i]) - 2.0 * s[i];
    return s;
}

/// M with its entries rounded to float32, as every table format but the CSV holds them.
LtcMatrix as_float32(LtcMatrix m) {
    for (double* v : {&m.m00, &m.m02, &m.m11, &m.m20, &m.m22}) *v = double(float(*v));
    return m;
}

/// The reported distance of each fit's M (kernels/ltc.cl, ltc_distance): on `distance_grids`
/// independent jittered grids of distance_side^2 points (not the fit's points, on which a fitted M
/// is biased low), each giving S_g = (lobe-sampled + LTC-sampled estimate of integral_H min(p, D))
/// / 2 and d_g = 1 + integral_H D - 2 S_g; the distance is the grids' mean, its error
/// `distance_sigmas` standard errors of that mean plus the kernel's rounding.
void report_distances(Engine& engine, const ModelConfig& model, const LtcFitOptions& o,
                      const std::vector<LtcCell>& cells, std::vector<LtcFit>& fits) {
    throw_if_cancelled();
    RealBuffers bufs(engine, o.precision);
    std::vector<double> mu, params, mats, albedo;
    for (size_t c = 0; c < cells.size(); ++c) {
        mu.push_back(cells[c].mu);
        params.insert(params.end(), cells[c].params.begin(), cells[c].params.end());
        const LtcMatrix& m = fits[c].m;
        double det = 0;
        const Mat3 inv = inverse(m, det);
        const Mat3 fwd = {m.m00, 0, m.m02, 0, m.m11, 0, m.m20, 0, m.m22};
        mats.insert(mats.end(), fwd.begin(), fwd.end());
        mats.insert(mats.end(), inv.begin(), inv.end());
        mats.push_back(det);
        albedo.push_back(fits[c].albedo);
    }
    const FresnelConfig none = resolve_fresnel("none");
    cl::Buffer b_mu = bufs.input(mu), b_p = bufs.input(params), b_m = bufs.input(mats), b_e = bufs.input(albedo);
    cl::Buffer b_fp = bufs.input({none.params.begin(), none.params.end()});
    cl::Buffer b_data = model_data_buffer(bufs, model.id);
    const size_t grids = size_t(o.distance_grids), n = cells.size() * grids;
    cl::Buffer b_out = bufs.output(2 * n);
    cl::Kernel k(ltc_program(engine, model, o.precision), BB_ENTRY_NAME(BB_ENTRY_LTC_DISTANCE));
    set_args(k, 0, b_mu, b_p, b_fp, b_data, cl_uint(cells.size()), cl_uint(grids), cl_uint(o.distance_side), b_m, b_e,
             b_out);
    run_range(engine, k, n);
    const std::vector<double> parts = bufs.read(b_out, 2 * n);
    // float sums of distance_side^2 terms of at most ~1: ~1e-6 relative each
    const double rounding = o.precision == Precision::Float ? 1e-5 : 1e-12;
    for (size_t c = 0; c < cells.size(); ++c) {
        double sum = 0, sum2 = 0;
        for (size_t g = 0; g < grids; ++g) {
            const double s = 0.5 * (parts[2 * (c * grids + g)] + parts[2 * (c * grids + g) + 1]);
            const double d = 1.0 + ltc_upper_mass(fits[c].m) - 2.0 * s;
            if (!std::isfinite(d)) throw Error("the LTC distance holds a non-finite value: the fit stops");
            sum += d;
            sum2 += d * d;
        }
        const double mean = sum / double(grids);
        const double var = grids > 1 ? std::max(0.0, (sum2 - sum * mean) / double(grids - 1)) : mean * mean;
        fits[c].distance = std::max(0.0, mean);
        fits[c].distance_error = o.distance_sigmas * std::sqrt(var / double(grids)) + rounding;
    }
}

std::array<double, 4> as_q(const std::vector<double>& x) { return {x[0], x[1], x[2], x[3]}; }

/// The start of each cell's minimisation, in the row's parameters x = (theta - theta_avg, ln a,
/// b, ln c) (the angle relative to the lobe's average direction): the best of a few candidates
/// evaluated in one launch: the clamped cosine turned to the average direction (x = 0), the same
/// scaled to the lobe's widths (CellSummary::width_x, width_y; times e^s, s = -0.5, 0, 0.5), and the
/// previous row's fit at the same cell with its widths (ln a, ln c) moved by s in -1.5 ... 0.5 (a
/// smoother row's lobe is narrower; the moved candidates bridge a coarse roughness axis).
std::vector<std::vector<double>> best_starts(const std::vector<CellSummary>& sums,
                                             const std::vector<std::array<double, 4>>* previous,
                                             const BatchObjective& objective) {
    const size_t n_cells = sums.size();
    std::vector<size_t> cell_of;
    std::vector<std::vector<double>> xs;
    for (size_t c = 0; c < n_cells; ++c) {
        cell_of.push_back(c);
        xs.push_back({0.0, 0.0, 0.0, 0.0});
        for (double s : {-0.5, 0.0, 0.5}) {
            cell_of.push_back(c);
            xs.push_back({0.0, std::log(sums[c].width_x) + s, 0.0, std::log(sums[c].width_y) + s});
        }
        if (!previous) continue;
        for (double s : {-1.5, -1.0, -0.5, -0.25, 0.0, 0.5}) {
            const std::array<double, 4>& x = (*previous)[c];
            cell_of.push_back(c);
            xs.push_back({x[0], x[1] + s, x[2], x[3] + s});
        }
    }
    const std::vector<double> f = objective(cell_of, xs);
    std::vector<std::vector<double>> best(n_cells, std::vector<double>(4, 0.0));
    std::vector<double> best_f(n_cells, HUGE_VAL);
    for (size_t i = 0; i < xs.size(); ++i)
        if (std::isfinite(f[i]) && f[i] < best_f[cell_of[i]]) {
            best[cell_of[i]] = xs[i];
            best_f[cell_of[i]] = f[i];
        }
    return best;
}

/// Cells whose neighbour's fit (the next or previous mu of the row) is better than their own
/// minimise again from it, as [HDHN16]'s fits start from the neighbouring texel; twice at most.
/// `moved(nb, c, x)`: the neighbour nb's parameters x expressed in cell c's.
void polish_from_neighbours(std::vector<Minimum>& minima, const NelderMeadOptions& nm, const BatchObjective& objective,
                            const std::function<std::vector<double>(size_t, size_t, const std::vector<double>&)>& moved) {
    const size_t n = minima.size();
    for (int pass = 0; pass < 2 && n > 1; ++pass) {
        std::vector<size_t> cell_of;
        std::vector<std::vector<double>> xs;
        for (size_t c = 0; c < n; ++c)
            for (size_t nb : {c - 1, c + 1})
                if (nb < n) {
                    cell_of.push_back(c);
                    xs.push_back(moved(nb, c, minima[nb].x));
                }
        const std::vector<double> f = objective(cell_of, xs);
        std::vector<size_t> redo;
        std::vector<std::vector<double>> starts;
        for (size_t i = 0; i < xs.size(); ++i) {
            const size_t c = cell_of[i];
            if (!(f[i] < minima[c].value * (1.0 - kPolishGain))) continue;
            if (!redo.empty() && redo.back() == c) {
                if (f[i] < f[i - 1]) starts.back() = xs[i];
                continue;
            }
            redo.push_back(c);
            starts.push_back(xs[i]);
        }
        if (redo.empty()) return;
        const std::vector<Minimum> again = minimize_batch(starts, nm, [&](const std::vector<size_t>& sub, const std::vector<std::vector<double>>& ys) {
            std::vector<size_t> cells;
            for (size_t k : sub) cells.push_back(redo[k]);
            return objective(cells, ys);
        });
        for (size_t k = 0; k < redo.size(); ++k)
            if (again[k].value < minima[redo[k]].value) {
                const int evals = minima[redo[k]].evaluations;
                minima[redo[k]] = again[k];
                minima[redo[k]].evaluations += evals;
            }
    }
}

/// Cells at normal view (mu = 1): for an isotropic model the lobe is symmetric about the normal,
/// and so is its best LTC; the fit is taken in that family, M = diag(a, a, 1) (theta = 0, b = 0,
/// a = c), a one-parameter Nelder-Mead on ln a from the mean of the free fit's ln a and ln c, as
/// fitLTC fits its first (isotropic) texel [HDHN16, ltc_code fitLTC.cpp]. The free fit's four
/// parameters wander along directions the fixed points barely see (its b and theta off zero),
/// which the independent distance sees (benchmarks/results/ltc-compare-amd-epyc-2c.md, ltc5).
/// `minima` hold absolute-relative parameters x = (theta - theta_avg, ln a, b, ln c).
void fit_normal_view(const std::vector<LtcCell>& cells, const std::vector<CellSummary>& sums,
                     const NelderMeadOptions& nm, const BatchObjective& objective,
                     std::vector<std::vector<double>>& xs, std::vector<int>& evaluations) {
    std::vector<size_t> normal;
    std::vector<std::vector<double>> starts;
    for (size_t c = 0; c < cells.size(); ++c)
        if (cells[c].mu >= 1.0 - 1e-12) {
            normal.push_back(c);
            starts.push_back({0.5 * (xs[c][1] + xs[c][3])});
        }
    if (normal.empty()) return;
    auto symmetric = [&](size_t c, double ln_a) { return std::vector<double>{-sums[c].average_theta, ln_a, 0.0, ln_a}; };
    // The distance of a lobe that an LTC matches almost exactly (GGX as alpha -> 0 is diag(2 alpha,
    // 2 alpha, 1)) grows as |ln a - ln a*| (the L1 distance of a rescaling), not quadratically: a
    // tolerance of 1e-3 on ln a left 3e-6 at alpha 2.5e-4 where the optimum's is 1e-7 (ltc6); the
    // fixed points place the tip of that V where p = D. So the simplex shrinks to 1e-8.
    NelderMeadOptions one = nm;
    one.steps = {0.05};
    one.size_tolerance = 1e-8;
    one.value_tolerance = 1e-10;
    const std::vector<Minimum> m = minimize_batch(starts, one, [&](const std::vector<size_t>& sub, const std::vector<std::vector<double>>& ys) {
        std::vector<size_t> cells_of;
        std::vector<std::vector<double>> x;
        for (size_t i = 0; i < sub.size(); ++i) {
            cells_of.push_back(normal[sub[i]]);
            x.push_back(symmetric(normal[sub[i]], ys[i][0]));
        }
        return objective(cells_of, x);
    });
    for (size_t k = 0; k < normal.size(); ++k) {
        xs[normal[k]] = symmetric(normal[k], m[k].x[0]);
        evaluations[normal[k]] += m[k].evaluations;
    }
}

/// The minimiser's coordinates of a cell: y = ((theta - theta_avg) / w, ln a, b / w, ln c) with w
/// the lobe's width (CellSummary::width_x, at most 1), so that the simplex's steps and size
/// tolerance are relative to the lobe (a lobe 2e-3 wide is lost in a step of 0.1 rad); and its
/// value the distance over the best start's (the value tolerance relative: narrow lobes' distances
/// are 1e-4 where rough ones' are 1e-1).
struct CellScale {
    double width = 1, value = 1;
    std::vector<double> scaled(const std::vector<double>& x) const { return {x[0] / width, x[1], x[2] / width, x[3]}; }
    std::vector<double> relative(const std::vector<double>& y) const { return {y[0] * width, y[1], y[2] * width, y[3]}; }
};

/// The narrowest lobe width (CellSummary::width_x, width_y) of a row.
double narrowest(const std::vector<CellSummary>& sums) {
    double w = HUGE_VAL;
    for (const CellSummary& s : sums) w = std::min({w, s.width_x, s.width_y});
    return w;
}

/// One row: the fit points and their summaries, the batched minimisation from `starts` (theta
/// taken from each cell's average direction), then the distance of the matrices as written.
std::vector<LtcFit> fit_row(Engine& engine, const ModelConfig& model, const std::vector<LtcCell>& cells,
                            const std::vector<std::array<double, 4>>* previous, const LtcFitOptions& o) {
    cl::Kernel kernel(ltc_program(engine, model, o.precision), BB_ENTRY_NAME(BB_ENTRY_LTC_OBJECTIVE));
    RealBuffers bufs(engine, o.precision);
    auto inverse_albedos = [&](const LobePoints& pts, std::vector<CellSummary>& sums) {
        std::vector<double> inv;
        for (size_t c = 0; c < cells.size(); ++c) {
            sums.push_back(summarise(pts, c));
            inv.push_back(sums.back().albedo > 0 ? 1.0 / sums.back().albedo : 0.0);
        }
        return bufs.input(inv);
    };
    const LobePoints fit_pts = lobe_points(engine, model, o.precision, cells, o.fit_side, o.fit_grade);
    std::vector<CellSummary> fit_sums;
    const cl::Buffer fit_inv_e = inverse_albedos(fit_pts, fit_sums);
    if (o.precision == Precision::Float && narrowest(fit_sums) < o.narrow_width) {
        LtcFitOptions narrow = o;
        narrow.precision = Precision::Double;
        narrow.value_tolerance = narrow.size_tolerance = o.narrow_tolerance;
        return fit_row(engine, model, cells, previous, narrow);
    }
    auto absolute = [&](size_t c, const std::vector<double>& x) {
        return std::array<double, 4>{fit_sums[c].average_theta + x[0], x[1], x[2], x[3]};
    };
    auto objective_on = [&](const LobePoints& pts, const cl::Buffer& inv_e) -> BatchObjective {
        return [&](const std::vector<size_t>& cell_of, const std::vector<std::vector<double>>& xs) {
            std::vector<LtcMatrix> ms;
            for (size_t i = 0; i < xs.size(); ++i) ms.push_back(ltc_matrix(absolute(cell_of[i], xs[i])));
            return distances(engine, kernel, o.precision, pts, inv_e, cell_of, ms);
        };
    };
    std::vector<CellScale> scale(cells.size());
    auto scaled = [&](const BatchObjective& objective) -> BatchObjective {
        return [&scale, objective](const std::vector<size_t>& cell_of, const std::vector<std::vector<double>>& ys) {
            std::vector<std::vector<double>> xs;
            for (size_t i = 0; i < ys.size(); ++i) xs.push_back(scale[cell_of[i]].relative(ys[i]));
            std::vector<double> f = objective(cell_of, xs);
            for (size_t i = 0; i < f.size(); ++i) f[i] /= scale[cell_of[i]].value;
            return f;
        };
    };
    std::vector<size_t> all(cells.size());
    std::iota(all.begin(), all.end(), size_t(0));
    const BatchObjective objective = objective_on(fit_pts, fit_inv_e);
    std::vector<std::vector<double>> starts = best_starts(fit_sums, previous, objective);
    const std::vector<double> f0 = objective(all, starts);
    for (size_t c = 0; c < cells.size(); ++c) {
        scale[c].width = std::min(1.0, fit_sums[c].width_x);
        scale[c].value = std::max(f0[c], kValueFloor);
        starts[c] = scale[c].scaled(starts[c]);
    }
    NelderMeadOptions nm;
    nm.steps = {0.5, 0.2, 0.5, 0.2};
    nm.max_evaluations = o.max_evaluations;
    nm.value_tolerance = o.value_tolerance;
    nm.size_tolerance = o.size_tolerance;
    std::vector<Minimum> minima = minimize_batch(starts, nm, scaled(objective));
    polish_from_neighbours(minima, nm, scaled(objective), [&](size_t nb, size_t c, const std::vector<double>& y) {
        std::vector<double> x = scale[nb].relative(y);
        x[0] += fit_sums[nb].average_theta - fit_sums[c].average_theta;
        return scale[c].scaled(x);
    });
    LobePoints fine_pts;
    cl::Buffer fine_inv_e;
    BatchObjective refined_objective = objective;  // the last stage's points: the normal-view fit's
    if (o.refine_side > 0) {
        // The coarse points' minimum is as far from the true one as their estimate's error lets
        // it be (a lobe-sampled midpoint rule of fit_side^2 points): polish it on refine_side^2
        // points with a smaller simplex and budget.
        fine_pts = lobe_points(engine, model, o.precision, cells, o.refine_side, o.fit_grade);
        std::vector<CellSummary> fine_sums;
        fine_inv_e = inverse_albedos(fine_pts, fine_sums);
        const BatchObjective fine = objective_on(fine_pts, fine_inv_e);
        refined_objective = fine;
        std::vector<std::vector<double>> from;
        for (size_t c = 0; c < cells.size(); ++c) from.push_back(scale[c].relative(minima[c].x));
        const std::vector<double> f1 = fine(all, from);
        for (size_t c = 0; c < cells.size(); ++c) {
            scale[c].value = std::max(f1[c], kValueFloor);
            from[c] = minima[c].x;
        }
        NelderMeadOptions polish = nm;
        for (double& s : polish.steps) s *= o.refine_step;
        polish.max_evaluations = o.refine_evaluations;
        polish.speculative = false;  // on refine_side^2 points the evaluations cost, not the rounds
        const std::vector<Minimum> refined = minimize_batch(from, polish, scaled(fine));
        for (size_t c = 0; c < cells.size(); ++c) {
            minima[c].evaluations += refined[c].evaluations;
            if (refined[c].value < 1.0) minima[c].x = refined[c].x;
        }
    }
    std::vector<std::vector<double>> xs;
    std::vector<int> evaluations;
    for (size_t c = 0; c < cells.size(); ++c) {
        xs.push_back(scale[c].relative(minima[c].x));
        evaluations.push_back(minima[c].evaluations);
    }
    fit_normal_view(cells, fit_sums, nm, refined_objective, xs, evaluations);
    std::vector<LtcFit> fits(cells.size());
    for (size_t c = 0; c < cells.size(); ++c) {
        fits[c].x = as_q(xs[c]);
        fits[c].q = absolute(c, xs[c]);
        fits[c].m = o.as_written ? o.as_written(ltc_matrix(fits[c].q)) : as_float32(ltc_matrix(fits[c].q));
        fits[c].evaluations = evaluations[c];
        fits[c].albedo = cells[c].albedo > 0 ? cells[c].albedo : fit_sums[c].albedo;
    }
    report_distances(engine, model, o, cells, fits);
    return fits;
}

}  // namespace

LtcMatrix ltc_matrix(const std::array<double, 4>& q) {
    const double ct = std::cos(q[0]), st = std::sin(q[0]), a = std::exp(q[1]), b = q[2], c = std::exp(q[3]);
    // R_y(theta) = [[ct, 0, st], [0, 1, 0], [-st, 0, ct]] times [[a, 0, b], [0, c, 0], [0, 0, 1]].
    LtcMatrix m;
    m.m00 = ct * a;
    m.m02 = ct * b + st;
    m.m11 = c;
    m.m20 = -st * a;
    m.m22 = -st * b + ct;
    return m;
}

double ltc_density(const LtcMatrix& m, const std::array<double, 3>& w) {
    double det = 0;
    const Mat3 inv = inverse(m, det);
    const double x = inv[0] * w[0] + inv[2] * w[2], y = inv[4] * w[1], z = inv[6] * w[0] + inv[8] * w[2];
    const double l2 = x * x + y * y + z * z;
    return std::max(z, 0.0) * det / (kPi * l2 * l2);
}

double ltc_upper_mass(const LtcMatrix& m) {
    const double n = std::hypot(m.m20, m.m22);
    return n > 0 ? 0.5 * (1.0 + m.m22 / n) : 0.5;
}

std::vector<std::vector<LtcFit>> fit_ltc_rows(Engine& engine, const ModelConfig& model,
                                              const std::vector<std::vector<LtcCell>>& rows,
                                              const LtcFitOptions& options,
                                              const std::function<void(size_t)>& row_done) {
    std::vector<std::vector<LtcFit>> out;
    std::vector<std::array<double, 4>> previous;
    for (size_t r = 0; r < rows.size(); ++r) {
        const bool seeded = r > 0 && rows[r].size() == rows[r - 1].size();
        out.push_back(fit_row(engine, model, rows[r], seeded ? &previous : nullptr, options));
        previous.clear();
        for (const LtcFit& f : out.back()) previous.push_back(f.x);
        if (row_done) row_done(r);
    }
    return out;
}

}  // namespace fit
}  // namespace brdfbake

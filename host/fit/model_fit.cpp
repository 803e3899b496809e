#include "fit/model_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "brdfbake/brdf/fit_metric.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/merl.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/cancel.h"
#include "brdfbake/error.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/output.h"
#include "engine/device_buffer.h"
#include "fit/nelder_mead.h"
#include "integrate/launch.h"
#include "models/merl_file.h"

namespace brdfbake {
namespace fit {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr FitParameter kAlpha{"alpha", 1e-3, 1.0, 0.5};  // the fitted alpha's range
constexpr unsigned kBlock = 256;                          // pairs per work-item
constexpr double kAlphaStarts[] = {0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 0.8};  // multi-start grid
constexpr int kRotations = 8;  // anisotropic fits: the pairs turned about the normal this many times
constexpr double kSizeTolerance = 1e-5;  // the minimiser's stop, in the logistic variables
constexpr FitParameter kDiffuse{"diffuse", 0.0, 1.0, 0.1};  // --diffuse: the Lambert weight kd
constexpr double kDiffuseStarts[] = {0.02, 0.2, 0.6};         // ... and its multi-start grid

double logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }
double logit(double p) { return std::log(p / (1.0 - p)); }
double value_of(const FitParameter& p, double x) { return p.lo + (p.hi - p.lo) * logistic(x); }
double x_of(const FitParameter& p, double v) { return logit((v - p.lo) / (p.hi - p.lo)); }
double slope_of(const FitParameter& p, double x) { return (p.hi - p.lo) * logistic(x) * (1.0 - logistic(x)); }

/// The row of `rows` (fit_metrics(), fit_amplitudes()) called `name`; else Error naming `option`.
template <typename Row>
const Row& row_named(const std::vector<Row>& rows, const std::string& name, const std::string& option,
                     const std::string& what) {
    std::string names;
    for (const Row& r : rows) {
        if (name == r.name) return r;
        names += (names.empty() ? "" : ", ") + std::string(r.name);
    }
    throw Error(option + " '" + name + "' is not " + what + "; they are " + names);
}

const FitMetric& metric_named(const std::string& name) {
    return row_named(fit_metrics(), name, "--metric", "a known metric");
}

const FitAmplitude& amplitude_named(const std::string& name) {
    return row_named(fit_amplitudes(), name, "--fresnel", "a fitted Fresnel term");
}

/// The channels fitted: r, g, b of a merl target without a channel (or channel=rgb), else the
/// target as given.
std::vector<std::pair<std::string, std::string>> target_channels(const std::string& target) {
    const Spec s = parse_spec(target);
    if (s.name != "merl") return {{"", target}};
    for (const auto& kv : s.keys)
        if (kv.first == "channel" && kv.second != "rgb") return {{kv.second, target}};
    std::vector<std::pair<std::string, std::string>> out;
    for (const char* c : {"r", "g", "b"}) out.push_back({c, merl_channel_spec(target, c)});
    return out;
}

std::vector<ModelConfig> channel_models(const ModelFitRequest& r, std::vector<std::string>& names) {
    std::vector<ModelConfig> out;
    for (const auto& [name, spec] : target_channels(r.target)) {
        names.push_back(name);
        out.push_back(resolve_model(spec));
    }
    return out;
}

/// Whether the fit has alpha_x and alpha_y: asked for, or the (analytic) target is anisotropic.
bool fits_anisotropic(const ModelFitRequest& r) {
    if (r.anisotropic) return true;
    std::vector<std::string> names;
    for (const ModelConfig& t : channel_models(r, names))
        if (t.anisotropic) return true;
    return false;
}

/// The free parameters of a fit and the specs they make: alpha (or alpha_x, alpha_y) of the
/// model, then the Fresnel term's (FitAmplitude). A point x of the minimiser holds one real per
/// parameter, mapped onto its range by value_of.
class Layout {
public:
    explicit Layout(const ModelFitRequest& r) : model_(r.model), amplitude_(amplitude_named(r.amplitude)) {
        if (fits_anisotropic(r)) {
            params_.push_back({"alpha_x", kAlpha.lo, kAlpha.hi, kAlpha.start});
            params_.push_back({"alpha_y", kAlpha.lo, kAlpha.hi, kAlpha.start});
        } else {
            params_.push_back(kAlpha);
        }
        alphas_ = params_.size();
        if (r.diffuse) params_.push_back(kDiffuse);
        model_params_ = params_.size();
        params_.insert(params_.end(), amplitude_.params.begin(), amplitude_.params.end());
    }

    const std::vector<FitParameter>& params() const { return params_; }
    size_t alphas() const { return alphas_; }
    bool diffuse() const { return model_params_ > alphas_; }

    /// A start: every alpha at `alpha`, kd at `kd` (--diffuse), the Fresnel parameters at their starts.
    std::vector<double> start(double alpha, double kd = kDiffuse.start) const {
        std::vector<double> x;
        for (size_t i = 0; i < params_.size(); ++i)
            x.push_back(x_of(params_[i], i < alphas_ ? alpha : i < model_params_ ? kd : params_[i].start));
        return x;
    }

    std::vector<double> values(const std::vector<double>& x) const {
        std::vector<double> v;
        for (size_t i = 0; i < params_.size(); ++i) v.push_back(value_of(params_[i], x[i]));
        return v;
    }

    /// The specs of the parameter values v, as the command line takes them.
    std::string model_spec(const std::vector<double>& v) const {
        std::string s = model_ + (model_.find(':') == std::string::npos ? ":" : ",");
        for (size_t i = 0; i < model_params_; ++i) s += (i ? "," : "") + std::string(params_[i].name) + "=" + round_trip_text(v[i]);
        return s;
    }
    std::string fresnel_spec(const std::vector<double>& v) const {
        std::string s = amplitude_.spec;
        for (size_t i = model_params_; i < params_.size(); ++i)
            for (size_t at; (at = s.find("{" + std::string(params_[i].name) + "}")) != std::string::npos;)
                s.replace(at, std::string(params_[i].name).size() + 2, round_trip_text(v[i]));
        return s;
    }

private:
    std::string model_;
    const FitAmplitude& amplitude_;
    std::vector<FitParameter> params_;
    size_t alphas_ = 1;
    size_t model_params_ = 1;  // the alphas and kd: the model spec's; the Fresnel term's after them
};

/// The direction pairs: MERL bin nodes (ih, id, ip) on a stride (sh, sd, sp), those above both
/// horizons, each weighted by the measure d wo d wi of the bins it stands for (model_fit.h);
/// with `rotations` > 1 each pair turned about the normal to phi_h = (k + 1/2) 2 pi / rotations
/// (the MERL nodes all have phi_h = 0: an isotropic BRDF does not depend on it), each turn
/// carrying its share of the weight; with rotations = 0 each pair turned once, pair j to
/// phi_h = 2 pi frac((j + 1/2) / golden ratio) (a low-discrepancy sequence: over the many pairs
/// of every bin the turns cover phi_h evenly, at the cost of one turn per pair).
struct Pairs {
    std::vector<double> values;  // BB_FIT_PAIR_VALUES per pair
    std::vector<int> bins;       // the MERL index of each pair's node
    std::vector<Vec3> wo, wi;
};

/// cos theta_h and cos theta_d of the nodes ih and id (merl_file.h's nodes: at theta_d = 0 wi is
/// the half vector; at theta_h = 0 it is the difference vector).
double cos_theta_h(int ih) {
    Vec3 wo, wi;
    merl_node_dirs(ih, 0, 0, wo, wi);
    return wi[2];
}
double cos_theta_d(int id) {
    Vec3 wo, wi;
    merl_node_dirs(0, id, 0, wo, wi);
    return wi[2];
}

Pairs make_pairs(int sh, int sd, int sp, int rotations) {
    Pairs p;
    for (int ih = 0; ih < BB_MERL_THETA_H; ih += sh) {
        const double wh = cos_theta_h(ih) - cos_theta_h(std::min(ih + sh, BB_MERL_THETA_H));
        for (int id = 0; id < BB_MERL_THETA_D; id += sd) {
            const double ca = cos_theta_d(id), cb = cos_theta_d(std::min(id + sd, BB_MERL_THETA_D));
            const double wd = 0.5 * (ca * ca - cb * cb);  // the integral of sin cos over the bins
            for (int ip = 0; ip < BB_MERL_PHI_D; ip += sp) {
                const double wp = (std::min(ip + sp, BB_MERL_PHI_D) - ip) * kPi / BB_MERL_PHI_D;
                Vec3 o, i;
                merl_node_dirs(ih, id, ip, o, i);
                if (!(o[2] > 0 && i[2] > 0)) continue;
                const int turns = std::max(rotations, 1);
                for (int k = 0; k < turns; ++k) {
                    const double golden = std::fmod((p.bins.size() + 0.5) * 0.6180339887498949, 1.0);
                    const double phi = rotations == 0 ? 2 * kPi * golden : (k + 0.5) * 2 * kPi / turns;
                    const double c = turns > 1 || rotations == 0 ? std::cos(phi) : 1.0;
                    const double s = turns > 1 || rotations == 0 ? std::sin(phi) : 0.0;
                    const Vec3 wo = {c * o[0] - s * o[1], s * o[0] + c * o[1], o[2]};
                    const Vec3 wi = {c * i[0] - s * i[1], s * i[0] + c * i[1], i[2]};
                    p.values.insert(p.values.end(), {wo[0], wo[1], wo[2], wi[0], wi[1], wi[2], 4 * wh * wd * wp / turns});
                    p.bins.push_back(bb_merl_index(ih, id, ip));
                    p.wo.push_back(wo);
                    p.wi.push_back(wi);
                }
            }
        }
    }
    return p;
}

/// The compressed target g(f cos theta_i) of every channel at every pair (channel-major), -1
/// where the target is unmeasured; the measured weight of each channel.
struct Targets {
    std::vector<double> t;
    std::vector<double> measured_weight, unmeasured_share;
    std::vector<size_t> measured_pairs;
};

Targets make_targets(Engine& engine, const ModelFitRequest& r, const std::vector<ModelConfig>& channels,
                     const Pairs& pairs, int metric) {
    const size_t n = pairs.bins.size();
    Targets out;
    const FresnelConfig fresnel = resolve_fresnel(r.target_fresnel);
    for (const ModelConfig& m : channels) {
        std::vector<double> f;
        if (m.traits().measured) {
            const double* table = bb_merl_host_table(int(m.params[BB_MERL_TABLE]));
            for (int bin : pairs.bins) f.push_back(table[bin]);
        } else {
            f = evaluate_on_device(engine, m, fresnel, r.precision, pairs.wo, pairs.wi);
        }
        double measured = 0, all = 0;
        size_t count = 0;
        for (size_t j = 0; j < n; ++j) {
            const double w = pairs.values[j * BB_FIT_PAIR_VALUES + 6];
            all += w;
            if (!std::isfinite(f[j])) throw Error("the target '" + m.canonical + "' is not finite at a direction pair");
            if (f[j] < 0) {
                out.t.push_back(-1.0);
                continue;
            }
            measured += w;
            ++count;
            out.t.push_back(bb_fit_compress(metric, f[j] * pairs.wi[j][2]));
        }
        if (!(measured > 0)) throw Error("the target '" + m.canonical + "' has no measured bin above the horizon");
        out.measured_weight.push_back(measured);
        out.unmeasured_share.push_back(1.0 - measured / all);
        out.measured_pairs.push_back(count);
    }
    return out;
}

/// One candidate: the channel it is fitted to, and its free parameters x (Layout).
struct Candidate {
    size_t channel;
    std::vector<double> x;
};

/// The objective on the device: sum_j w_j (g(f_c cos) - t_j)^2 per candidate (kernels/fit.cl),
/// or the residuals g(f_c cos) - t_j of every pair.
class Objective {
public:
    Objective(Engine& engine, const ModelFitRequest& r, const Layout& layout, const Pairs& pairs,
              const Targets& targets, int metric)
        : engine_(engine), layout_(layout), bufs_(engine, r.precision), n_(pairs.bins.size()), metric_(metric) {
        pairs_ = bufs_.input(pairs.values);
        targets_ = bufs_.input(targets.t);
        const std::vector<double> mid = layout.values(layout.start(0.5));
        const ModelConfig m = resolve_model(layout.model_spec(mid));
        BuildRequest build;
        build.kernel_file = "fit.cl";
        build.precision = r.precision;
        build.model = m.id;
        build.fresnel = resolve_fresnel(layout.fresnel_spec(mid)).kind;
        kernel_ = cl::Kernel(engine.program(build), BB_ENTRY_NAME(BB_ENTRY_MODEL_FIT_OBJECTIVE));
        data_ = model_data_buffer(bufs_, m.id);
    }

    size_t pairs() const { return n_; }

    /// S of each candidate.
    std::vector<double> operator()(const std::vector<Candidate>& cands) {
        const size_t blocks = (n_ + kBlock - 1) / kBlock;
        const std::vector<double> parts = launch(cands, kBlock, false);
        std::vector<double> out(cands.size(), 0.0);
        for (size_t c = 0; c < cands.size(); ++c)
            for (size_t b = 0; b < blocks; ++b) out[c] += parts[c * blocks + b];
        return out;
    }

    /// The residual of every pair for each candidate (candidate-major; 0 where unmeasured).
    std::vector<double> residuals(const std::vector<Candidate>& cands) { return launch(cands, 1, true); }

private:
    std::vector<double> launch(const std::vector<Candidate>& cands, unsigned block, bool residuals) {
        std::vector<double> mp, fp;
        std::vector<cl_uint> channel;
        for (const Candidate& c : cands) {
            const std::vector<double> v = layout_.values(c.x);
            const ModelConfig m = resolve_model(layout_.model_spec(v));
            const FresnelConfig f = resolve_fresnel(layout_.fresnel_spec(v));
            mp.insert(mp.end(), m.params.begin(), m.params.end());
            fp.insert(fp.end(), f.params.begin(), f.params.end());
            channel.push_back(cl_uint(c.channel));
        }
        const size_t items = cands.size() * ((n_ + block - 1) / block);
        cl::Buffer b_mp = bufs_.input(mp), b_fp = bufs_.input(fp);
        cl::Buffer b_ch(engine_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, channel.size() * sizeof(cl_uint),
                        channel.data());
        cl::Buffer b_out = bufs_.output(items);
        set_args(kernel_, 0, pairs_, targets_, cl_uint(n_), b_mp, b_fp, b_ch, cl_uint(cands.size()), cl_uint(block),
                 cl_int(metric_), cl_int(residuals), data_, b_out);
        run_items(engine_, kernel_, items, double(block), "fit");
        return bufs_.read(b_out, items);
    }

    Engine& engine_;
    const Layout& layout_;
    RealBuffers bufs_;
    size_t n_;
    int metric_;
    cl::Kernel kernel_;
    cl::Buffer pairs_, targets_, data_;
};

/// Multi-start minimisation: per channel, every alpha on a grid of starts (the Fresnel
/// parameters at their starts) evaluated in one launch, Nelder-Mead from the best of them
/// (restarted once around its minimum).
std::vector<Minimum> minimise(Objective& objective, const Layout& layout, size_t n_channels, int max_evaluations) {
    std::vector<Candidate> grid;
    for (size_t c = 0; c < n_channels; ++c)
        for (double a : kAlphaStarts) {
            if (!layout.diffuse()) grid.push_back({c, layout.start(a)});
            for (double kd : kDiffuseStarts)
                if (layout.diffuse()) grid.push_back({c, layout.start(a, kd)});
        }
    const std::vector<double> g = objective(grid);
    std::vector<std::vector<double>> starts(n_channels);
    std::vector<double> best(n_channels, HUGE_VAL);
    for (size_t i = 0; i < grid.size(); ++i)
        if (g[i] < best[grid[i].channel]) {
            best[grid[i].channel] = g[i];
            starts[grid[i].channel] = grid[i].x;
        }
    NelderMeadOptions nm;
    nm.steps.assign(layout.params().size(), 0.3);
    nm.max_evaluations = max_evaluations > 0 ? max_evaluations : evaluation_budget(layout.params().size());
    nm.value_tolerance = HUGE_VAL;  // converged on the simplex's size alone
    nm.size_tolerance = kSizeTolerance;  // alpha to ~3e-6
    const BatchObjective f = [&](const std::vector<size_t>& problem, const std::vector<std::vector<double>>& xs) {
        std::vector<Candidate> cands;
        for (size_t i = 0; i < xs.size(); ++i) cands.push_back({problem[i], xs[i]});
        return objective(cands);
    };
    return minimize_batch(starts, nm, f);
}

/// The inverse of the symmetric positive definite n x n matrix a (row-major) by Gauss-Jordan
/// elimination with partial pivoting; empty when it is singular.
std::vector<double> inverse(std::vector<double> a, size_t n) {
    std::vector<double> b(n * n, 0.0);
    for (size_t i = 0; i < n; ++i) b[i * n + i] = 1.0;
    for (size_t c = 0; c < n; ++c) {
        size_t piv = c;
        for (size_t r = c + 1; r < n; ++r)
            if (std::fabs(a[r * n + c]) > std::fabs(a[piv * n + c])) piv = r;
        if (!(std::fabs(a[piv * n + c]) > 0)) return {};
        for (size_t k = 0; k < n; ++k) {
            std::swap(a[c * n + k], a[piv * n + k]);
            std::swap(b[c * n + k], b[piv * n + k]);
        }
        const double d = a[c * n + c];
        for (size_t k = 0; k < n; ++k) {
            a[c * n + k] /= d;
            b[c * n + k] /= d;
        }
        for (size_t r = 0; r < n; ++r) {
            if (r == c) continue;
            const double m = a[r * n + c];
            for (size_t k = 0; k < n; ++k) {
                a[r * n + k] -= m * a[c * n + k];
                b[r * n + k] -= m * b[c * n + k];
            }
        }
    }
    return b;
}

/// The standard errors of the fitted parameters of every channel: the sandwich (Huber-White)
/// covariance of the weighted least-squares estimate, Huber 1967 ("The behavior of maximum
/// likelihood estimates under nonstandard conditions"), White 1980 (Econometrica 48, eq. 4):
///   cov = A^-1 B A^-1,  A = sum_j w_j J_j J_j^T,  B = sum_j w_j^2 r_j^2 J_j J_j^T,
/// with r_j the residual of pair j at the minimum and J_j its gradient in the minimiser's
/// variables (central differences), mapped onto the parameters by their logistic slopes. It
/// reads the residuals as independent errors of the pairs, of any variance: a measured file's
/// noise. A target the model matches has every r_j = 0: what is left is the minimiser's stop
/// (kSizeTolerance in the logistic variables), added in quadrature. A model's misfit is not
/// noise, and the distance is what tells it.
std::vector<std::vector<double>> parameter_errors(Objective& objective, const Layout& layout, const Pairs& pairs,
                                                  const std::vector<Minimum>& minima, Precision precision) {
    const size_t np = layout.params().size(), n = objective.pairs();
    const double h = precision == Precision::Double ? 1e-4 : 3e-3;
    std::vector<Candidate> cands;
    for (size_t c = 0; c < minima.size(); ++c) {
        cands.push_back({c, minima[c].x});
        for (size_t i = 0; i < np; ++i)
            for (double s : {h, -h}) {
                std::vector<double> x = minima[c].x;
                x[i] += s;
                cands.push_back({c, x});
            }
    }
    const std::vector<double> r = objective.residuals(cands);
    std::vector<std::vector<double>> out;
    for (size_t c = 0; c < minima.size(); ++c) {
        const double* r0 = &r[c * (2 * np + 1) * n];
        std::vector<double> a(np * np, 0.0), b(np * np, 0.0), jac(np);
        for (size_t j = 0; j < n; ++j) {
            const double w = pairs.values[j * BB_FIT_PAIR_VALUES + 6];
            for (size_t i = 0; i < np; ++i) jac[i] = (r0[(1 + 2 * i) * n + j] - r0[(2 + 2 * i) * n + j]) / (2 * h);
            for (size_t i = 0; i < np; ++i)
                for (size_t k = 0; k < np; ++k) {
                    a[i * np + k] += w * jac[i] * jac[k];
                    b[i * np + k] += w * w * r0[j] * r0[j] * jac[i] * jac[k];
                }
        }
        const std::vector<double> ai = inverse(a, np);
        std::vector<double> e(np, 0.0);
        for (size_t i = 0; i < np; ++i)  // a direction the metric does not see: the whole range
            if (ai.empty()) e[i] = layout.params()[i].hi - layout.params()[i].lo;
        for (size_t i = 0; i < np && !ai.empty(); ++i) {
            double v = 0;  // (A^-1 B A^-1)_ii
            for (size_t k = 0; k < np; ++k)
                for (size_t l = 0; l < np; ++l) v += ai[i * np + k] * b[k * np + l] * ai[l * np + i];
            e[i] = std::hypot(std::sqrt(std::max(0.0, v)), kSizeTolerance) * slope_of(layout.params()[i], minima[c].x[i]);
        }
        out.push_back(e);
    }
    return out;
}

}  // namespace

// What the fits need grows about as n^2 (Nelder-Mead's steps per simplex and the simplex's
// n + 1 vertices). Measured (amd-epyc-2c; analytic GGX targets at stride 4-6, conductor and
// diffuse combinations, every channel converged with no budget): n = 1: 124 evaluations, 2: 290,
// 3: 632-856, 4: 1074-1326, 5: 1844. 200 + 100 n^2 (300, 600, 1100, 1800, 2700) leaves 28 % or
// more above each; the conductor fit (n = 3) used all of its former flat 400.
int evaluation_budget(size_t n) { return int(200 + 100 * n * n); }

const std::vector<FitMetric>& fit_metrics() {
    static const std::vector<FitMetric> metrics = {
        {"cbrt", BB_FIT_METRIC_CBRT,
         "L2 of (f cos theta_i)^(1/3), the compressed cosine-weighted BRDF of Ngan et al. 2005 (default)"},
        {"log", BB_FIT_METRIC_LOG, "L2 of log(1 + f cos theta_i)"},
        {"l2", BB_FIT_METRIC_L2, "L2 of f cos theta_i, uncompressed (the specular peak dominates)"},
    };
    return metrics;
}

const std::vector<FitAmplitude>& fit_amplitudes() {
    // The conductor's ranges hold the metals of the usual tables at visible wavelengths (gold's
    // eta 0.17 at 650 nm to silver's k 4.2 and aluminium's eta 1.4 and k 7.5 at 550 nm).
    static const std::vector<FitAmplitude> terms = {
        {"scale", "gen-schlick:f0={s},f90={s}", {{"s", 0.0, 1.0, 0.5}}, "F = s, a constant in [0, 1] (default)"},
        {"schlick", "schlick:f0={f0}", {{"f0", 0.0, 1.0, 0.5}}, "Schlick 1994 with f0 in [0, 1]"},
        {"conductor", "conductor:eta={eta},k={k}", {{"eta", 0.02, 10.0, 1.0}, {"k", 0.0, 12.0, 3.0}},
         "the exact conductor (Fresnel equations, index eta + ik) with eta in [0.02, 10], k in [0, 12]"},
        {"none", "none", {}, "F = 1: alpha alone"},
    };
    return terms;
}

void check_model_fit_request(const ModelFitRequest& r) {
    metric_named(r.metric);
    const FitAmplitude& amp = amplitude_named(r.amplitude);
    if (r.stride < 1 || r.stride > 15) throw Error("--stride must be 1 to 15");
    if (r.max_evaluations != 0 && r.max_evaluations < 20)
        throw Error("--max-evaluations must be at least 20 (or 0: the default for the parameter count)");
    const Spec base = parse_spec(r.model);
    for (const auto& kv : base.keys) {
        if (kv.first == "alpha" || kv.first == "alpha_x" || kv.first == "alpha_y" || kv.first == "roughness")
            throw Error("--model '" + r.model + "': leave " + kv.first + " out, the fit finds alpha (e.g. --model " +
                        base.name + ")");
        if (r.diffuse && kv.first == "diffuse")
            throw Error("--model '" + r.model + "': leave diffuse out with --diffuse, the fit finds it");
    }
    const ModelConfig m = resolve_model(r.model + (r.model.find(':') == std::string::npos ? ":" : ",") + "alpha=0.5");
    if (m.traits().alpha_x_slot < 0 || m.traits().measured)
        throw Error("--model '" + m.name + "' has no roughness alpha to fit; fit a microfacet model such as ggx or beckmann");
    if (r.diffuse && (m.id != BB_MODEL_GGX && m.id != BB_MODEL_BECKMANN))
        throw Error("--diffuse: --model '" + m.name + "' has no diffuse=KD key; fit ggx or beckmann");
    if (!amp.params.empty() && !m.uses_fresnel)
        throw Error("--model '" + m.name + "' has no Fresnel term to carry --fresnel " + amp.name + "; use --fresnel none");
    resolve_fresnel(r.target_fresnel);
    std::vector<std::string> names;
    for (const ModelConfig& t : channel_models(r, names)) {
        if (!t.traits().measured && t.uses_fresnel == false && r.target_fresnel != "none")
            throw Error("--target '" + t.name + "' has no Fresnel term; drop --target-fresnel");
        if (t.traits().measured && r.anisotropic)
            throw Error("--anisotropic: a MERL file is isotropic (its bins have no phi_h); drop --anisotropic");
    }
}

ModelFitResult fit_model(Engine& engine, const ModelFitRequest& r) {
    check_model_fit_request(r);
    const int metric = metric_named(r.metric).id;
    std::vector<std::string> names;
    const std::vector<ModelConfig> channels = channel_models(r, names);
    ModelFitResult result;
    if (channels[0].traits().measured) result.unmeasured_bins = merl_table_info(int(channels[0].params[BB_MERL_TABLE])).unmeasured;

    const Layout layout(r);
    const int rotations = layout.alphas() > 1 ? kRotations : 1;
    const Pairs pairs = make_pairs(r.stride, r.stride, 2 * r.stride, rotations);
    const Targets targets = make_targets(engine, r, channels, pairs, metric);
    result.pairs = pairs.bins.size();
    Objective objective(engine, r, layout, pairs, targets, metric);
    const std::vector<Minimum> minima = minimise(objective, layout, channels.size(), r.max_evaluations);
    const std::vector<std::vector<double>> errors = parameter_errors(objective, layout, pairs, minima, r.precision);
    // The distance over every bin (stride 1): the fit's pairs are a subset, on which the minimum
    // is biased low. Anisotropic: each bin's pair at its own turn (make_pairs, rotations = 0).
    const Pairs all = r.stride == 1 && rotations == 1 ? Pairs() : make_pairs(1, 1, 1, rotations == 1 ? 1 : 0);
    const bool same = all.bins.empty();
    const Targets all_targets = same ? targets : make_targets(engine, r, channels, all, metric);
    result.all_pairs = same ? result.pairs : all.bins.size();
    Objective all_objective(engine, r, layout, same ? pairs : all, all_targets, metric);
    std::vector<Candidate> finals;
    for (size_t c = 0; c < channels.size(); ++c) finals.push_back({c, minima[c].x});
    const std::vector<double> all_values = all_objective(finals);

    for (size_t c = 0; c < channels.size(); ++c) {
        const Minimum& m = minima[c];
        ChannelFit f;
        f.channel = names[c];
        const std::vector<double> v = layout.values(m.x);
        for (size_t i = 0; i < v.size(); ++i) {
            f.params.push_back({layout.params()[i].name, v[i], errors[c][i]});
            if (!std::isfinite(v[i]) || !std::isfinite(errors[c][i]))
                throw Error("the fit of channel '" + f.channel + "' is not finite");
        }
        f.model_spec = resolve_model(layout.model_spec(v)).canonical;
        f.fresnel_spec = resolve_fresnel(layout.fresnel_spec(v)).canonical;
        f.distance_fit = std::sqrt(std::max(0.0, m.value) / targets.measured_weight[c]);
        f.distance = std::sqrt(std::max(0.0, all_values[c]) / all_targets.measured_weight[c]);
        f.unmeasured_share = all_targets.unmeasured_share[c];
        // and the grid of starts
        f.evaluations = m.evaluations + int(std::size(kAlphaStarts) * (layout.diffuse() ? std::size(kDiffuseStarts) : 1));
        f.budget = r.max_evaluations > 0 ? r.max_evaluations : evaluation_budget(layout.params().size());
        f.converged = m.converged;
        if (!std::isfinite(f.distance)) throw Error("the fit of channel '" + f.channel + "' is not finite");
        result.channels.push_back(f);
    }
    return result;
}

}  // namespace fit
}  // namespace brdfbake

#include "fit/model_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

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
constexpr double kAlphaLo = 1e-3, kAlphaHi = 1.0;  // the fitted alpha's range
constexpr unsigned kBlock = 256;                   // pairs per work-item

double logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }
double logit(double p) { return std::log(p / (1.0 - p)); }
double alpha_of(double x) { return kAlphaLo + (kAlphaHi - kAlphaLo) * logistic(x); }

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
    return row_named(fit_amplitudes(), name, "--fresnel", "a fitted amplitude term");
}

bool has_parameter(const FitAmplitude& a) { return std::string(a.spec).find("%s") != std::string::npos; }

std::string model_spec_with_alpha(const std::string& model, double alpha) {
    return model + (model.find(':') == std::string::npos ? ":" : ",") + "alpha=" + round_trip_text(alpha);
}

std::string amplitude_spec(const FitAmplitude& a, double value) {
    std::string s = a.spec;
    const std::string v = round_trip_text(value);
    for (size_t at; (at = s.find("%s")) != std::string::npos;) s.replace(at, 2, v);
    return s;
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

/// The direction pairs: MERL bin nodes (ih, id, ip) on a stride (sh, sd, sp), those above both
/// horizons, each weighted by the measure d wo d wi of the bins it stands for (model_fit.h).
struct Pairs {
    std::vector<double> values;  // BB_FIT_PAIR_VALUES per pair
    std::vector<int> bins;       // the MERL index of each pair's node
    std::vector<Vec3> wo, wi;
};

Pairs make_pairs(int sh, int sd, int sp) {
    Pairs p;
    const auto theta_h = [](int i) { return double(i) * i / (90.0 * 90.0) * kPi / 2; };
    for (int ih = 0; ih < BB_MERL_THETA_H; ih += sh) {
        const double wh = std::cos(theta_h(ih)) - std::cos(theta_h(std::min(ih + sh, BB_MERL_THETA_H)));
        for (int id = 0; id < BB_MERL_THETA_D; id += sd) {
            const double a = id * kPi / 180, b = std::min(id + sd, BB_MERL_THETA_D) * kPi / 180;
            const double wd = 0.5 * (std::sin(b) * std::sin(b) - std::sin(a) * std::sin(a));
            for (int ip = 0; ip < BB_MERL_PHI_D; ip += sp) {
                const double wp = (std::min(ip + sp, BB_MERL_PHI_D) - ip) * kPi / 180;
                Vec3 wo, wi;
                merl_node_dirs(ih, id, ip, wo, wi);
                if (!(wo[2] > 0 && wi[2] > 0)) continue;
                p.values.insert(p.values.end(), {wo[0], wo[1], wo[2], wi[0], wi[1], wi[2], 4 * wh * wd * wp});
                p.bins.push_back(bb_merl_index(ih, id, ip));
                p.wo.push_back(wo);
                p.wi.push_back(wi);
            }
        }
    }
    return p;
}

double compress(int metric, double v) {
    if (metric == BB_FIT_METRIC_CBRT) return std::cbrt(v);
    if (metric == BB_FIT_METRIC_LOG) return std::log1p(v);
    return v;
}

/// The compressed target g(f cos theta_i) of every channel at every pair (channel-major), -1
/// where the target is unmeasured; the measured weight of each channel.
struct Targets {
    std::vector<double> t;
    std::vector<double> measured_weight, unmeasured_share;
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
        for (size_t j = 0; j < n; ++j) {
            const double w = pairs.values[j * BB_FIT_PAIR_VALUES + 6];
            all += w;
            if (!std::isfinite(f[j])) throw Error("the target '" + m.canonical + "' is not finite at a direction pair");
            if (f[j] < 0) {
                out.t.push_back(-1.0);
                continue;
            }
            measured += w;
            out.t.push_back(compress(metric, f[j] * pairs.wi[j][2]));
        }
        if (!(measured > 0)) throw Error("the target '" + m.canonical + "' has no measured bin above the horizon");
        out.measured_weight.push_back(measured);
        out.unmeasured_share.push_back(1.0 - measured / all);
    }
    return out;
}

/// One candidate: the channel it is fitted to, and its free parameters x (model_fit.h's maps).
struct Candidate {
    size_t channel;
    std::vector<double> x;
};

/// The objective on the device: sum_j w_j (g(f_c cos) - t_j)^2 per candidate (kernels/fit.cl).
class Objective {
public:
    Objective(Engine& engine, const ModelFitRequest& r, const Pairs& pairs, const Targets& targets, int metric)
        : engine_(engine), r_(r), bufs_(engine, r.precision), n_(pairs.bins.size()), metric_(metric),
          amplitude_(amplitude_named(r.amplitude)) {
        pairs_ = bufs_.input(pairs.values);
        targets_ = bufs_.input(targets.t);
        const ModelConfig m = resolve_model(model_spec_with_alpha(r.model, 0.5));
        fresnel_kind_ = resolve_fresnel(amplitude_spec(amplitude_, 0.5)).kind;
        BuildRequest build;
        build.kernel_file = "fit.cl";
        build.precision = r.precision;
        build.model = m.id;
        build.fresnel = fresnel_kind_;
        kernel_ = cl::Kernel(engine.program(build), BB_ENTRY_NAME(BB_ENTRY_MODEL_FIT_OBJECTIVE));
        data_ = model_data_buffer(bufs_, m.id);
    }

    /// The parameters of a candidate's x: (alpha, amplitude).
    std::pair<double, double> parameters(const std::vector<double>& x) const {
        return {alpha_of(x[0]), has_parameter(amplitude_) ? logistic(x[1]) : 1.0};
    }
    std::string model_spec(double alpha) const { return resolve_model(model_spec_with_alpha(r_.model, alpha)).canonical; }
    std::string fresnel_spec(double amplitude) const { return resolve_fresnel(amplitude_spec(amplitude_, amplitude)).canonical; }

    std::vector<double> operator()(const std::vector<Candidate>& cands) {
        throw_if_cancelled();
        std::vector<double> mp, fp;
        std::vector<cl_uint> channel;
        for (const Candidate& c : cands) {
            const auto [alpha, amp] = parameters(c.x);
            const ModelConfig m = resolve_model(model_spec_with_alpha(r_.model, alpha));
            const FresnelConfig f = resolve_fresnel(amplitude_spec(amplitude_, amp));
            mp.insert(mp.end(), m.params.begin(), m.params.end());
            fp.insert(fp.end(), f.params.begin(), f.params.end());
            channel.push_back(cl_uint(c.channel));
        }
        const size_t blocks = (n_ + kBlock - 1) / kBlock, items = cands.size() * blocks;
        cl::Buffer b_mp = bufs_.input(mp), b_fp = bufs_.input(fp);
        cl::Buffer b_ch(engine_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, channel.size() * sizeof(cl_uint),
                        channel.data());
        cl::Buffer b_out = bufs_.output(items);
        set_args(kernel_, 0, pairs_, targets_, cl_uint(n_), b_mp, b_fp, b_ch, cl_uint(cands.size()), cl_uint(kBlock),
                 cl_int(metric_), data_, b_out);
        engine_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange,
                                             cl::NDRange((items + kLocalSize - 1) / kLocalSize * kLocalSize),
                                             cl::NDRange(kLocalSize));
        const std::vector<double> parts = bufs_.read(b_out, items);
        std::vector<double> out(cands.size(), 0.0);
        for (size_t c = 0; c < cands.size(); ++c)
            for (size_t b = 0; b < blocks; ++b) out[c] += parts[c * blocks + b];
        return out;
    }

private:
    Engine& engine_;
    const ModelFitRequest& r_;
    RealBuffers bufs_;
    size_t n_;
    int metric_;
    const FitAmplitude& amplitude_;
    int fresnel_kind_ = 0;
    cl::Kernel kernel_;
    cl::Buffer pairs_, targets_, data_;
};

std::vector<ModelConfig> channel_models(const ModelFitRequest& r, std::vector<std::string>& names) {
    std::vector<ModelConfig> out;
    for (const auto& [name, spec] : target_channels(r.target)) {
        names.push_back(name);
        out.push_back(resolve_model(spec));
    }
    return out;
}

/// Multi-start minimisation: per channel, alpha on a grid of starts (amplitude 1/2) evaluated in
/// one launch, Nelder-Mead from the best of them (restarted once around its minimum).
std::vector<Minimum> minimise(Objective& objective, size_t n_channels, bool amplitude, int max_evaluations) {
    std::vector<Candidate> grid;
    for (size_t c = 0; c < n_channels; ++c)
        for (double a : {0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 0.8}) {
            const double x0 = logit((a - kAlphaLo) / (kAlphaHi - kAlphaLo));
            grid.push_back({c, amplitude ? std::vector<double>{x0, 0.0} : std::vector<double>{x0}});
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
    nm.steps.assign(amplitude ? 2 : 1, 0.3);
    nm.max_evaluations = max_evaluations;
    nm.value_tolerance = HUGE_VAL;  // converged on the simplex's size alone
    nm.size_tolerance = 1e-5;  // in the logistic variables: alpha to ~3e-6
    const BatchObjective f = [&](const std::vector<size_t>& problem, const std::vector<std::vector<double>>& xs) {
        std::vector<Candidate> cands;
        for (size_t i = 0; i < xs.size(); ++i) cands.push_back({problem[i], xs[i]});
        return objective(cands);
    };
    return minimize_batch(starts, nm, f);
}

}  // namespace

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
    static const std::vector<FitAmplitude> terms = {
        {"scale", "gen-schlick:f0=%s,f90=%s", "F = s, a constant in [0, 1] (default)"},
        {"schlick", "schlick:f0=%s", "Schlick 1994 with f0 in [0, 1]"},
        {"none", "none", "F = 1: alpha alone"},
    };
    return terms;
}

void check_model_fit_request(const ModelFitRequest& r) {
    metric_named(r.metric);
    const FitAmplitude& amp = amplitude_named(r.amplitude);
    if (r.stride < 1 || r.stride > 15) throw Error("--stride must be 1 to 15");
    if (r.max_evaluations < 20) throw Error("--max-evaluations must be at least 20");
    const Spec base = parse_spec(r.model);
    for (const auto& kv : base.keys)
        if (kv.first == "alpha" || kv.first == "alpha_x" || kv.first == "alpha_y" || kv.first == "roughness")
            throw Error("--model '" + r.model + "': leave " + kv.first + " out, the fit finds alpha (e.g. --model " +
                        base.name + ")");
    const ModelConfig m = resolve_model(model_spec_with_alpha(r.model, 0.5));
    if (m.traits().alpha_x_slot < 0 || m.traits().measured)
        throw Error("--model '" + m.name + "' has no roughness alpha to fit; fit a microfacet model such as ggx or beckmann");
    if (has_parameter(amp) && !m.uses_fresnel)
        throw Error("--model '" + m.name + "' has no Fresnel term to carry --fresnel " + amp.name + "; use --fresnel none");
    resolve_fresnel(r.target_fresnel);
    std::vector<std::string> names;
    for (const ModelConfig& t : channel_models(r, names))
        if (!t.traits().measured && t.uses_fresnel == false && r.target_fresnel != "none")
            throw Error("--target '" + t.name + "' has no Fresnel term; drop --target-fresnel");
}

ModelFitResult fit_model(Engine& engine, const ModelFitRequest& r) {
    check_model_fit_request(r);
    const int metric = metric_named(r.metric).id;
    std::vector<std::string> names;
    const std::vector<ModelConfig> channels = channel_models(r, names);
    ModelFitResult result;
    if (channels[0].traits().measured) result.unmeasured_bins = merl_table_info(int(channels[0].params[BB_MERL_TABLE])).unmeasured;

    const Pairs pairs = make_pairs(r.stride, r.stride, 2 * r.stride);
    const Targets targets = make_targets(engine, r, channels, pairs, metric);
    result.pairs = pairs.bins.size();
    Objective objective(engine, r, pairs, targets, metric);
    const bool amplitude = has_parameter(amplitude_named(r.amplitude));
    const std::vector<Minimum> minima = minimise(objective, channels.size(), amplitude, r.max_evaluations);
    // The distance over every bin (stride 1): the fit's pairs are a subset, on which the minimum
    // is biased low.
    const Pairs all = r.stride == 1 ? Pairs() : make_pairs(1, 1, 1);
    const Targets all_targets = r.stride == 1 ? targets : make_targets(engine, r, channels, all, metric);
    result.all_pairs = r.stride == 1 ? result.pairs : all.bins.size();
    Objective all_objective(engine, r, r.stride == 1 ? pairs : all, all_targets, metric);
    std::vector<Candidate> finals;
    for (size_t c = 0; c < channels.size(); ++c) finals.push_back({c, minima[c].x});
    const std::vector<double> all_values = all_objective(finals);

    for (size_t c = 0; c < channels.size(); ++c) {
        const Minimum& m = minima[c];
        ChannelFit f;
        f.channel = names[c];
        std::tie(f.alpha, f.amplitude) = objective.parameters(m.x);
        f.model_spec = objective.model_spec(f.alpha);
        f.fresnel_spec = objective.fresnel_spec(f.amplitude);
        f.distance_fit = std::sqrt(std::max(0.0, m.value) / targets.measured_weight[c]);
        f.distance = std::sqrt(std::max(0.0, all_values[c]) / all_targets.measured_weight[c]);
        f.unmeasured_share = all_targets.unmeasured_share[c];
        f.evaluations = m.evaluations + 10;  // and the grid of starts
        if (!std::isfinite(f.distance) || !std::isfinite(f.alpha)) throw Error("the fit of channel '" + f.channel + "' is not finite");
        result.channels.push_back(f);
    }
    return result;
}

}  // namespace fit
}  // namespace brdfbake

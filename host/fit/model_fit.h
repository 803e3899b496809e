// Fitting an analytic model's free parameters to a target BRDF (`brdfbake fit`): a measured MERL
// file (host/models/merl_file.h) or any model spec. The free parameters are the microfacet
// roughness alpha (or alpha_x and alpha_y) and the Fresnel term's parameters, per colour channel; the
// objective is evaluated on the device (kernels/fit.cl) over the MERL grid's direction pairs and
// minimised by the batched Nelder-Mead of nelder_mead.h, every channel and start in one launch
// per round.
//
// The distance (the metric, fit_metrics()): with g the metric's compression,
//   d = sqrt( sum_j w_j (g(f_fit cos theta_i) - g(f_target cos theta_i))^2 / sum_j w_j )
// over the pairs j whose target is measured, w_j the pair's share of the measure d wo d wi
// = 4 cos theta_d sin theta_h sin theta_d d theta_h d phi_h d theta_d d phi_d (Rusinkiewicz 1998,
// the half/difference change of variables) integrated over the bins the pair stands for. The
// default compression is the cube root of Ngan, Durand and Matusik 2005 ("Experimental Analysis
// of BRDF Models", EGSR 2005, sec. 4), who fit the cosine-weighted BRDF so compressed.
#pragma once

#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace brdfbake {
namespace fit {

/// A metric of the fit: its name on the command line, the kernel's compression
/// (BB_FIT_METRIC_*) and a description.
struct FitMetric {
    const char* name;
    int id;
    const char* description;
};
const std::vector<FitMetric>& fit_metrics();

/// A free parameter of the fit: its name (in the specs and in "params"), its range (the fit
/// maps the whole real line onto it by a logistic, so that no step leaves it) and its start.
struct FitParameter {
    const char* name;
    double lo, hi, start;
};

/// The fitted Fresnel term (`--fresnel NAME`): a Fresnel spec with free parameters, written
/// {name} where each goes (or none): `scale` F = s (gen-schlick with f0 = f90 = s), `schlick`
/// Schlick's f0, `conductor` the exact conductor's eta and k, `none` F = 1.
struct FitAmplitude {
    const char* name;
    const char* spec;
    std::vector<FitParameter> params;
    const char* description;
};
const std::vector<FitAmplitude>& fit_amplitudes();

struct ModelFitRequest {
    std::string target;                  // a model spec: merl:file=... or any analytic model
    std::string target_fresnel = "none"; // the target's Fresnel term (analytic targets)
    std::string model = "ggx";           // the fitted model, without alpha (ggx, beckmann, keys)
    std::string amplitude = "scale";     // fit_amplitudes()
    std::string metric = "cbrt";         // fit_metrics()
    int stride = 2;                      // fit on every stride-th bin along theta_h and theta_d,
                                         // every 2 stride-th along phi_d; the distance on all bins
    Precision precision = Precision::Double;
    int max_evaluations = 0;             // per start; 0: evaluation_budget(free parameters)
    bool anisotropic = false;            // fit alpha_x and alpha_y (automatic for an anisotropic target)
    bool diffuse = false;                // fit a Lambert weight kd beside the lobe (the model's diffuse=KD)
};

/// The default budget of objective evaluations per start for a fit of n free parameters
/// (model_fit.cpp measures what the fits need).
int evaluation_budget(size_t n);

/// A fitted parameter and its standard error (fit_model's estimate, model_fit.cpp: the sandwich
/// covariance of the weighted least-squares fit; 0 for a target the model matches exactly).
struct FittedParameter {
    std::string name;  // alpha, or alpha_x and alpha_y; diffuse (--diffuse); then the Fresnel term's (FitParameter)
    double value = 0;
    double error = 0;
};

struct ChannelFit {
    std::string channel;        // r, g, b, y, or "" for an analytic target
    std::vector<FittedParameter> params;
    std::string model_spec;     // the fitted spec, usable as --model as it stands
    std::string fresnel_spec;   // usable as --fresnel
    double distance = 0;        // d over every bin (stride 1)
    double distance_fit = 0;    // d over the fit's pairs (what was minimised)
    double unmeasured_share = 0;  // the share of the pair measure whose target is unmeasured
    int evaluations = 0;
    int budget = 0;             // the minimiser's budget (evaluations per start)
    bool converged = true;      // false: the budget stopped the minimiser before it converged
};

struct ModelFitResult {
    std::vector<ChannelFit> channels;
    std::size_t pairs = 0;       // the fit's pairs above both horizons
    std::size_t all_pairs = 0;   // every bin's pair above both horizons
    std::size_t unmeasured_bins = 0;  // the target file's unmeasured bins (merl targets)
};

/// Checks every input (throws Error naming the mistake) before any device work, then fits.
ModelFitResult fit_model(Engine& engine, const ModelFitRequest& request);

/// Checks a request's specs and names without a device; throws Error naming the mistake.
void check_model_fit_request(const ModelFitRequest& request);

}  // namespace fit
}  // namespace brdfbake

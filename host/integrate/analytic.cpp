// Closed-form albedo of the delta lobes: the shared formulas of brdf/specular.h, in double.
#include "brdfbake/analytic.h"

#include <cmath>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "models/params.h"

namespace brdfbake {
namespace {

void check_mu(double mu) {
    if (!(mu > 0.0 && mu <= 1.0)) throw Error("mu must lie in (0, 1]; got " + std::to_string(mu));
}

}  // namespace

bool has_analytic_albedo(const ModelConfig& model) { return model.traits().delta; }

// A delta lobe's sampler is deterministic (the mirror direction) and its weight is the
// reflected fraction of energy: the albedo itself (brdf/specular.h), whatever u.
bool analytic_albedo(const ModelConfig& model, const FresnelConfig& fresnel, double mu, double& value) {
    if (!has_analytic_albedo(model)) return false;
    check_mu(mu);
    value = bb_model_sample(model.id, to_bb_params(model.params), fresnel.kind, to_bb_params(fresnel.params),
                            bb_dir_from_mu_phi(mu, 0.0), 0.0, 0.0)
                .weight;
    return true;
}

double analytic_albedo_error(double value) {
    // The exact Fresnel forms take about 20 double operations; 64 ulps bounds their rounding.
    return 64.0 * 2.220446049250313e-16 * std::fmax(std::fabs(value), 1e-300);
}

bool analytic_transmission(const ModelConfig& model, double mu, SpecularTransmission& out) {
    if (model.id != BB_MODEL_DIELECTRIC_SPECULAR) return false;
    check_mu(mu);
    const double eta = model.params[BB_DIELECTRIC_SPECULAR_ETA];
    out.energy = bb_dielectric_specular_transmittance(to_bb_params(model.params), mu);
    out.radiance_factor = eta * eta;
    return true;
}

AlbedoResult analytic_albedo_result(const ModelConfig& model, const FresnelConfig& fresnel,
                                    const std::vector<AlbedoCell>& cells) {
    AlbedoResult r;
    r.method = "analytic (delta lobe: albedo = F(mu))";
    for (const AlbedoCell& c : cells) {
        double v = 0.0;
        if (!analytic_albedo(model, fresnel, c.mu, v))
            throw Error("internal error: model '" + model.name + "' has no analytic albedo");
        r.values.push_back({v, analytic_albedo_error(v)});
    }
    return r;
}

AlbedoResult albedo_of_model(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                             const AlbedoRequest& request, const ToleranceRequest& tolerance) {
    if (request.model != model.id) throw Error("albedo_of_model: the request is for another model");
    if (has_analytic_albedo(model)) return analytic_albedo_result(model, fresnel, request.cells);
    if (tolerance.tolerance > 0.0) return compute_albedo_to_tolerance(engine, request, tolerance);
    return compute_albedo(engine, request);
}

}  // namespace brdfbake

// Closed-form directional albedo of the delta lobes (mirror, dielectric-specular), which are
// never integrated by Monte Carlo. The formulas are those of brdf/specular.h,
// evaluated on the host in double.
#pragma once

#include "brdfbake/albedo.h"
#include "brdfbake/spec.h"

namespace brdfbake {

/// True for the models whose albedo is analytic (the delta lobes).
bool has_analytic_albedo(const ModelConfig& model);

/// Directional albedo E(mu) of a delta lobe: F(mu) of `fresnel` for `mirror`, the exact
/// dielectric reflectance F(mu, eta) for `dielectric-specular` (which ignores `fresnel`; its
/// spec carries eta). Sets `value` and returns true for those models; returns false, leaving
/// `value` alone, for every other model. mu must lie in (0, 1]. The value is exact up to the
/// rounding of a few double operations: report an error of analytic_albedo_error(value).
bool analytic_albedo(const ModelConfig& model, const FresnelConfig& fresnel, double mu, double& value);

/// The rounding bound to report with an analytic albedo (a few ulps of the value).
double analytic_albedo_error(double value);

/// The albedo of a delta lobe at every cell, in the form compute_albedo returns (method
/// "analytic", no samples). Throws Error for a model without an analytic albedo.
AlbedoResult analytic_albedo_result(const ModelConfig& model, const FresnelConfig& fresnel,
                                    const std::vector<AlbedoCell>& cells);

/// The directional albedo of any model at every cell of `request` (whose model must be `model`):
/// the closed form for a delta lobe, else the kernels, refined to `tolerance` when it is given
/// (tolerance.tolerance > 0), else at request.samples. The one dispatch the command line, the
/// scene bake and the Python module share.
AlbedoResult albedo_of_model(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                             const AlbedoRequest& request, const ToleranceRequest& tolerance);

/// Specular transmission of `dielectric-specular` at mu: the transmitted energy fraction
/// 1 - F(mu, eta) and the factor eta^2 by which the transmitted radiance is scaled (L/n^2 is
/// invariant across the interface; light crossing into the far side).
struct SpecularTransmission {
    double energy = 0.0;
    double radiance_factor = 1.0;
};

/// Sets `out` and returns true for `dielectric-specular`; false for every other model.
bool analytic_transmission(const ModelConfig& model, double mu, SpecularTransmission& out);

}  // namespace brdfbake

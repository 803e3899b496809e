// Point evaluations of a model on the device (kernels/eval.cl), for scans and parity checks.
#pragma once

#include <array>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace brdfbake {

using Vec3 = std::array<double, 3>;

/// f(wo[i], wi[i]) (no cosine) for every pair, computed on the device.
std::vector<double> evaluate_on_device(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                       Precision precision, const std::vector<Vec3>& wo,
                                       const std::vector<Vec3>& wi);

struct DeviceSample {
    Vec3 wi;
    double weight;  // f cos(theta_i) / pdf
};

/// The model's importance sample for each wo[i] and uniform pair u[i], computed on the device.
std::vector<DeviceSample> sample_on_device(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                           Precision precision, const std::vector<Vec3>& wo,
                                           const std::vector<std::array<double, 2>>& u);

}  // namespace brdfbake

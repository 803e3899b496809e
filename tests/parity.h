// Host vs device parity: a model's evaluation and importance sample from the same shared headers
// in double on the host and in a PoCL kernel in float and double. Shared by test_parity.cpp
// (chosen specs) and the generic battery (test_model_battery.cpp, every registered model).
#pragma once

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "brdfbake/brdf/models.h"
#include "brdfbake/evaluate.h"
#include "models/params.h"
#include "support.h"

namespace testing {

/// A random direction of the upper hemisphere: cos(theta) uniform in [mu_min, 1], phi uniform.
inline brdfbake::Vec3 random_dir(std::mt19937& rng, double mu_min) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double mu = mu_min + (1.0 - mu_min) * u(rng), phi = 2 * M_PI * u(rng);
    const double s = std::sqrt(1 - mu * mu);
    return {s * std::cos(phi), s * std::sin(phi), mu};
}

/// Checks the device's evaluation and sample (float and double) of model m, Fresnel none, against
/// the host's at `points` random direction pairs and unit-square points, the directions down to
/// 1e-3 from the horizon (grazing angles, where float loses the most): relative tolerance 1e-11 in
/// double and 2e-4 in float (as the README states), with an absolute floor where the value is
/// too small for float to resolve it relatively (an evaluation below about 1e-5 underflows
/// towards 0: 1e-10; a sample weight below about 0.05: 1e-5; double: 1e-18 and 1e-15), and the
/// sampled wi.z to the relative tolerance as an absolute one. Measured over test_parity's
/// specs: float evaluations 1.8e-5 relative wherever |f| >= 1e-5, weights 4.8e-5 relative at
/// 0.1 and above.
inline void check_host_device_parity(const brdfbake::ModelConfig& m, const std::string& label, int points) {
    using namespace brdfbake;
    const FresnelConfig f = resolve_fresnel("none");
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<Vec3> wo, wi;
    std::vector<std::array<double, 2>> u;
    for (int i = 0; i < points; ++i) {
        wo.push_back(random_dir(rng, 1e-3));
        wi.push_back(random_dir(rng, 1e-3));
        u.push_back({uni(rng), uni(rng)});
    }
    for (Precision p : {Precision::Float, Precision::Double}) {
        const bool dbl = p == Precision::Double;
        const double tol = dbl ? 1e-11 : 2e-4;
        const double eval_floor = dbl ? 1e-18 : 1e-10, weight_floor = dbl ? 1e-15 : 1e-5;
        const std::vector<double> dev = evaluate_on_device(engine(), m, f, p, wo, wi);
        const std::vector<DeviceSample> ds = sample_on_device(engine(), m, f, p, wo, u);
        int bad_eval = 0, bad_sample = 0;
        double worst_eval = 0.0, worst_weight = 0.0;  // the largest relative differences, for the report
        for (size_t i = 0; i < wo.size(); ++i) {
            const bb_vec3 o = bb_v3(wo[i][0], wo[i][1], wo[i][2]), in = bb_v3(wi[i][0], wi[i][1], wi[i][2]);
            const double host = bb_model_eval(m.id, to_bb_params(m.params), f.kind, to_bb_params(f.params), o, in);
            bad_eval += !(std::fabs(dev[i] - host) <= tol * std::fabs(host) + eval_floor);
            if (host != 0) worst_eval = std::fmax(worst_eval, std::fabs(dev[i] - host) / std::fabs(host));
            const bb_sample hs =
                bb_model_sample(m.id, to_bb_params(m.params), f.kind, to_bb_params(f.params), o, u[i][0], u[i][1]);
            bad_sample += !(std::fabs(ds[i].weight - hs.weight) <= tol * std::fabs(hs.weight) + weight_floor &&
                            std::fabs(ds[i].wi[2] - hs.wi.z) <= tol);
            if (hs.weight != 0) worst_weight = std::fmax(worst_weight, std::fabs(ds[i].weight - hs.weight) / std::fabs(hs.weight));
        }
        INFO(label << " " << precision_name(p) << ": worst relative difference " << worst_eval << " (evaluation), "
                   << worst_weight << " (sample weight)");
        CHECK(bad_eval == 0);
        CHECK(bad_sample == 0);
    }
}

}  // namespace testing

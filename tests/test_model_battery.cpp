// The generic battery: every model of the registry (brdf/model_registry.h), each at its example
// spec, is held to the properties every BRDF model must have. A model gets these tests by being
// registered: white furnace bound, reciprocity (where its entry claims it, and its absence where
// it does not), host/kernel parity, its sampler against its evaluation, and finite values at the
// extremes. The truths come from outside the code under test: energy conservation (albedo <= 1),
// the Helmholtz reciprocity of physical BRDFs, and the identity of two independent estimators of
// one integral (the sampler's weights and the uniform-hemisphere integral of f cos).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "brdfbake/albedo.h"
#include "brdfbake/analytic.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/spec.h"
#include "models/params.h"
#include "parity.h"
#include "support.h"

using namespace brdfbake;

namespace {

const bb_params kNoFresnel = {{0}};

using testing::random_dir;

bb_vec3 v3(const Vec3& d) { return bb_v3(d[0], d[1], d[2]); }

double host_eval(const ModelConfig& m, const Vec3& wo, const Vec3& wi) {
    return bb_model_eval(m.id, to_bb_params(m.params), BB_FRESNEL_NONE, kNoFresnel, v3(wo), v3(wi));
}

AlbedoResult albedo(const ModelConfig& m, const std::vector<double>& mus, Method method, std::uint64_t samples) {
    AlbedoRequest req = testing::albedo_request(m.canonical, mus, method, Precision::Double, samples);
    return compute_albedo(testing::engine(), req);
}

}  // namespace

TEST_CASE("battery: every registered model resolves its example spec", "[battery][quick]") {
    CHECK(model_registry().size() == model_names().size());
    for (const ModelTraits& t : model_registry()) {
        INFO(t.name << ": " << t.example);
        // a layer's walk (sheen-volume) has no pointwise f: every pointwise command refuses it
        if (t.layer_walk) CHECK_THROWS_WITH(resolve_model(t.example), Catch::Contains("no pointwise value"));
        const ModelConfig m = resolve_model_simulated(t.example);
        CHECK(m.id == t.id);
        CHECK(m.name == t.name);
        CHECK(&m.traits() == &model_traits(t.id));
        // a roughness axis is a pair of slots or none, and roughness_slots agrees
        CHECK((t.alpha_x_slot >= 0) == (t.alpha_y_slot >= 0));
        if (t.alpha_x_slot >= 0)
            CHECK(roughness_slots(m) == std::vector<int>{t.alpha_x_slot, t.alpha_y_slot});
        else if (t.roughness_axis.key)  // a mapped key (oren-nayar's sigma, the Phong lobes' n)
            CHECK(roughness_slots(m) == std::vector<int>{t.roughness_axis.slot});
        else
            CHECK_THROWS_WITH(roughness_slots(m), Catch::Contains("has no roughness alpha to sweep"));
    }
}

TEST_CASE("battery: reciprocity where the registry claims it, and only there", "[battery][quick]") {
    for (const ModelTraits& t : model_registry()) {
        if (t.layer_walk) continue;  // no pointwise f (tests/test_sheen_volume_model.cpp)
        const ModelConfig m = resolve_model(t.example);
        std::mt19937 rng(17);
        int worse = 0, nonzero = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 a = random_dir(rng, 1e-3), b = random_dir(rng, 1e-3);
            const double f1 = host_eval(m, a, b), f2 = host_eval(m, b, a);
            nonzero += f1 > 0.0;
            worse += !(std::fabs(f1 - f2) <= 1e-12 * std::fmax(std::fabs(f1), std::fabs(f2)));
        }
        INFO(t.name << ": " << worse << " of 2000 pairs not reciprocal to 1e-12");
        if (t.reciprocal)
            CHECK(worse == 0);
        else
            CHECK(worse > 100);  // the flag is a claim: a non-reciprocal model must show it
        CHECK((nonzero > 0) == !t.delta);  // delta lobes have no finite values
    }
}

TEST_CASE("battery: host and kernel evaluate and sample alike, float and double", "[battery][parity][device]") {
    for (const ModelTraits& t : model_registry()) {
        if (t.layer_walk) continue;  // no pointwise f (tests/test_sheen_volume_model.cpp)
        const ModelConfig m = resolve_model(t.example);
        testing::check_host_device_parity(m, t.name, 1000);
    }
}

TEST_CASE("battery: white furnace, the albedo of an energy-conserving example is at most 1", "[battery][device]") {
    const std::vector<double> mus = {1e-3, 0.1, 0.5, 1.0};
    for (const ModelTraits& t : model_registry()) {
        if (t.layer_walk) continue;  // no pointwise f (tests/test_sheen_volume_model.cpp)
        if (!t.energy_conserving_example) continue;
        const ModelConfig m = resolve_model(t.example);
        const AlbedoResult r = has_analytic_albedo(m) ? analytic_albedo_result(m, resolve_fresnel("none"), cells_for(mus, 0.0, m.params))
                                                      : albedo(m, mus, Method::Quadrature, 4 * 64 * 64);
        for (size_t c = 0; c < mus.size(); ++c) {
            INFO(t.name << " mu " << mus[c] << ": E = " << r.values[c].value << " +- " << r.values[c].error);
            CHECK(r.values[c].value <= 1.0 + r.values[c].error);
            CHECK(r.values[c].value >= 0.0);
        }
    }
}

TEST_CASE("battery: the importance sampler integrates the model's own evaluation", "[battery][device]") {
    // The sampler's weights f cos / pdf (importance) and f cos itself under uniform hemisphere
    // points (qmc, nothing of the sampler) estimate one integral: they must agree within their
    // combined error estimates. A sampler whose density is not the one its weight assumes fails.
    const std::vector<double> mus = {0.05, 0.4, 1.0};
    for (const ModelTraits& t : model_registry()) {
        if (t.layer_walk) continue;  // no pointwise f (tests/test_sheen_volume_model.cpp)
        const ModelConfig m = resolve_model(t.example);
        const AlbedoResult imp = albedo(m, mus, Method::Importance, 1u << 14);
        if (t.delta) {  // eval is 0: the sampler's weight is the analytic albedo
            for (size_t c = 0; c < mus.size(); ++c) {
                double exact = 0.0;
                REQUIRE(analytic_albedo(m, resolve_fresnel("none"), mus[c], exact));
                CHECK(imp.values[c].value == Approx(exact).epsilon(1e-14));
            }
            continue;
        }
        const AlbedoResult uni = albedo(m, mus, Method::QuasiMonteCarlo, 1u << 18);
        for (size_t c = 0; c < mus.size(); ++c) {
            const AlbedoValue &a = imp.values[c], &b = uni.values[c];
            INFO(t.name << " mu " << mus[c] << ": importance " << a.value << " +- " << a.error << ", qmc " << b.value
                        << " +- " << b.error);
            CHECK(a.value > 0.0);
            CHECK(std::fabs(a.value - b.value) <= a.error + b.error);
            CHECK(b.error < 0.05 * b.value);  // the comparison has teeth
        }
    }
}

TEST_CASE("battery: finite and non-negative at the extremes", "[battery][quick]") {
    // mu = 1e-6 and 1 for wo, grazing wi, and alpha at its floor where the model has roughness;
    // the host's double and the sampler's weights too.
    const std::vector<double> mus = {1e-6, 1e-3, 0.5, 1.0};
    for (const ModelTraits& t : model_registry()) {
        if (t.layer_walk) continue;  // no pointwise f (tests/test_sheen_volume_model.cpp)
        std::vector<ModelConfig> configs = {resolve_model(t.example)};
        if (t.alpha_x_slot >= 0) {
            ModelConfig floor = configs.front();
            for (int s : roughness_slots(floor)) floor.params[s] = BB_ALPHA_MIN;
            configs.push_back(floor);
        }
        for (const ModelConfig& m : configs) {
            int bad = 0;
            for (double mo : mus)
                for (double mi : mus)
                    for (double dphi : {0.0, 0.5 * M_PI, M_PI}) {
                        const bb_vec3 wo = bb_dir_from_mu_phi(mo, 0.3), wi = bb_dir_from_mu_phi(mi, 0.3 + dphi);
                        const double f = bb_model_eval(m.id, to_bb_params(m.params), BB_FRESNEL_NONE, kNoFresnel, wo, wi);
                        bad += !(std::isfinite(f) && f >= 0.0);
                        for (double u1 : {0.0, 0.5, 1.0 - 1e-16})
                            for (double u2 : {0.0, 0.25, 1.0 - 1e-16}) {
                                const bb_sample s =
                                    bb_model_sample(m.id, to_bb_params(m.params), BB_FRESNEL_NONE, kNoFresnel, wo, u1, u2);
                                bad += !(std::isfinite(s.weight) && s.weight >= 0.0);
                            }
                    }
            INFO(m.canonical << " (alpha at the floor: " << (&m != &configs.front()) << ")");
            CHECK(bad == 0);
        }
    }
}

TEST_CASE("battery: the vector paths the registry gives a model agree with its scalar kernel", "[battery][device]") {
    // DISK or VSAMPLE: importance sampling on W lanes; VEVAL: qmc's uniform weights on W lanes;
    // quadrature: the half-vector rule, or the sampler's square where the sampler (the cosine
    // warp's rule: the evaluation) is branch-free, one row per lane. The same points and the same
    // shared functions as the scalar kernel: the same sums up to rounding, in float.
    const bool cpu = testing::engine().device().type == "cpu";
    const std::vector<double> mus = {0.02, 0.3, 1.0};
    for (const ModelTraits& t : model_registry()) {
        if (t.layer_walk) continue;  // no pointwise f (tests/test_sheen_volume_model.cpp)
        std::vector<Method> methods;
        if (t.samples_disk || t.samples_vector) methods.push_back(Method::Importance);
        if (t.evals_vector) methods.push_back(Method::QuasiMonteCarlo);
        if (!t.delta && (t.halfvector_quadrature || (t.cosine_sampler ? t.evals_vector : t.samples_vector)))
            methods.push_back(Method::Quadrature);
        const ModelConfig m = resolve_model(t.example);
        for (Method method : methods) {
            AlbedoRequest req = testing::albedo_request(t.example, mus, method, Precision::Float, 1u << 14);
            req.cells = cells_for(mus, 0.3, m.params);
            req.vector_width = 1;
            const AlbedoResult s = compute_albedo(testing::engine(), req);
            req.vector_width = 0;
            const AlbedoResult v = compute_albedo(testing::engine(), req);
            CHECK(s.vector_width == 1);
            CHECK((v.vector_width > 1) == cpu);
            for (size_t c = 0; c < mus.size(); ++c) {
                INFO(t.name << " " << method_name(method) << " mu " << mus[c] << ": scalar " << s.values[c].value
                            << " +- " << s.values[c].error << ", vector " << v.values[c].value);
                CHECK(std::fabs(s.values[c].value - v.values[c].value) <= s.values[c].error);
                CHECK(std::fabs(s.values[c].value - v.values[c].value) <= 2e-5);
            }
        }
    }
}

// The albedo kernel's vector path (real = float16 / double8, tabulated disk points) against its
// scalar path: one shared source, the same estimator, so the same answer within the error.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/spec.h"
#include "support.h"

using namespace brdfbake;

namespace {

AlbedoResult run_lanes(const std::string& spec, const std::string& fresnel, Precision p, unsigned lanes,
                       std::uint64_t samples = 1 << 14, Method method = Method::Importance) {
    const ModelConfig m = resolve_model(spec);
    AlbedoRequest req;
    req.method = method;
    req.model = m.id;
    req.fresnel = resolve_fresnel(fresnel);
    req.cells = cells_for({0.02, 0.1, 0.3, 0.5, 0.8, 1.0}, 0.3, m.params);
    req.precision = p;
    req.samples = samples;
    req.vector_width = lanes;
    return compute_albedo(testing::engine(), req);
}

}  // namespace

TEST_CASE("GGX albedo: vector and scalar kernels agree within the error estimate", "[albedo][parity][device]") {
    const bool fp64 = testing::engine().device().fp64;
    for (const char* spec : {"ggx:alpha=0.05,shadowing=correlated", "ggx:alpha=0.5,shadowing=separable",
                             "ggx:alpha_x=0.2,alpha_y=0.9", "ggx:alpha=1"})
        for (const char* fresnel : {"none", "schlick:f0=0.04", "conductor:eta=0.2,k=3"})
            for (Precision p : {Precision::Float, Precision::Double}) {
                if (p == Precision::Double && !fp64) continue;
                const unsigned lanes = p == Precision::Float ? 16 : 8;
                const AlbedoResult s = run_lanes(spec, fresnel, p, 1);
                const AlbedoResult v = run_lanes(spec, fresnel, p, lanes);
                CHECK(s.vector_width == 1);
                CHECK(v.vector_width == lanes);
                for (size_t i = 0; i < s.values.size(); ++i) {
                    INFO(spec << " " << fresnel << " " << precision_name(p) << " cell " << i << ": scalar "
                              << s.values[i].value << " +- " << s.values[i].error << ", vector " << v.values[i].value
                              << " +- " << v.values[i].error);
                    CHECK(std::fabs(s.values[i].value - v.values[i].value) <= s.values[i].error);
                    CHECK(std::fabs(s.values[i].value - v.values[i].value) <= v.values[i].error);
                    // Same points, same shifts: only rounding differs.
                    CHECK(std::fabs(s.values[i].value - v.values[i].value) <=
                          (p == Precision::Float ? 2e-5 : 1e-12));
                }
            }
}

TEST_CASE("albedo of every model with a branch-free sampler: the generic vector kernel gives the scalar answer",
          "[albedo][parity][device]") {
    // albedo_replicas_points (the rotated Hammersley points tabulated in the kernel's precision,
    // bb_model_sample on W lanes) against the scalar kernel: the same points to the last bit,
    // the same shared sampler, so the same sums up to rounding. Grazing to normal incidence.
    const bool fp64 = testing::engine().device().fp64;
    const bool cpu = testing::engine().device().type == "cpu";
    struct Case {
        const char* spec;
        const char* fresnel;
    };
    const Case cases[] = {{"lambert", "none"},
                          {"oren-nayar:sigma=0.5", "none"},
                          {"phong:n=20", "none"},
                          {"phong-original:n=200", "none"},
                          {"blinn-phong:n=20", "none"},
                          {"blinn-phong:n=2000", "none"},
                          {"torrance-sparrow:alpha=0.3", "schlick:f0=0.04"},
                          {"torrance-sparrow:d=blinn,n=50", "none"},
                          {"torrance-sparrow:d=ggx,alpha=0.05", "conductor:eta=0.2,k=3"},
                          {"beckmann:alpha=0.3", "none"},
                          {"beckmann:alpha_x=0.05,alpha_y=0.6,shadowing=separable", "conductor:eta=0.2,k=3"},
                          {"beckmann:alpha=1", "schlick:f0=0.04"}};
    for (const Case& c : cases) {
        const ModelConfig m = resolve_model(c.spec);
        CHECK(bb_model_samples_vector(m.id) == 1);
        for (Precision p : {Precision::Float, Precision::Double}) {
            if (p == Precision::Double && !fp64) continue;
            const unsigned lanes = p == Precision::Float ? 16 : 8;
            const AlbedoResult s = run_lanes(c.spec, c.fresnel, p, 1);
            const AlbedoResult v = run_lanes(c.spec, c.fresnel, p, 0);
            CHECK(s.vector_width == 1);
            CHECK(v.vector_width == (cpu ? lanes : 1u));
            for (size_t i = 0; i < s.values.size(); ++i) {
                INFO(c.spec << " " << c.fresnel << " " << precision_name(p) << " cell " << i << ": scalar "
                            << s.values[i].value << " +- " << s.values[i].error << ", vector " << v.values[i].value);
                CHECK(std::fabs(s.values[i].value - v.values[i].value) <= s.values[i].error);
                CHECK(std::fabs(s.values[i].value - v.values[i].value) <= (p == Precision::Float ? 2e-5 : 1e-12));
            }
        }
    }
}

TEST_CASE("qmc albedo of every model with a branch-free evaluation: vector and scalar kernels agree",
          "[albedo][parity][device]") {
    // The uniform hemisphere weights of the qmc method on W lanes (-D BB_VECTOR_UNIFORM) against
    // the scalar kernel, on the same rotated Hammersley points.
    const bool fp64 = testing::engine().device().fp64;
    const bool cpu = testing::engine().device().type == "cpu";
    for (const char* spec : {"ggx:alpha=0.3", "ggx:alpha_x=0.1,alpha_y=0.6", "beckmann:alpha=0.3", "lambert",
                             "oren-nayar:sigma=0.5", "phong:n=20", "phong-original:n=20", "blinn-phong:n=20",
                             "torrance-sparrow:alpha=0.3"})
        for (const char* fresnel : {"none", "schlick:f0=0.04"}) {
            const ModelConfig m = resolve_model(spec);
            if (!m.uses_fresnel && std::string(fresnel) != "none") continue;
            CHECK(bb_model_evals_vector(m.id) == 1);
            for (Precision p : {Precision::Float, Precision::Double}) {
                if (p == Precision::Double && !fp64) continue;
                const unsigned lanes = p == Precision::Float ? 16 : 8;
                const AlbedoResult s = run_lanes(spec, fresnel, p, 1, 1 << 14, Method::QuasiMonteCarlo);
                const AlbedoResult v = run_lanes(spec, fresnel, p, 0, 1 << 14, Method::QuasiMonteCarlo);
                CHECK(s.vector_width == 1);
                CHECK(v.vector_width == (cpu ? lanes : 1u));
                for (size_t i = 0; i < s.values.size(); ++i) {
                    INFO(spec << " " << fresnel << " " << precision_name(p) << " cell " << i << ": scalar "
                              << s.values[i].value << " +- " << s.values[i].error << ", vector " << v.values[i].value);
                    CHECK(std::fabs(s.values[i].value - v.values[i].value) <= s.values[i].error);
                    CHECK(std::fabs(s.values[i].value - v.values[i].value) <= (p == Precision::Float ? 2e-5 : 1e-12));
                }
            }
        }
}

TEST_CASE("GGX albedo: every vector width gives the scalar answer", "[albedo][parity][device]") {
    const AlbedoResult s = run_lanes("ggx:alpha=0.3", "none", Precision::Float, 1, 1 << 12);
    for (unsigned lanes : {2u, 4u, 8u, 16u}) {
        const AlbedoResult v = run_lanes("ggx:alpha=0.3", "none", Precision::Float, lanes, 1 << 12);
        CHECK(v.vector_width == lanes);
        for (size_t i = 0; i < s.values.size(); ++i) CHECK(std::fabs(s.values[i].value - v.values[i].value) <= 2e-5);
    }
}

TEST_CASE("GGX albedo: the vector path falls back to scalar for ragged point counts", "[albedo][device]") {
    // 16 replicas x 17 points: not a multiple of 16 lanes.
    const AlbedoResult r = run_lanes("ggx:alpha=0.3", "none", Precision::Float, 0, 16 * 17);
    CHECK(r.vector_width == 1);
    const AlbedoResult v = run_lanes("ggx:alpha=0.3", "none", Precision::Float, 0, 16 * 32);
    CHECK(v.vector_width == (testing::engine().device().type == "cpu" ? 16u : 1u));
}

TEST_CASE("GGX albedo: the vector path counts non-finite parameters and refuses", "[albedo][device]") {
    const ModelConfig m = resolve_model("ggx:alpha=0.5");
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = resolve_fresnel("none");
    req.cells = cells_for({0.5}, 0.0, m.params);
    req.cells[0].params[BB_GGX_ALPHA_X] = std::numeric_limits<double>::quiet_NaN();
    req.samples = 1 << 10;
    req.vector_width = 16;
    CHECK_THROWS_AS(compute_albedo(testing::engine(), req), NonFiniteError);
}

TEST_CASE("Build options choose the vector path in one place", "[albedo][device]") {
    Engine& e = testing::engine();
    BuildRequest b;
    b.kernel_file = "albedo.cl";
    b.has_vector_path = true;
    const bool cpu = e.device().type == "cpu";
    CHECK((e.build_options(b).find("BB_VECTOR_WIDTH=16") != std::string::npos) == cpu);
    b.vector_width = 1;
    CHECK(e.build_options(b).find("BB_VECTOR_WIDTH") == std::string::npos);
    b.has_vector_path = false;
    b.vector_width = 0;
    CHECK(e.build_options(b).find("BB_VECTOR_WIDTH") == std::string::npos);
    CHECK(e.build_options(b).find("fast-relaxed") == std::string::npos);
    // A vector path's options only where the build has lanes; the model and Fresnel always.
    b.has_vector_path = true;
    b.vector_width = 4;
    b.model = BB_MODEL_PHONG;
    b.fresnel = BB_FRESNEL_SCHLICK;
    b.vector_path = VectorPath::UniformPoints;
    const std::string uniform = e.build_options(b);
    CHECK(uniform.find(" -D BB_VECTOR_POINTS=1 -D BB_VECTOR_UNIFORM=1") != std::string::npos);
    CHECK(uniform.find(" -D BB_MODEL=" + std::to_string(BB_MODEL_PHONG)) != std::string::npos);
    b.vector_width = 1;
    const std::string scalar = e.build_options(b);
    CHECK(scalar.find("BB_VECTOR_") == std::string::npos);
    CHECK(scalar.find(" -D BB_FRESNEL=" + std::to_string(BB_FRESNEL_SCHLICK)) != std::string::npos);
}

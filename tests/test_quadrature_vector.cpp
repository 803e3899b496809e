// The quadrature kernel's vector path (albedo_quadrature_rows: one row of the half-vector rule
// per lane, real = float16 / double8) against its scalar kernel: the same nodes, weights and
// shared functions, so the same sums to rounding.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/spec.h"
#include "support.h"

using namespace brdfbake;

namespace {

AlbedoResult run_quad(const std::string& spec, const std::string& fresnel, Precision p, unsigned lanes,
                      std::uint64_t samples, double phi) {
    const ModelConfig m = resolve_model(spec);
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = resolve_fresnel(fresnel);
    req.cells = cells_for({1e-4, 0.01, 0.2, 0.6, 1.0}, phi, m.params);
    req.method = Method::Quadrature;
    req.precision = p;
    req.samples = samples;
    req.vector_width = lanes;
    return compute_albedo(testing::engine(), req);
}

bool cpu() { return testing::engine().device().type == "cpu"; }

}  // namespace

TEST_CASE("Quadrature: vector and scalar kernels agree to rounding", "[albedo][quadrature][parity][device]") {
    const bool fp64 = testing::engine().device().fp64;
    const char* specs[] = {"ggx:alpha=0.001",
                           "ggx:alpha=0.01,shadowing=separable",
                           "ggx:alpha=0.2",
                           "ggx:alpha=1",
                           "ggx:alpha_x=0.01,alpha_y=0.5",
                           "ggx:alpha_x=1,alpha_y=0.001",
                           "beckmann:alpha=0.05",
                           "beckmann:alpha_x=0.3,alpha_y=0.02,shadowing=separable",
                           "torrance-sparrow:d=ggx,alpha=0.1",
                           "torrance-sparrow:d=beckmann,alpha_x=0.4,alpha_y=0.1",
                           "torrance-sparrow:d=blinn,n=200",
                           "blinn-phong:n=50",
                           "blinn-phong:n=10000,normalized=1"};
    double worst_float = 0.0, worst_double = 0.0;
    for (const char* spec : specs)
        for (const char* fresnel : {"none", "schlick:f0=0.04", "conductor:eta=0.2,k=3"})
            for (Precision p : {Precision::Float, Precision::Double}) {
                if (p == Precision::Double && !fp64) continue;
                const unsigned lanes = p == Precision::Float ? 16 : 8;
                // n = 4 (rules of 4, 2 and 1 nodes), 20 (20, 10, 5: none a multiple of the
                // lanes) and 64.
                for (std::uint64_t samples : {std::uint64_t(4 * 4 * 4), std::uint64_t(4 * 20 * 20),
                                              std::uint64_t(4 * 64 * 64)})
                    for (double phi : {0.0, 0.7}) {
                        const AlbedoResult s = run_quad(spec, fresnel, p, 1, samples, phi);
                        const AlbedoResult v = run_quad(spec, fresnel, p, lanes, samples, phi);
                        CHECK(s.vector_width == 1);
                        CHECK(v.vector_width == lanes);
                        for (size_t i = 0; i < s.values.size(); ++i) {
                            const double d = std::fabs(s.values[i].value - v.values[i].value);
                            INFO(spec << " " << fresnel << " " << precision_name(p) << " " << samples
                                      << " samples, phi " << phi << ", cell " << i << ": scalar "
                                      << s.values[i].value << " +- " << s.values[i].error << ", vector "
                                      << v.values[i].value << " +- " << v.values[i].error);
                            CHECK(v.values[i].samples == s.values[i].samples);
                            if (p == Precision::Float) {
                                worst_float = std::max(worst_float, d);
                                // (The error estimates may differ more: a rounding-level
                                // difference between the rules can switch quadrature_error
                                // between its geometric and algebraic forms.)
                                CHECK(d <= 1e-6 + s.values[i].error);
                            } else {
                                worst_double = std::max(worst_double, d);
                                CHECK(d <= 1e-12);
                                CHECK(std::fabs(s.values[i].error - v.values[i].error) <= 1e-12);
                            }
                        }
                    }
            }
    WARN("largest scalar - vector difference: float " << worst_float << ", double " << worst_double);
}

TEST_CASE("Quadrature: the device's choice is the vector path for the half-vector rule and the sampler's square", "[albedo][quadrature][device]") {
    const AlbedoResult g = run_quad("ggx:alpha=0.3", "none", Precision::Float, 0, 1024, 0.0);
    CHECK(g.vector_width == (cpu() ? 16u : 1u));
    // The sampler's square of a model whose sampler (here the cosine warp's evaluation) is
    // branch-free takes the vector path too (-D BB_QUAD_SAMPLER_ROWS).
    const AlbedoResult l = run_quad("oren-nayar:sigma=0.5", "none", Precision::Float, 0, 1024, 0.0);
    CHECK(l.vector_width == (cpu() ? 16u : 1u));
    for (unsigned lanes : {2u, 4u, 8u}) {
        const AlbedoResult s = run_quad("ggx:alpha_x=0.05,alpha_y=0.3", "schlick:f0=0.04", Precision::Float, 1, 4 * 20 * 20, 0.7);
        const AlbedoResult v = run_quad("ggx:alpha_x=0.05,alpha_y=0.3", "schlick:f0=0.04", Precision::Float, lanes, 4 * 20 * 20, 0.7);
        CHECK(v.vector_width == lanes);
        for (size_t i = 0; i < s.values.size(); ++i)
            CHECK(std::fabs(s.values[i].value - v.values[i].value) <= 1e-6 + s.values[i].error);
    }
}

TEST_CASE("Quadrature: the vector path counts non-finite parameters and refuses", "[albedo][quadrature][device]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (unsigned lanes : {1u, 0u})
        for (const char* spec : {"ggx:alpha=0.5", "beckmann:alpha_x=0.1,alpha_y=0.3", "blinn-phong:n=20"}) {
            const ModelConfig m = resolve_model(spec);
            AlbedoRequest req;
            req.model = m.id;
            req.fresnel = resolve_fresnel("none");
            req.method = Method::Quadrature;
            req.samples = 1024;
            req.vector_width = lanes;
            for (double phi : {0.0, 0.7}) {
                req.cells = cells_for({0.5}, phi, m.params);
                req.cells[0].params[0] = nan;
                CHECK_THROWS_AS(compute_albedo(testing::engine(), req), NonFiniteError);
                req.cells[0].params[0] = std::numeric_limits<double>::infinity();
                CHECK_THROWS_AS(compute_albedo(testing::engine(), req), NonFiniteError);
            }
            req.cells = cells_for({0.5}, 0.0, m.params);
            req.fresnel = resolve_fresnel("schlick:f0=0.04");
            req.fresnel.params[0] = nan;
            CHECK_THROWS_AS(compute_albedo(testing::engine(), req), NonFiniteError);
        }
}

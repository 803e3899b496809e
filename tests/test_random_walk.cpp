// The multiple-scattering Smith microsurface by random walk (brdf/random_walk.h,
// integrate/random_walk.h): its Lambda and visible normals below the horizon against quadrature of
// the textbook D, the white furnace (E + cut-off = 1 for F = 1), the first scattering order against
// the height-correlated lobe's albedo by independent quadrature (benchmarks/reference), a conductor
// Fresnel term between single scattering and 1, and the command line's refusals.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "brdfbake/brdf/random_walk.h"
#include "integrate/random_walk.h"
#include "model_refs.h"
#include "support.h"

using namespace brdfbake;

namespace {

/// A walk request: `spec` (resolved with its simulated keys), mu at phi = 0, `walks` per cell.
AlbedoRequest walk_request(const std::string& spec, const std::vector<double>& mus, const std::string& fresnel,
                           std::uint64_t walks) {
    const ModelConfig m = resolve_model_simulated(spec);
    REQUIRE(m.simulated);
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = resolve_fresnel(fresnel);
    req.cells = cells_for(mus, 0.0, m.params);
    req.samples = walks;
    req.precision = Precision::Float;
    return req;
}

/// The textbook D and Lambda (reference.h) of a distribution name.
ref::ld ref_d(bool beckmann, ref::Dir m, double a) { return beckmann ? ref::beckmann_d(m, a, a) : ref::ggx_d(m, a, a); }

}  // namespace

TEST_CASE("walk: the signed Lambda is the projected area of the visible normals, both hemispheres", "[random-walk]") {
    // integral of <v, m> D(m) dm over the upper hemisphere = (1 + Lambda(v)) v.z for every v,
    // Lambda(-w) = -1 - Lambda(w) below the horizon [HHdD16]: quadrature of the textbook D.
    for (bool beckmann : {false, true})
        for (double a : {0.2, 0.8})
            for (double vz : {0.7, -0.3, -0.9}) {
                const ref::Dir v{std::sqrt(1 - vz * vz), 0, vz};
                const double area = ref::integrate2(
                    [&](double th, double ph) {
                        const ref::Dir m = ref::dir(th, ph);
                        return double(std::max<ref::ld>(0, ref::dot(v, m)) * ref_d(beckmann, m, a) * std::sin(th));
                    },
                    0, M_PI / 2, 0, M_PI, 1e-6);
                const bb_real lambda = bb_walk_lambda(beckmann ? BB_SMITH_BECKMANN : BB_SMITH_GGX,
                                                      bb_v3(v.x, v.y, v.z), a, a);
                INFO((beckmann ? "beckmann" : "ggx") << " alpha " << a << " v.z " << vz);
                CHECK((1 + lambda) * vz == Approx(2 * area).epsilon(1e-5).margin(1e-12));  // phi in [0, pi], twice
            }
}

TEST_CASE("walk: visible normals of a direction below the horizon have the density <v, m> D(m)", "[random-walk]") {
    // The mean of m.z and of <v, m> over 2^17 samples against their quadrature under <v, m>+ D;
    // views within Beckmann's BB_WALK_BECKMANN_MIN_COS (stretched cosine >= -0.9).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (bool beckmann : {false, true})
        for (double a : {0.3, 1.0})
            for (double vz : {-0.2, -0.5}) {
                const ref::Dir v{std::sqrt(1 - vz * vz), 0, vz};
                auto moment = [&](int k) {
                    return ref::integrate2(
                        [&](double th, double ph) {
                            const ref::Dir m = ref::dir(th, ph);
                            const double w = double(std::max<ref::ld>(0, ref::dot(v, m)) * ref_d(beckmann, m, a));
                            return w * std::sin(th) * (k == 0 ? 1.0 : k == 1 ? double(m.z) : double(ref::dot(v, m)));
                        },
                        0, M_PI / 2, 0, M_PI, 1e-6);  // the mirror half in phi: the ratios need no factor 2
                };
                const double norm = moment(0), ez = moment(1) / norm, ev = moment(2) / norm;
                const int n = 1 << 17;
                double sz = 0, sz2 = 0, sv = 0, sv2 = 0, below = 0;
                for (int i = 0; i < n; ++i) {
                    const bb_vec3 m = bb_walk_sample_vndf(beckmann ? BB_SMITH_BECKMANN : BB_SMITH_GGX,
                                                          bb_v3(v.x, v.y, v.z), a, a, u(rng), u(rng));
                    const double c = m.x * v.x + m.y * v.y + m.z * v.z;
                    below += (m.z < 0 || c < -1e-9) ? 1 : 0;
                    sz += m.z, sz2 += m.z * m.z, sv += c, sv2 += c * c;
                }
                const double mz = sz / n, mv = sv / n;
                const double ez_err = 5 * std::sqrt((sz2 / n - mz * mz) / n) + 1e-5;
                const double ev_err = 5 * std::sqrt((sv2 / n - mv * mv) / n) + 1e-5;
                INFO((beckmann ? "beckmann" : "ggx") << " alpha " << a << " v.z " << vz);
                CHECK(below == 0);
                CHECK(std::fabs(mz - ez) < ez_err);
                CHECK(std::fabs(mv - ev) < ev_err);
            }
}

TEST_CASE("walk: white furnace, E + cut-off = 1 for F = 1 (ggx and beckmann)", "[random-walk]") {
    const std::vector<double> mus = {0.1, 0.5, 1.0};
    for (const char* d : {"ggx", "beckmann"})
        for (double a : {0.1, 0.5, 1.0, 1.5}) {
            const std::string spec = std::string(d) + ":alpha=" + modelref::num(a) + ",scattering=multiple";
            const WalkResult r = walk_albedo(testing::engine(), walk_request(spec, mus, "none", 1 << 14));
            for (size_t c = 0; c < mus.size(); ++c) {
                const WalkAlbedo& w = r.values[c];
                INFO(spec << " mu " << mus[c] << ": E " << w.energy.value << " +- " << w.energy.error << ", cutoff "
                          << w.cutoff.value << ", single " << w.single.value);
                CHECK(std::fabs(w.energy.value + w.cutoff.value - 1.0) <= w.energy.error + w.cutoff.error + 1e-6);
                CHECK(w.cutoff.value < 1e-3);  // 100 bounces keep nearly every walk
                CHECK(w.single.value <= w.energy.value);
            }
        }
}

TEST_CASE("walk: the first order is the height-correlated lobe's albedo (quadrature)", "[random-walk]") {
    const std::vector<double> mus = {0.2, 0.6, 1.0};
    for (bool beckmann : {false, true})
        for (double a : {0.1, 0.6, 1.5}) {
            const modelref::Case ref = beckmann ? modelref::beckmann(a, true) : modelref::ggx(a, true);
            const std::string spec = ref.spec + ",scattering=multiple";
            const WalkResult r = walk_albedo(testing::engine(), walk_request(spec, mus, "none", 1 << 16));
            for (size_t c = 0; c < mus.size(); ++c) {
                const double e1 = ref.albedo(mus[c]);
                INFO(spec << " mu " << mus[c] << ": first order " << r.values[c].single.value << " +- "
                          << r.values[c].single.error << ", quadrature " << e1);
                CHECK(std::fabs(r.values[c].single.value - e1) <= r.values[c].single.error);
                if (a >= 0.6) CHECK(r.values[c].energy.value - r.values[c].energy.error > e1);  // energy comes back
            }
        }
}

TEST_CASE("walk: anisotropic alpha, the first order against quadrature at two azimuths", "[random-walk]") {
    const double ax = 0.2, ay = 0.8, mu = 0.5;
    AlbedoRequest req = walk_request("ggx:alpha_x=0.2,alpha_y=0.8,scattering=multiple", {mu, mu}, "none", 1 << 16);
    req.cells[1].phi = M_PI / 2;
    const WalkResult r = walk_albedo(testing::engine(), req);
    for (size_t c = 0; c < 2; ++c) {
        const double e1 = ref::albedo_halfvector(
            [=](ref::Dir o, ref::Dir i) { return ref::ggx_f(o, i, ax, ay, true); }, mu, req.cells[c].phi, 1e-7);
        INFO("phi " << req.cells[c].phi << ": first order " << r.values[c].single.value << " quadrature " << e1);
        CHECK(std::fabs(r.values[c].single.value - e1) <= r.values[c].single.error);
        CHECK(std::fabs(r.values[c].energy.value + r.values[c].cutoff.value - 1) <= r.values[c].energy.error + 1e-6);
    }
}

TEST_CASE("walk: bounces=1 cuts off exactly what single scattering loses", "[random-walk]") {
    // E = E_single and cutoff = 1 - E_single, E_single by quadrature of the correlated lobe.
    const double a = 1.0;
    const modelref::Case ref = modelref::beckmann(a, true);
    const std::vector<double> mus = {0.3, 1.0};
    const WalkResult r =
        walk_albedo(testing::engine(), walk_request(ref.spec + ",scattering=multiple,bounces=1", mus, "none", 1 << 16));
    for (size_t c = 0; c < mus.size(); ++c) {
        const WalkAlbedo& w = r.values[c];
        INFO("mu " << mus[c] << ": E " << w.energy.value << " cutoff " << w.cutoff.value);
        CHECK(w.energy.value == w.single.value);
        CHECK(std::fabs(w.cutoff.value - (1 - ref.albedo(mus[c]))) <= w.cutoff.error);
    }
}

TEST_CASE("walk: with a conductor Fresnel term single scattering <= E < 1", "[random-walk]") {
    // Schlick f0 = 0.5 at every bounce; the first order against the quadrature of the textbook
    // correlated GGX times Schlick's F(wo.h) [S94].
    const double a = 0.8, f0 = 0.5;
    const std::vector<double> mus = {0.3, 0.9};
    const WalkResult r = walk_albedo(
        testing::engine(), walk_request("ggx:alpha=0.8,scattering=multiple", mus, "schlick:f0=0.5", 1 << 16));
    for (size_t c = 0; c < mus.size(); ++c) {
        const double e1 = ref::albedo_halfvector(
            [=](ref::Dir o, ref::Dir i) {
                const ref::Dir h = ref::normalize({o.x + i.x, o.y + i.y, o.z + i.z});
                return ref::ggx_f(o, i, a, a, true) * (f0 + (1 - f0) * std::pow(1 - ref::dot(o, h), 5));
            },
            mus[c], 0.0, 1e-7);
        const WalkAlbedo& w = r.values[c];
        INFO("mu " << mus[c] << ": E " << w.energy.value << " single " << w.single.value << " quadrature " << e1);
        CHECK(std::fabs(w.single.value - e1) <= w.single.error);
        CHECK(w.energy.value - w.energy.error > w.single.value);
        CHECK(w.energy.value + w.energy.error < 1.0);
    }
}

TEST_CASE("walk: the command prints E, its single-scattering part and the cut-off, other uses refuse", "[random-walk]") {
    const auto r = testing::run_cli("albedo --model ggx:alpha=0.5,scattering=multiple --mu 0.5 --samples 16384");
    REQUIRE(r.status == 0);
    CHECK(r.out.find("scattering=multiple,bounces=100") != std::string::npos);
    CHECK(r.out.find("single") != std::string::npos);
    CHECK(r.out.find("cutoff") != std::string::npos);
    for (const std::string& args :
         {std::string("albedo --model ggx:alpha=0.5,scattering=multiple --method quadrature"),
          std::string("albedo --model ggx:alpha=0.5,bounces=10"),
          std::string("albedo --model beckmann:alpha=0.5,scattering=multiple,shadowing=separable"),
          std::string("lut dfg --model ggx:scattering=multiple --size 4x4 -o /tmp/walk-refused.exr"),
          std::string("lut eavg --model ggx:scattering=multiple,eta=1.5 --size 4 -o /tmp/walk-refused.exr"),
          std::string("reciprocity --model beckmann:alpha=0.5,scattering=multiple -o /tmp/walk-refused.exr"),
          std::string("furnace --model ggx:alpha=0.5,scattering=multiple -o /tmp/walk-refused.png")}) {
        const auto e = testing::run_cli(args);
        INFO(args << "\n" << e.err);
        CHECK(e.status == 2);
        CHECK(testing::count_lines(e.err) == 1);
        CHECK(e.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(e.err.find("scattering=multiple") != std::string::npos);
        CHECK(e.out.empty());
    }
}

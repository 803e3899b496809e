// The integration methods (importance, qmc, mc, quadrature) and the tolerance mode against
// independent high-precision references (tests/model_refs.h: Boost.Math Gauss-Kronrod).
#include <catch2/catch.hpp>

#include <iomanip>

#include <nlohmann/json.hpp>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "model_refs.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

constexpr double kRefSlack = 1e-8;

const std::vector<Method> kMethods = {Method::Importance, Method::QuasiMonteCarlo, Method::MonteCarlo,
                                      Method::Quadrature};


/// A model case with its references at the test's directions, computed once.
struct RefCase {
    modelref::Case c;
    std::vector<double> mus;
    std::vector<double> ref;
};

std::vector<RefCase>& grid() {
    static std::vector<RefCase> cases = [] {
        std::vector<RefCase> v = {
            {modelref::ggx(0.5, true, 1e-9), {0.01, 0.3, 1.0}, {}},
            {modelref::ggx(0.05, false, 1e-9), {0.01, 0.3, 1.0}, {}},
            {modelref::beckmann(0.3, true, 1e-9), {0.01, 0.3, 1.0}, {}},
            {modelref::oren_nayar(1.0, 0.8), {0.01, 0.3, 1.0}, {}},
            {modelref::blinn_phong(50, 1e-9), {0.05, 0.5}, {}},
            {modelref::phong(20, 1e-9), {0.05, 0.5}, {}},
        };
        for (auto& rc : v)
            for (double mu : rc.mus) rc.ref.push_back(rc.c.albedo(mu));
        return v;
    }();
    return cases;
}

}  // namespace

TEST_CASE("every method agrees with independent references within its error estimate", "[methods][device]") {
    int runs = 0, beyond3 = 0;
    for (const RefCase& rc : grid())
        for (Method method : kMethods)
            for (Precision p : {Precision::Float, Precision::Double})
                for (std::uint64_t samples : {std::uint64_t(1) << 12, std::uint64_t(1) << 16}) {
                    const AlbedoResult r = compute_albedo(testing::engine(), testing::albedo_request(rc.c.spec, rc.mus, method, p, samples));
                    for (size_t i = 0; i < rc.mus.size(); ++i) {
                        // The references are good to about their tolerance (1e-9): below
                        // kRefSlack the comparison judges the reference, not the method.
                        const double actual = std::max(0.0, std::fabs(r.values[i].value - rc.ref[i]) - kRefSlack);
                        INFO(rc.c.spec << " " << method_name(method) << " " << precision_name(p) << " " << samples
                                       << " samples, mu = " << rc.mus[i] << ": " << r.values[i].value << " +- "
                                       << r.values[i].error << ", reference " << rc.ref[i]);
                        CHECK(std::isfinite(r.values[i].error));
                        CHECK(r.values[i].error > 0.0);
                        CHECK(r.values[i].method == method);
                        ++runs;
                        if (actual > 3.0 * r.values[i].error) ++beyond3;
                        // Issue 7's honesty criterion, per run: within 3x the estimate (the
                        // estimate is itself 3 standard errors or a rule difference). A
                        // uniform sampler that rarely hits a narrow lobe underestimates its
                        // variance: mc and qmc at 4096 samples come closest (see docs/accuracy.md).
                        CHECK(actual <= 3.0 * r.values[i].error);
                    }
                }
    INFO(beyond3 << " of " << runs << " runs beyond 3x their estimate");
    CHECK(runs > 200);
    CHECK(double(beyond3) / runs < 0.01);
}

TEST_CASE("quadrature converges fast for smooth lobes, at grazing too", "[methods][device]") {
    // GGX alpha = 0.5, double precision: the 32-node rule (5120 points) against the reference
    // to 1e-9; the half-vector rows end exactly at the horizon, so grazing converges as fast.
    const std::vector<double> mus = {1e-3, 0.1, 0.5, 1.0};
    const AlbedoResult r =
        compute_albedo(testing::engine(), testing::albedo_request("ggx:alpha=0.5", mus, Method::Quadrature, Precision::Double, 4 * 32 * 32));
    for (size_t i = 0; i < mus.size(); ++i) {
        const double expect = ref::albedo_halfvector(
            [](ref::Dir o, ref::Dir i) { return ref::ggx_f(o, i, 0.5, 0.5, true); }, mus[i], 0.0, 1e-9);
        INFO("mu = " << mus[i] << ": " << r.values[i].value << " +- " << r.values[i].error << ", reference " << expect);
        CHECK(std::fabs(r.values[i].value - expect) < 1e-6);
        CHECK(std::fabs(r.values[i].value - expect) <= r.values[i].error);
        CHECK(r.values[i].samples <= 5120u);
    }
}

TEST_CASE("tolerance mode: results meet their tolerance", "[methods][tolerance][device]") {
    struct Run {
        Precision precision;
        double tolerance;
        bool auto_method;
        Method method;
    };
    for (const Run& run : {Run{Precision::Float, 1e-5, true, Method::Importance},
                           Run{Precision::Double, 1e-7, true, Method::Importance},
                           Run{Precision::Float, 2e-4, false, Method::Importance},
                           Run{Precision::Float, 1e-4, false, Method::QuasiMonteCarlo}})
        for (const RefCase& rc : grid()) {
            if (!run.auto_method && rc.mus.front() < 0.05) continue;  // sampling to 1e-4 at grazing: slow
            AlbedoRequest req = testing::albedo_request(rc.c.spec, rc.mus, run.method, run.precision, 0);
            ToleranceRequest tol;
            tol.tolerance = run.tolerance;
            tol.auto_method = run.auto_method;
            tol.max_samples = std::uint64_t(1) << 26;
            const AlbedoResult r = compute_albedo_to_tolerance(testing::engine(), req, tol);
            CHECK(r.tolerance == run.tolerance);
            for (size_t i = 0; i < rc.mus.size(); ++i) {
                INFO(rc.c.spec << " " << precision_name(run.precision) << " tolerance " << run.tolerance << " ("
                               << (run.auto_method ? "auto" : method_name(run.method)) << "), mu = " << rc.mus[i]
                               << ": " << r.values[i].value << " +- " << r.values[i].error << " by "
                               << method_name(r.values[i].method) << " in " << r.values[i].samples
                               << " samples; reference " << rc.ref[i]);
                CHECK(r.values[i].error <= run.tolerance);
                CHECK(std::fabs(r.values[i].value - rc.ref[i]) <= run.tolerance);
                if (!run.auto_method) CHECK(r.values[i].method == run.method);
            }
        }
}

TEST_CASE("albedo --tolerance 1e-5 meets it at a narrow lobe and at grazing", "[methods][tolerance][cli]") {
    struct Case {
        double alpha, mu;
    };
    for (const Case c : {Case{0.001, 0.1}, Case{0.5, 1e-3}}) {
        const auto r = testing::run_cli("albedo --model ggx:alpha=" + std::to_string(c.alpha) + " --mu " +
                                        std::to_string(c.mu) + " --tolerance 1e-5 --format json");
        REQUIRE(r.status == 0);
        const auto j = nlohmann::json::parse(r.out);
        CHECK(j["tolerance"].get<double>() == 1e-5);
        const double got = j["results"][0]["albedo"].get<double>();
        const double err = j["results"][0]["error"].get<double>();
        const double expect = ref::albedo_halfvector(
            [&](ref::Dir o, ref::Dir i) { return ref::ggx_f(o, i, c.alpha, c.alpha, true); }, c.mu, 0.0, 1e-11);
        INFO("alpha = " << c.alpha << ", mu = " << c.mu << ": " << got << " +- " << err << ", reference " << expect
                        << "; " << j["estimator"].get<std::string>());
        CHECK(err <= 1e-5);
        CHECK(std::fabs(got - expect) <= 1e-5);
        CHECK(j["results"][0]["samples"].get<std::uint64_t>() > 0);
    }
}

TEST_CASE("tolerance and method options refuse bad input", "[methods][tolerance][cli]") {
    // Below what float can certify: one message, exit 2.
    auto r = testing::run_cli("albedo --model ggx:alpha=0.5 --tolerance 1e-9");
    CHECK(r.status == 2);
    CHECK(r.err.find("--precision double") != std::string::npos);
    CHECK(testing::count_lines(r.err) == 1);
    // A tolerance and a fixed sample count exclude each other.
    r = testing::run_cli("albedo --model ggx:alpha=0.5 --tolerance 1e-4 --samples 1024");
    CHECK(r.status == 2);
    r = testing::run_cli("albedo --model ggx:alpha=0.5 --tolerance -1");
    CHECK(r.status == 2);
    r = testing::run_cli("albedo --model ggx:alpha=0.5 --method simpson");
    CHECK(r.status == 2);
    // A tolerance that the budget cannot reach: exit 1, the worst cell named, no table written.
    r = testing::run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --method mc --tolerance 1e-5 --max-samples 65536");
    CHECK(r.status == 1);
    CHECK(r.err.find("not met") != std::string::npos);
    const std::string table = "/tmp/brdfbake-test-methods-unmet.exr";
    std::remove(table.c_str());
    r = testing::run_cli("lut albedo --model ggx --size 4x4 --method mc --tolerance 1e-5 --max-samples 65536 -o " + table);
    CHECK(r.status == 1);
    CHECK(!std::ifstream(table).good());
}

TEST_CASE("mc streams are reproducible by seed and independent across seeds", "[methods][device]") {
    AlbedoRequest req = testing::albedo_request("ggx:alpha=0.5", {0.5}, Method::MonteCarlo, Precision::Double, 1 << 14);
    const double a = compute_albedo(testing::engine(), req).values[0].value;
    const double b = compute_albedo(testing::engine(), req).values[0].value;
    req.seed += 1;
    const double c = compute_albedo(testing::engine(), req).values[0].value;
    CHECK(a == b);
    CHECK(a != c);
}

TEST_CASE("quadrature follows elongated anisotropic lobes off their axes", "[methods][device]") {
    // The azimuth map of the half-vector rule follows the lobe's azimuthal marginal: at ratios
    // of 8 and 25 between the roughnesses, off the axes and towards grazing, the 64-node rule is
    // at the reference. The reference integrates over the whole azimuth range, cut where it
    // crosses the distribution's axes (|phi_h - phi_o| = |j pi/2 - phi_o|).
    struct Case {
        double ax, ay, phi_deg;
    };
    const std::vector<double> mus = {0.05, 0.5};
    for (const Case c : {Case{0.1, 0.8, 30.0}, Case{0.02, 0.5, 60.0}}) {
        const std::string spec = "ggx:alpha_x=" + modelref::num(c.ax) + ",alpha_y=" + modelref::num(c.ay);
        AlbedoRequest req = testing::albedo_request(spec, mus, Method::Quadrature, Precision::Double, 4 * 64 * 64);
        const double phi = c.phi_deg * M_PI / 180.0;
        for (auto& cell : req.cells) cell.phi = phi;
        const AlbedoResult r = compute_albedo(testing::engine(), req);
        for (size_t i = 0; i < mus.size(); ++i) {
            const double expect = ref::albedo_halfvector(
                [&](ref::Dir o, ref::Dir w) { return ref::ggx_f(o, w, c.ax, c.ay, true); }, mus[i], phi, 1e-8,
                [&](ref::ld) {
                    std::vector<ref::ld> b;
                    for (int j = -1; j <= 4; ++j) b.push_back(std::fabs(j * M_PI / 2 - phi));
                    return b;
                });
            INFO(std::setprecision(12) << spec << " phi " << c.phi_deg << " mu " << mus[i] << ": " << r.values[i].value << " +- "
                      << r.values[i].error << ", reference " << expect);
            CHECK(std::fabs(r.values[i].value - expect) <= 8e-9);  // the README's figure
            CHECK(std::fabs(r.values[i].value - expect) <= r.values[i].error + 1e-8);  // reference to ~1e-8
            CHECK(r.values[i].samples == 8u * (64u * 64u + 32u * 32u + 16u * 16u));  // 8 azimuth pieces off the axes
        }
    }
}

TEST_CASE("quadrature counts the azimuth pieces it runs: an isotropic lobe cut where rows stop crossing a kink",
          "[methods][quadrature][device]") {
    // gen-schlick-ior at eta 4.56 (Cycles' z = 0.8): its clamped weight is 0 above wo.h = 0.09, so
    // at mu_o = 1e-4 < 0.09 rows stop crossing that kink inside each quarter of the azimuth, which
    // an isotropic lobe's two mirrored quarters are cut at (4 pieces); at mu_o = 0.9 every row's
    // largest wo.h is above it, no cut (2 pieces). n = 32: rules of 32, 16 and 8 nodes.
    AlbedoRequest req = testing::albedo_request("ggx:alpha=0.5", {1e-4, 0.9}, Method::Quadrature, Precision::Double,
                                                4 * 32 * 32);
    req.fresnel = resolve_fresnel("gen-schlick-ior:f0=0,f90=1,eta=4.55556");
    const AlbedoResult r = compute_albedo(testing::engine(), req);
    const std::uint64_t per_piece = 32u * 32u + 16u * 16u + 8u * 8u;
    CHECK(r.values[0].samples == 4u * per_piece);
    CHECK(r.values[1].samples == 2u * per_piece);
    CHECK(r.samples_per_cell == 4u * per_piece);
}

TEST_CASE("float carries an index as close to 1 as 1.0001 through eta - 1", "[methods][fresnel][device]") {
    // 1.0001f is 1 + 1.00017e-4: from eta alone a float kernel would integrate F of the wrong
    // index, 3.3e-4 relative off (F ~ (eta - 1)^2), beyond its own error estimate.
    AlbedoRequest req = testing::albedo_request("ggx:alpha=0.001,shadowing=separable", {1e-3, 0.1}, Method::Importance,
                                    Precision::Float, 1 << 18);
    req.fresnel = resolve_fresnel("dielectric:eta=1.0001");
    const AlbedoResult f = compute_albedo(testing::engine(), req);
    req.precision = Precision::Double;
    const AlbedoResult d = compute_albedo(testing::engine(), req);
    for (size_t i = 0; i < f.values.size(); ++i) {
        INFO("mu = " << req.cells[i].mu << ": float " << f.values[i].value << " +- " << f.values[i].error << ", double "
                     << d.values[i].value << " +- " << d.values[i].error);
        CHECK(std::fabs(f.values[i].value - d.values[i].value) <= 0.25 * f.values[i].error);
    }
}

TEST_CASE("estimates stay honest where the replicas cannot see the error", "[methods][device]") {
    // The three ways the trade-off study (docs/accuracy.md) caught estimates claiming too much,
    // each against an independent reference: the true error must be within 3x the estimate.
    struct Case {
        modelref::Case ref;
        double mu;
        Method method;
        std::uint64_t samples;
    };
    const std::vector<Case> cases = {
        // rare grazing reflections of a narrow GGX lobe, missed by all 4096 samples
        {modelref::ggx(0.01, true, 1e-8), 1.0, Method::Importance, 4096},
        // the V-groove weight is 2 on half the square, 0 on the other: every Hammersley replica
        // splits it exactly in half
        {modelref::torrance_sparrow(ref::Dist::Ggx, 1.0, 1e-7), 1e-4, Method::Importance, 16384},
        // a lobe 1e-3 wide that 256 uniform samples do not hit
        {modelref::beckmann(0.001, true, 1e-6), 0.3, Method::QuasiMonteCarlo, 256},
        {modelref::beckmann(0.001, true, 1e-6), 0.3, Method::MonteCarlo, 256},
    };
    for (const Case& c : cases) {
        const AlbedoResult r =
            compute_albedo(testing::engine(), testing::albedo_request(c.ref.spec, {c.mu}, c.method, Precision::Double, c.samples));
        const double expect = c.ref.albedo(c.mu);
        INFO(std::setprecision(10) << c.ref.spec << " mu " << c.mu << " " << method_name(c.method) << " " << c.samples
                                   << ": " << r.values[0].value << " +- " << r.values[0].error << ", reference " << expect);
        CHECK(std::fabs(r.values[0].value - expect) <= 3.0 * r.values[0].error);
    }
}

TEST_CASE("a stochastic model refuses quadrature and keeps the sampling methods", "[methods][registry]") {
    // A registry row with BB_TRAIT_STOCHASTIC (a simulated BRDF: its value a random-walk
    // estimate) must never meet a quadrature rule, which would read its noise as the integrand.
    ModelTraits simulated = model_traits(BB_MODEL_LAMBERT);
    simulated.stochastic = true;
    try {
        check_method_for_model(simulated, Method::Quadrature);
        FAIL("quadrature of a stochastic model was accepted");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("stochastic") != std::string::npos);
        CHECK(std::string(e.what()).find("--method importance") != std::string::npos);
    }
    for (Method m : {Method::Importance, Method::QuasiMonteCarlo, Method::MonteCarlo})
        CHECK_NOTHROW(check_method_for_model(simulated, m));
    simulated.stochastic = false;
    CHECK_NOTHROW(check_method_for_model(simulated, Method::Quadrature));
}

TEST_CASE("the host's model traits are the registry rows' flags, as the kernels read them", "[registry]") {
    // Both sides are generated from BB_MODEL_REGISTRY: ModelTraits (host/models/spec.cpp) and
    // bb_model_has_trait (model_registry.h, compiled into the kernels); every model registered
    // today is a closed form but the sheen layer (sheen-volume), stochastic as a layer's walk.
    for (const ModelTraits& t : model_registry()) {
        INFO(t.name);
        CHECK(t.delta == (bb_model_is_delta(t.id) != 0));
        CHECK(t.samples_disk == (bb_model_samples_disk(t.id) != 0));
        CHECK(t.samples_vector == (bb_model_samples_vector(t.id) != 0));
        CHECK(t.evals_vector == (bb_model_evals_vector(t.id) != 0));
        CHECK(t.cosine_sampler == (bb_quad_sampler_is_cosine(t.id) != 0));
        CHECK(t.stochastic == (bb_model_has_trait(t.id, BB_TRAIT_STOCHASTIC) != 0));
        CHECK(t.layer_walk == (bb_model_has_trait(t.id, BB_TRAIT_LAYER_WALK) != 0));
        CHECK(t.stochastic == t.layer_walk);  // the one stochastic row is the sheen layer's walk
    }
}

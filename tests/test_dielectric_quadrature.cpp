// The rough dielectric by quadrature (brdf/dielectric_quadrature.h): against the independent
// Boost.Math quadrature of benchmarks/reference (a different parameterisation, adaptive), in the
// three shadowing forms; the honesty of its error estimate over a grid from roughness 1e-3 to 1,
// mu 1e-4 to 1, eta 1.0001 to 3 and 1/1.5; the tolerance runs (auto: quadrature, then importance);
// and the table's agreement with the importance-sampled table within the two error estimates.
#include <catch2/catch.hpp>

#include <cmath>
#include <iomanip>

#include "brdfbake/albedo.h"
#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "reference/reference.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

struct Form {
    Shadowing shadowing;
    TransmissionShadowing transmission_shadowing;
    ref::DielectricShadowing reference;
    const char* name;
};

const Form kForms[] = {
    {Shadowing::Correlated, TransmissionShadowing::Beta, ref::DielectricShadowing::Beta, "beta"},
    {Shadowing::Separable, TransmissionShadowing::Beta, ref::DielectricShadowing::Separable, "separable"},
    {Shadowing::Correlated, TransmissionShadowing::Cycles, ref::DielectricShadowing::Cycles, "cycles"}};

DielectricRequest quadrature_request(const std::vector<DielectricCell>& cells, const Form& form, unsigned n,
                                     Precision precision) {
    DielectricRequest r;
    r.cells = cells;
    r.method = Method::Quadrature;
    r.samples = 4ull * n * n;
    r.precision = precision;
    r.shadowing = form.shadowing;
    r.transmission_shadowing = form.transmission_shadowing;
    return r;
}

}  // namespace

TEST_CASE("dielectric quadrature: R and T against independent quadrature in three shadowing forms", "[dielectric][device]") {
    const std::vector<DielectricCell> cells = {{0.5, 0.3, 1.5},   {0.9, 0.6, 1 / 1.5}, {0.3, 0.1, 1.33},
                                               {0.05, 0.5, 1 / 1.5}, {1.0, 0.02, 3.0}, {0.2, 1.0, 1 / 1.33}};
    for (const Form& form : kForms) {
        const DielectricResult res =
            compute_dielectric(testing::engine(), quadrature_request(cells, form, 64, Precision::Double));
        for (size_t k = 0; k < cells.size(); ++k) {
            double r, t;
            ref::rough_dielectric_rt(cells[k].mu, cells[k].alpha, cells[k].eta, form.reference, r, t, 1e-9);
            INFO(form.name << " mu " << cells[k].mu << " alpha " << cells[k].alpha << " eta " << cells[k].eta << ": R "
                           << std::setprecision(12) << res.reflected[k].value << " +- " << res.reflected[k].error
                           << " vs " << r << ", T " << res.transmitted[k].value << " +- " << res.transmitted[k].error
                           << " vs " << t);
            CHECK(res.reflected[k].method == Method::Quadrature);
            CHECK(std::fabs(res.reflected[k].value - r) <= res.reflected[k].error + 1e-8);
            CHECK(std::fabs(res.transmitted[k].value - t) <= res.transmitted[k].error + 1e-8);
            CHECK(std::fabs(res.reflected[k].value - r) <= 1e-6);
            CHECK(std::fabs(res.transmitted[k].value - t) <= 1e-6);
        }
    }
}

TEST_CASE("dielectric quadrature: the error estimate is honest from roughness 1e-3 to 1", "[dielectric][device]") {
    // Issue 20's criterion, as for the albedo methods: over a grid of cells the true error
    // (against the independent reference, itself good to about 1e-9 relative) exceeds 3x the
    // estimate in under 1% of the (cell, channel, rule order) runs.
    std::vector<DielectricCell> cells;
    for (double alpha : {1e-3, 0.03, 0.3, 1.0})
        for (double mu : {1e-4, 0.02, 0.3, 0.7, 1.0})
            for (double eta : {1.0001, 1.5, 3.0, 1 / 1.5}) cells.push_back({mu, alpha, eta});
    std::vector<double> ref_r(cells.size()), ref_t(cells.size());
    for (size_t k = 0; k < cells.size(); ++k)
        ref::rough_dielectric_rt(cells[k].mu, cells[k].alpha, cells[k].eta, ref::DielectricShadowing::Beta, ref_r[k],
                                 ref_t[k], 1e-9);
    int runs = 0, beyond = 0;
    for (unsigned n : {16u, 32u, 64u}) {
        const DielectricResult res =
            compute_dielectric(testing::engine(), quadrature_request(cells, kForms[0], n, Precision::Double));
        for (size_t k = 0; k < cells.size(); ++k)
            for (int channel = 0; channel < 2; ++channel) {
                const AlbedoValue& v = channel == 0 ? res.reflected[k] : res.transmitted[k];
                const double expect = channel == 0 ? ref_r[k] : ref_t[k];
                const double actual = std::fabs(v.value - expect);
                ++runs;
                CHECK(std::isfinite(v.value));
                CHECK(v.error > 0.0);
                if (actual > 3.0 * v.error + 1e-9 * std::max(1.0, std::fabs(expect))) {
                    ++beyond;
                    WARN("n " << n << (channel == 0 ? " R" : " T") << " mu " << cells[k].mu << " alpha "
                              << cells[k].alpha << " eta " << cells[k].eta << ": " << std::setprecision(12) << v.value
                              << " +- " << v.error << ", reference " << expect);
                }
            }
    }
    INFO(beyond << " of " << runs << " runs beyond 3x their estimate");
    CHECK(runs == 3 * 2 * int(cells.size()));
    CHECK(double(beyond) / runs < 0.01);
}

TEST_CASE("dielectric to a tolerance: auto meets it in float and double against the reference", "[dielectric][tolerance][device]") {
    const std::vector<DielectricCell> cells = {{1e-4, 1e-3, 1.5}, {0.02, 0.03, 1 / 1.5}, {0.3, 0.3, 3.0},
                                               {0.7, 1.0, 1.0001}, {1.0, 0.3, 1 / 1.5},   {0.1, 1e-3, 1 / 1.5}};
    for (Precision p : {Precision::Float, Precision::Double}) {
        if (p == Precision::Double && !testing::engine().device().fp64) continue;
        DielectricRequest req;
        req.cells = cells;
        req.precision = p;
        ToleranceRequest tol;
        tol.tolerance = 1e-4;
        tol.auto_method = true;
        tol.max_samples = std::uint64_t(1) << 24;
        const DielectricResult res = compute_dielectric_to_tolerance(testing::engine(), req, tol);
        for (size_t k = 0; k < cells.size(); ++k) {
            double r, t;
            ref::rough_dielectric_rt(cells[k].mu, cells[k].alpha, cells[k].eta, ref::DielectricShadowing::Beta, r, t, 1e-9);
            INFO(precision_name(p) << " mu " << cells[k].mu << " alpha " << cells[k].alpha << " eta " << cells[k].eta
                                   << ": R " << res.reflected[k].value << " +- " << res.reflected[k].error << " ("
                                   << method_name(res.reflected[k].method) << ") vs " << r << ", T "
                                   << res.transmitted[k].value << " +- " << res.transmitted[k].error << " vs " << t);
            CHECK(res.reflected[k].error <= 1e-4);
            CHECK(res.transmitted[k].error <= 1e-4);
            CHECK(std::fabs(res.reflected[k].value - r) <= 1e-4);
            CHECK(std::fabs(res.transmitted[k].value - t) <= 1e-4);
        }
    }
}

TEST_CASE("dielectric table: auto (quadrature) agrees with importance sampling within the two estimates",
          "[dielectric][tolerance][device]") {
    LutRequest lr = testing::lut_request("dielectric", "ggx", 5, 4, 3);
    lr.eta_lo = 1.0;
    lr.eta_hi = 3.0;
    lr.tolerance.tolerance = 1e-3;
    lr.tolerance.max_samples = std::uint64_t(1) << 22;
    lr.tolerance.auto_method = true;
    const Table q = compute_lut(testing::engine(), lr);
    lr.tolerance.auto_method = false;
    lr.method = Method::Importance;
    const Table s = compute_lut(testing::engine(), lr);
    REQUIRE(q.error.size() == s.error.size());
    CHECK(q.attributes.at("method") != s.attributes.at("method"));
    for (size_t k = 0; k < q.error.size(); ++k) {
        CHECK(q.error[k] <= 1e-3);
        CHECK(s.error[k] <= 1e-3);
        for (int c = 0; c < 4; ++c) {
            INFO("texel " << k << " channel " << q.channels[c] << ": " << q.values[c][k] << " +- " << q.error[k]
                          << " vs " << s.values[c][k] << " +- " << s.error[k]);
            CHECK(std::fabs(q.values[c][k] - s.values[c][k]) <= q.error[k] + s.error[k]);
        }
    }
}

TEST_CASE("dielectric: methods other than importance and quadrature are refused", "[dielectric][quick]") {
    LutRequest lr;
    lr.kind = "dielectric";
    lr.model = "ggx";
    lr.width = lr.height = lr.depth = 2;
    lr.method = Method::QuasiMonteCarlo;
    CHECK_THROWS_AS(validate_lut(lr), Error);
    lr.method = Method::Quadrature;
    CHECK_NOTHROW(validate_lut(lr));
}

TEST_CASE("dielectric quadrature: the row-per-lane kernel gives the scalar kernel's sums", "[dielectric][parity][device]") {
    // The same nodes, segments and functions, W rows at a time: the sums differ by rounding only.
    std::vector<DielectricCell> cells;
    for (double mu : {1e-3, 0.3, 1.0})
        for (double alpha : {1e-3, 0.3, 1.0})
            for (double eta : {1.0001, 1.5, 1.0 / 1.5}) cells.push_back({mu, alpha, eta});
    // n = 16: the 31-point Kronrod rule and its embedded Gauss rule; 64: three Gauss-Legendre rules.
    for (unsigned n : {16u, 64u})
        for (Precision p : {Precision::Float, Precision::Double}) {
            if (p == Precision::Double && !testing::engine().device().fp64) continue;
            DielectricRequest r = quadrature_request(cells, kForms[0], n, p);
            r.vector_width = 1;
            const DielectricResult s = compute_dielectric(testing::engine(), r);
            r.vector_width = 0;
            const DielectricResult v = compute_dielectric(testing::engine(), r);
            CHECK(s.vector_width == 1);
            const double tol = p == Precision::Float ? 2e-5 : 1e-12;
            for (size_t i = 0; i < cells.size(); ++i) {
                INFO(precision_name(p) << " n " << n << " mu " << cells[i].mu << " alpha " << cells[i].alpha << " eta "
                                       << cells[i].eta << ": R " << s.reflected[i].value << " +- " << s.reflected[i].error
                                       << " vs " << v.reflected[i].value << " +- " << v.reflected[i].error << ", T "
                                       << s.transmitted[i].value << " +- " << s.transmitted[i].error << " vs "
                                       << v.transmitted[i].value << " +- " << v.transmitted[i].error);
                CHECK(std::fabs(s.reflected[i].value - v.reflected[i].value) <= tol);
                CHECK(std::fabs(s.transmitted[i].value - v.transmitted[i].value) <= tol);
                // The Kronrod rule's estimate is a difference of such sums: equal to twice the
                // rounding. (The Gauss-Legendre triple's may switch between its two forms on a
                // rounding difference where the convergence test is at its threshold.)
                if (n == 16) {
                    CHECK(std::fabs(s.reflected[i].error - v.reflected[i].error) <= 2 * tol + 0.01 * s.reflected[i].error);
                    CHECK(std::fabs(s.transmitted[i].error - v.transmitted[i].error) <= 2 * tol + 0.01 * s.transmitted[i].error);
                }
            }
        }
}

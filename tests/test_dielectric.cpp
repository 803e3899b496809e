// Rough dielectric interface: smooth limit against the Fresnel equations, energy bounds,
// reciprocity between the two sides, and independent quadrature of R and T.
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/beta.hpp>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/lut.h"
#include "reference/reference.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

DielectricResult run(const std::vector<DielectricCell>& cells, std::uint64_t samples = 1 << 18) {
    DielectricRequest r;
    r.cells = cells;
    r.samples = samples;
    return compute_dielectric(testing::engine(), r);
}

}  // namespace

TEST_CASE("a nearly smooth dielectric reflects F and transmits 1 - F from both sides", "[dielectric][device]") {
    std::vector<DielectricCell> cells;
    const std::vector<double> mus = {0.2, 0.5, 0.8, 1.0};
    for (double eta : {1.5, 1 / 1.5, 1.0001, 3.0})
        for (double mu : mus) cells.push_back({mu, 1e-3, eta});
    const DielectricResult res = run(cells, 1 << 16);
    for (size_t k = 0; k < cells.size(); ++k) {
        const double F = ref::fresnel_dielectric(cells[k].mu, cells[k].eta);
        INFO("mu " << cells[k].mu << " eta " << cells[k].eta << " R " << res.reflected[k].value << " T "
                   << res.transmitted[k].value << " F " << F);
        // Roughness 1e-3 changes the result by far less than 1e-3.
        CHECK(std::fabs(res.reflected[k].value - F) <= 1e-3 + res.reflected[k].error);
        CHECK(std::fabs(res.transmitted[k].value - (1 - F)) <= 1e-3 + res.transmitted[k].error);
    }
}

TEST_CASE("rough dielectric R and T match independent quadrature", "[dielectric][device]") {
    const std::vector<DielectricCell> cells = {{0.5, 0.3, 1.5}, {0.9, 0.6, 1 / 1.5}, {0.3, 0.1, 1.33}};
    const DielectricResult res = run(cells);
    for (size_t k = 0; k < cells.size(); ++k) {
        double r, t;
        ref::rough_dielectric_rt(cells[k].mu, cells[k].alpha, cells[k].eta, ref::DielectricShadowing::Beta, r, t);
        INFO("cell " << k << ": R " << res.reflected[k].value << " vs " << r << ", T " << res.transmitted[k].value
                     << " vs " << t);
        CHECK(std::fabs(res.reflected[k].value - r) <= res.reflected[k].error);
        CHECK(std::fabs(res.transmitted[k].value - t) <= res.transmitted[k].error);
        CHECK(std::fabs(res.transmitted[k].value - t) <= 1e-4);
    }
}

TEST_CASE("dielectric table: R + T <= 1, and the two sides are reciprocal", "[dielectric][device]") {
    LutRequest lr = testing::lut_request("dielectric", "ggx", 6, 3, 3);
    lr.samples = 1 << 14;
    const Table t = compute_lut(testing::engine(), lr);
    REQUIRE(t.channels == std::vector<std::string>{"R", "T", "R_inside", "T_inside"});
    REQUIRE(t.image_height() == 9);
    for (size_t k = 0; k < t.error.size(); ++k) {
        CHECK(t.values[0][k] + t.values[1][k] <= 1 + 2 * t.error[k]);
        CHECK(t.values[2][k] + t.values[3][k] <= 1 + 2 * t.error[k]);
        for (int c = 0; c < 4; ++c) CHECK(t.values[c][k] >= 0.0);
    }
    // Reciprocity of the BTDF, f_t(i, o) / eta_o^2 = f_t(o, i) / eta_i^2, integrated over both
    // hemispheres: the hemispherical transmittance seen from outside equals eta^2 times that seen
    // from inside.
    using G = boost::math::quadrature::gauss<double, 20>;
    for (double alpha : {0.2, 0.7}) {
        const double eta = 1.5;
        std::vector<DielectricCell> cells;
        std::vector<double> w;
        for (size_t i = 0; i < G::abscissa().size(); ++i)
            for (int s : {-1, 1}) {
                const double mu = 0.5 + 0.5 * s * G::abscissa()[i];
                cells.push_back({mu, alpha, eta});
                cells.push_back({mu, alpha, 1 / eta});
                w.push_back(G::weights()[i]);  // 0.5 (interval) x 2 (definition of the average)
            }
        const DielectricResult res = run(cells, 1 << 16);
        double out = 0, in = 0, err = 0;
        for (size_t i = 0; i < w.size(); ++i) {
            const double mu = cells[2 * i].mu;
            out += w[i] * mu * res.transmitted[2 * i].value;
            in += w[i] * mu * res.transmitted[2 * i + 1].value;
            err += w[i] * mu * (res.transmitted[2 * i].error + eta * eta * res.transmitted[2 * i + 1].error);
        }
        INFO("alpha " << alpha << ": outside " << out << ", eta^2 inside " << eta * eta * in << " +- " << err);
        CHECK(std::fabs(out - eta * eta * in) <= err + 1e-4);
    }
}

TEST_CASE("rough dielectric: the vector kernel gives the scalar kernel's answer", "[dielectric][parity][device]") {
    // Same points, same shifts, the same shared sample function on float16/double8 lanes: the
    // two kernels may differ only by rounding. Grazing, smooth, rough, total internal reflection.
    std::vector<DielectricCell> cells;
    for (double mu : {1e-3, 0.2, 0.7, 1.0})
        for (double alpha : {1e-3, 0.3, 1.0})
            for (double eta : {1.0001, 1.5, 1.0 / 1.5}) cells.push_back({mu, alpha, eta});
    const bool fp64 = testing::engine().device().fp64;
    for (Precision p : {Precision::Float, Precision::Double}) {
        if (p == Precision::Double && !fp64) continue;
        for (bool correlated : {true, false}) {
            DielectricRequest r;
            r.cells = cells;
            r.samples = 1 << 14;
            r.precision = p;
            r.shadowing = correlated ? Shadowing::Correlated : Shadowing::Separable;
            r.vector_width = 1;
            const DielectricResult s = compute_dielectric(testing::engine(), r);
            r.vector_width = 0;
            const DielectricResult v = compute_dielectric(testing::engine(), r);
            CHECK(s.vector_width == 1);
            CHECK(v.vector_width == (testing::engine().device().type == "cpu" ? (p == Precision::Float ? 16u : 8u) : 1u));
            const double tol = p == Precision::Float ? 2e-5 : 1e-12;
            for (size_t i = 0; i < cells.size(); ++i) {
                INFO(precision_name(p) << " correlated " << correlated << " mu " << cells[i].mu << " alpha "
                                       << cells[i].alpha << " eta " << cells[i].eta << ": R " << s.reflected[i].value
                                       << " vs " << v.reflected[i].value << ", T " << s.transmitted[i].value << " vs "
                                       << v.transmitted[i].value);
                CHECK(std::fabs(s.reflected[i].value - v.reflected[i].value) <= tol);
                CHECK(std::fabs(s.transmitted[i].value - v.transmitted[i].value) <= tol);
                CHECK(std::fabs(s.reflected[i].value - v.reflected[i].value) <= s.reflected[i].error);
                CHECK(std::fabs(s.transmitted[i].value - v.transmitted[i].value) <= s.transmitted[i].error);
            }
        }
    }
}

TEST_CASE("the Beta function of height-correlated transmission against Boost", "[dielectric][quick]") {
    // bb_beta (a Stirling difference, branch-free for the vector kernels) against
    // boost::math::beta in long double, from a = b = 1 to b = 1e8, across its shift at 8.
    for (long double a : {1.0L, 1.0001L, 1.5L, 3.0L, 7.9L, 8.0L, 10.0L, 100.0L, 1e4L})
        for (long double b : {1.0L, 1.01L, 2.5L, 6.0L, 7.99L, 8.0L, 8.01L, 50.0L, 1e3L, 1e6L, 1e8L}) {
            const long double expect = boost::math::beta(a, b);
            const double got = bb_beta(double(a), double(b));
            INFO("a " << double(a) << " b " << double(b) << ": " << got << " vs " << double(expect));
            // log Gamma(a) + D, each of size a log a, leave about 1e-16 a log a in the exponent
            CHECK(got == Approx(double(expect)).epsilon(a > 100 ? 1e-10 : 2e-12));
        }
}

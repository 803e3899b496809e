// Issue 37's honesty sweep: for every table kind of the registry, a few texels of a small table
// refined to a tolerance against an independent reference (Boost.Math quadrature of the textbook
// formulas, benchmarks/reference/), each texel within its own error channel and every error
// within the tolerance. The texels include the cells where estimates lied before: the sheen's
// mirror cone at high roughness (ashikhmin, alpha 0.9375), the z = 0.99 slice of Cycles'
// generalized Schlick (a cusp at wo.h = 1), sheen-viewer at grazing mu (its visibility clamp's
// kinks), dielectric-eavg from inside (a bend of R + T at mu = 1/eta). A kind the sweep does not cover yet stands in
// kNotSwept with the reason; a registry kind in neither list fails the sweep, so a new kind must
// be added to one of them.
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <iomanip>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"
#include "ggx_albedo_reference.h"
#include "reference/gen_schlick_reference.h"
#include "reference/reference.h"
#include "checks.h"
#include "support.h"

using namespace brdfbake;

namespace {

/// The kinds the sweep does not cover yet, and why.
const std::map<std::string, std::string> kNotSwept = {
    {"ltc", "tests/python/test_ltc_reference.py checks it against numpy"},
    {"sheen-ltc", "random walks (minutes for a table): tests/test_sheen_volume.cpp checks the walk's R, first order "
                  "and transmission against closed forms and quadrature"},
    {"thin-film", "each thickness slice is the spectral conductor table (swept) at that thickness: "
                  "tests/test_thin_film_table.cpp checks slices against single-wavelength tables summed at 5 nm"},
};

/// Reference allowance: what the references' own error may add (their tolerances 1e-9 to 1e-10).
constexpr double kRefError = 1e-7;

/// A texel of a table: its channel values' references.
using Reference = std::function<std::vector<double>(double mu, double alpha, double z)>;

/// Checks every texel of `t` (or every `stride`-th from `first`) against `reference`: |value - reference| <=
/// error + kRefError per channel, and error <= tolerance.
void check_table(const Table& t, double tolerance, const Reference& reference, size_t stride = 1, size_t first = 0) {
    const size_t w = t.x.parameter.size(), h = t.y.parameter.size(), d = std::max<size_t>(1, t.z.parameter.size());
    size_t checked = 0;
    for (size_t k = first; k < w * h * d; k += stride) {
        const size_t i = k % w, j = (k / w) % h, l = k / (w * h);
        // 1D kinds: x is the roughness axis.
        const bool one_d = table_kind(t.kind).one_dimensional;
        const double mu = one_d ? 0.0 : t.x.parameter[i], alpha = one_d ? t.x.parameter[i] : t.y.parameter[j];
        const double z = t.z.parameter.empty() ? 0.0 : t.z.parameter[l];
        const std::vector<double> want = reference(mu, alpha, z);
        REQUIRE(want.size() == t.channels.size());
        for (size_t c = 0; c < want.size(); ++c) {
            const double got = t.values[c][k];
            INFO(t.kind << " channel " << t.channels[c] << " at mu " << mu << ", alpha " << alpha << ", z parameter " << z
                        << ": " << got << " +- " << t.error[k] << ", reference " << want[c] << " (off by "
                        << std::fabs(got - want[c]) << ")");
            CHECK(std::fabs(got - want[c]) <= t.error[k] + kRefError);
            CHECK(t.error[k] <= tolerance);
        }
        ++checked;
    }
    CHECK(checked > 0);
}

LutRequest request(const std::string& kind, const std::string& model, int w, int h, int d = 1) {
    LutRequest r = testing::lut_request(kind, model, w, h, d);
    r.precision = Precision::Double;
    r.tolerance.tolerance = 1e-6;
    r.alpha_map = "roughness";
    r.mu_map = "sqrt";
    r.alpha_lo = 0.2;  // the narrow lobes are the references' slow cases
    return r;
}

/// A rough dielectric kind's request at one eta texel, 1.5, and `w` roughness texels over [lo, hi].
LutRequest eta_15_request(const std::string& kind, int w, double alpha_lo, double alpha_hi) {
    LutRequest r = request(kind, "ggx", w, 1, 1);
    r.alpha_lo = alpha_lo;
    r.alpha_hi = alpha_hi;
    r.eta_lo = 1.4;
    r.eta_hi = 1.6;
    return r;
}

/// GGX (height-correlated) weighted by w(wo.h): the albedo under a Fresnel factor w.
double weighted(double mu, double alpha, const std::function<ref::ld(ref::ld)>& w) {
    return ref::ggx_albedo_weighted(mu, alpha, w, 1e-9);
}

double ggx_albedo(double mu, double alpha) { return testing::ggx_albedo_reference<30>(alpha, mu, 1e-11); }

ref::ld schlick_weight(ref::ld c) { return std::pow(std::max<ref::ld>(0, 1 - c), 5); }

/// The textbook conductor Fresnel (Born & Wolf), complex index n = eta + i k.
double conductor_fresnel(double c, double eta, double k) {
    const std::complex<double> n(eta, k), s2(1 - c * c, 0);
    const std::complex<double> nt = std::sqrt(n * n - s2);  // n cos(theta_t)
    const std::complex<double> rs = (c - nt) / (c + nt), rp = (n * n * c - nt) / (n * n * c + nt);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}

/// Cycles' estimate s_C = integral of w(wo.h) G1(wo) (wo.h) D(h) / mu_o over the half vectors h
/// whose reflection is above the horizon (gen_schlick_reference.h), w = (1 - wo.h)^exponent, in
/// polar coordinates about wo: h = cos(psi) wo + sin(psi) (cos(chi) e1 + sin(chi) e2), e1 =
/// (-mu_o, 0, sin_o) towards the normal, e2 = y. Then w depends on psi alone, its cusp at h = wo
/// is the end psi = 0, and wi.z = 2 cos(psi) h.z - mu_o > 0 is cos(chi) > -mu_o cos(2 psi) /
/// (sin(2 psi) sin_o): |chi| < chi_max(psi), which is pi up to psi1 = (pi/2 - theta_o)/2 and 0
/// from psi2 = (pi/2 + theta_o)/2. Tanh-sinh (Boost.Math) over psi in [0, psi1] and [psi1, psi2]
/// (every feature on an end), Gauss-Kronrod over chi (smooth). (The adaptive reference in (theta_h,
/// phi_h) takes minutes at exponent 0.05: the cusp lies inside its domain.)
double cycles_s_polar(double mu, double alpha, double exponent) {
    using ref::ld;
    boost::math::quadrature::tanh_sinh<double> ts;
    const ld sin_o = std::sqrt(1 - (ld)mu * mu), th_o = std::acos((ld)mu);
    const ref::Dir wo{sin_o, 0, (ld)mu};
    const ld g1 = ref::ggx_g1(wo, alpha, alpha);
    auto outer = [&](double psi) -> double {
        const ld cp = std::cos((ld)psi), sp = std::sin((ld)psi);
        const ld q = -(ld)mu * std::cos(2 * (ld)psi) / (std::sin(2 * (ld)psi) * sin_o);
        const ld chi_max = q <= -1 ? ref::kPi : q >= 1 ? 0 : std::acos(q);
        if (chi_max <= 0) return 0.0;
        const ld w = std::pow(std::max<ld>(0, 1 - cp), (ld)exponent);
        auto inner = [&](double chi) -> double {
            const ld c = std::cos((ld)chi), s = std::sin((ld)chi);
            const ref::Dir h{cp * wo.x - sp * c * (ld)mu, sp * s, cp * wo.z + sp * c * sin_o};
            if (h.z <= 0) return 0.0;
            return double(ref::ggx_d(h, alpha, alpha));
        };
        const double d = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(inner, 0.0, double(chi_max), 15, 1e-13);
        return double(2 * w * g1 * cp / (ld)mu * sp) * d;
    };
    const double psi1 = double((ref::kPi / 2 - th_o) / 2), psi2 = double((ref::kPi / 2 + th_o) / 2);
    return ts.integrate(outer, 0.0, psi1, 1e-12) + ts.integrate(outer, psi1, psi2, 1e-12);
}

/// The glTF Sample Viewer's sheen albedo (sheen-viewer, docs/models.md#sheen): E(mu_o) = integral
/// of D_Charlie(theta_h) min(V, 1) cos(theta_i) over the hemisphere, V the Estevez-Kulla ("charlie",
/// [EK17]'s fitted Lambda) or the Neubelt-Pettineo ("ashikhmin") visibility of
/// reference/reference.h, the texel min(E, 1). V depends on (mu_o, cos theta_i) alone, so the kinks
/// of the clamp are circles theta_i = const: found by bisection of V = 1 on a scan in theta_i and
/// added, with theta_o (the mirror cone of D), to the splits of the tanh-sinh quadrature (Boost.Math)
/// over theta_i; phi_i over [0, pi] (the lobe is symmetric).
double viewer_sheen(double mu, double alpha, bool charlie, double tol) {
    using ref::ld;
    const ref::Dir wo = ref::dir_mu(mu, 0);
    auto vis = [&](ld ci) {
        return charlie ? 1 / ((1 + ref::charlie_lambda(mu, alpha) + ref::charlie_lambda(ci, alpha)) * 4 * mu * ci)
                       : 1 / (4 * (ci + mu - ci * mu));
    };
    std::vector<double> splits = {0.0, std::acos(mu), double(ref::kPi / 2)};
    const int scan = 2000;
    auto above = [&](double th) { return vis(std::cos((ld)th)) > 1; };
    for (int k = 0; k < scan; ++k) {
        double a = double(ref::kPi / 2) * k / scan, b = double(ref::kPi / 2) * (k + 1) / scan;
        if (above(a) == above(b)) continue;
        const bool at_a = above(a);
        for (int it = 0; it < 80; ++it) {
            const double m = 0.5 * (a + b);
            (above(m) == at_a ? a : b) = m;
        }
        splits.push_back(0.5 * (a + b));
    }
    std::sort(splits.begin(), splits.end());
    boost::math::quadrature::tanh_sinh<double> ts(12);
    auto inner = [&](double th) {
        const ld c = std::cos((ld)th), s = std::sin((ld)th);
        if (c <= 0) return 0.0;
        const ld v = std::min<ld>(vis(c), 1);
        auto g = [&](double ph) {
            const ref::Dir wi = ref::dir(th, ph);
            const ref::Dir h = ref::normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
            return double(ref::charlie_d(std::acos(std::min<ld>(1, h.z)), alpha) * v * c * s);
        };
        return ts.integrate(g, 0.0, double(ref::kPi), 0.1 * tol);
    };
    double sum = 0;
    for (size_t k = 0; k + 1 < splits.size(); ++k)
        if (splits[k + 1] > splits[k]) sum += 2 * ts.integrate(inner, splits[k], splits[k + 1], tol);
    return std::min(sum, 1.0);
}

/// The sheen-viewer sweep: both LUTs (lut_sheen_E: charlie, lut_charlie: ashikhmin) at 3 x 3
/// texels, mu from 1/36 (grazing, where V clamps: the former 128^2 vs 64^2 rules understated
/// their error there, e.g. ashikhmin at mu 1/36, alpha 0.36: 0.654161 +- 1.04e-5 for 0.6541787)
/// to 0.69, roughness 1/3 to 0.87. A fixed rule, no tolerance: its errors within 1e-6 (the
/// README's bound over the 128 x 128 tables, 7.7e-7).
void sweep_sheen_viewer() {
    for (const bool charlie : {true, false}) {
        LutRequest r = request("sheen-viewer", std::string("sheen:visibility=") + (charlie ? "charlie" : "ashikhmin"), 3, 3);
        r.tolerance.tolerance = 0;
        check_table(compute_lut(testing::engine(), r), 1e-6, [&](double mu, double a, double) {
            return std::vector<double>{viewer_sheen(mu, a, charlie, 1e-9)};
        });
    }
}

/// Eavg = 2 integral of (R + T)(mu) mu dmu of the rough dielectric (GGX, Beta shadowing as the
/// dielectric sweep), E(mu) from ref::rough_dielectric_rt to 1e-9 (tanh-sinh split at its cuts and
/// at total internal reflection), by 15-point Gauss-Kronrod on mu panels that shrink toward grazing,
/// each halved `halvings` times, split at mu = eta for eta < 1 (from inside): there the cone of
/// half vectors past total internal reflection, wo.h < sqrt(1 - eta^2), starts to reach the horizon
/// of h (sin(theta_o) = sqrt(1 - eta^2)), and (R + T)(mu) bends (its slope is least there: 0.128 at
/// mu 0.65, 0.094 at 0.673, 0.098 at 0.69 for alpha 0.64, eta 1/1.5).
double dielectric_eavg_reference(double alpha, double eta, int halvings) {
    std::vector<double> edges = {0.0, 0.01, 0.1, 0.4};
    if (eta < 1) edges.push_back(eta);
    edges.push_back(1.0);
    for (int h = 0; h < halvings; ++h)
        for (size_t k = edges.size() - 1; k > 0; --k) edges.insert(edges.begin() + k, 0.5 * (edges[k - 1] + edges[k]));
    double sum = 0;
    for (size_t k = 0; k + 1 < edges.size(); ++k)
        sum += boost::math::quadrature::gauss_kronrod<double, 15>::integrate(
            [&](double mu) {
                double r, t;
                ref::rough_dielectric_rt(mu, alpha, eta, ref::DielectricShadowing::Beta, r, t, 1e-9);
                return (r + t) * mu;
            },
            edges[k], edges[k + 1], 0, 0);
    return 2 * sum;
}

/// dielectric_eavg_reference at alpha 0.64, eta 1.5 from outside and 1/1.5 from inside, recorded
/// here so that CI needs no minutes of quadrature (amd-epyc-2c, 2026-12-03). Outside: halvings 1,
/// E(mu) to 1e-9: 0.848355303098 (halvings 0: 0.84835530999, 6.9e-9 apart; 0.848355309991 with
/// E(mu) to 1e-8). Inside: halvings 0, E(mu) to 1e-8: 0.600208278547534 (the halved run did not
/// finish in that session: it takes about 3 times the outside's half hour on the loaded 2 cores).
/// Both far inside the sweep's allowance kRefError; the hidden test "[.][reference][dielectric-eavg]"
/// below recomputes them with every panel halved and checks these digits.
constexpr double kEavgOutside = 0.848355303098, kEavgInside = 0.600208278547534;

using Sweep = std::function<void()>;

/// One entry per kind the sweep covers.
std::map<std::string, Sweep> sweeps() {
    std::map<std::string, Sweep> s;
    s["albedo"] = [] {
        const LutRequest r = request("albedo", "ggx", 3, 3);
        check_table(compute_lut(testing::engine(), r), 1e-6,
                    [](double mu, double a, double) { return std::vector<double>{ggx_albedo(mu, a)}; });
    };
    s["eavg"] = [] {
        LutRequest r = request("eavg", "ggx", 2, 1);
        r.alpha_lo = 0.4;
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double, double a, double) {
            // 2 integral of E(mu) mu over mu: composite 20-point Gauss-Legendre on panels that
            // shrink toward grazing, where E(mu) bends.
            const double edges[] = {0.0, 0.01, 0.1, 0.4, 1.0};
            double sum = 0;
            for (size_t k = 0; k + 1 < std::size(edges); ++k)
                sum += boost::math::quadrature::gauss<double, 20>::integrate(
                    [&](double mu) { return ggx_albedo(mu, a) * mu; }, edges[k], edges[k + 1]);
            return std::vector<double>{2 * sum};
        });
    };
    s["dfg"] = [] {
        const LutRequest r = request("dfg", "ggx", 2, 2);
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double) {
            const double b = weighted(mu, a, schlick_weight);
            return std::vector<double>{ggx_albedo(mu, a) - b, b};
        }, 3);
    };
    s["dfg-ms"] = [] {
        const LutRequest r = request("dfg-ms", "ggx", 2, 2);
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double) {
            return std::vector<double>{weighted(mu, a, schlick_weight), ggx_albedo(mu, a)};
        }, 3);
    };
    s["dfg-f82"] = [] {
        const LutRequest r = request("dfg-f82", "ggx", 2, 2);
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double) {
            const double b = weighted(mu, a, schlick_weight);
            const double c = weighted(mu, a, [](ref::ld x) { return x * std::pow(std::max<ref::ld>(0, 1 - x), 6); });
            return std::vector<double>{ggx_albedo(mu, a) - b, b, c};
        }, 3);
    };
    s["conductor"] = [] {
        LutRequest r = request("conductor", "ggx", 2, 2);
        r.fresnel = "conductor:eta=0.2,k=3";
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double) {
            return std::vector<double>{
                weighted(mu, a, [](ref::ld c) { return ref::ld(conductor_fresnel(double(c), 0.2, 3.0)); })};
        }, 3);
    };
    s["sheen-albedo"] = [] {
        // High sheenRoughness (alpha near 0.9375, issue 37's cell): the cone at the mirror direction
        // that fooled the rules' comparison (issue 37), in both visibilities.
        for (const char* vis : {"ashikhmin", "charlie"}) {
            LutRequest r = request("sheen-albedo", std::string("sheen:visibility=") + vis, 1, 1);
            r.alpha_lo = std::sqrt(0.9375) - 0.01;  // one texel: alpha 0.9375
            r.alpha_hi = std::sqrt(0.9375) + 0.01;
            r.mu_lo = 0.7;  // sqrt map: mu 0.5625
            r.mu_hi = 0.8;
            const bool charlie = std::string(vis) == "charlie";
            check_table(compute_lut(testing::engine(), r), 1e-6, [&](double mu, double a, double) {
                return std::vector<double>{ref::albedo_sheen(a, charlie, mu, 1e-9)};
            }, 3);
        }
    };
    s["gen-schlick"] = [] {
        // Both estimators; the cycles one over the texels of Cycles' z = 0.99 slice (its z = 1,
        // clamped) at roughness 11/15 and mu 0.8, where its error claimed 4.3e-6 for 5.5e-5.
        LutRequest r = request("gen-schlick", "ggx", 2, 2, 2);
        r.alpha_lo = 0.4;
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double e) {
            return std::vector<double>{ref::ggx_gen_schlick_s(mu, a, e, 1e-9)};
        }, 3);
        LutRequest c = testing::lut_request("gen-schlick", "ggx:shadowing=masking", 2, 2, 2);
        c.estimator = "cycles";
        c.precision = Precision::Double;
        c.tolerance.tolerance = 1e-6;
        c.texels = Texels::Edge;
        c.alpha_map = "roughness";
        c.mu_lo = 0.8;
        c.mu_hi = 0.9;
        c.alpha_lo = 11.0 / 15;
        c.alpha_hi = 12.0 / 15;
        check_table(compute_lut(testing::engine(), c), 1e-6, [](double mu, double a, double e) {
            return std::vector<double>{cycles_s_polar(mu, a, e)};
        }, 8, 4);  // texel 4: mu 0.8, roughness 11/15, z = 0.99
    };
    s["gen-schlick-ior"] = [] {
        LutRequest r = request("gen-schlick-ior", "ggx", 2, 2, 2);
        r.alpha_lo = 0.4;
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double eta) {
            return std::vector<double>{ref::ggx_gen_schlick_ior_s(mu, a, eta, 1e-9)};
        }, 3);
    };
    s["sheen-viewer"] = sweep_sheen_viewer;
    s["dielectric-eavg"] = [] {
        // One texel: roughness 0.8 (alpha 0.64), eta 1.5, both sides; inside bends at mu = 1/1.5.
        const LutRequest r = eta_15_request("dielectric-eavg", 1, 0.75, 0.85);
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double, double a, double eta) {
            REQUIRE(a == Approx(0.64).epsilon(1e-12));
            REQUIRE(eta == Approx(1.5).epsilon(1e-12));
            return std::vector<double>{kEavgOutside, kEavgInside};
        });
    };
    s["dielectric"] = [] {
        // Two texels of R, T, R_inside, T_inside at eta 1.5, rough lobes (the reference is slow
        // for narrow ones seen from inside).
        LutRequest r = eta_15_request("dielectric", 2, 0.5, 0.7);
        r.mu_lo = 0.5;
        check_table(compute_lut(testing::engine(), r), 1e-6, [](double mu, double a, double eta) {
            double ro, to, ri, ti;
            ref::rough_dielectric_rt(mu, a, eta, ref::DielectricShadowing::Beta, ro, to, 1e-9);
            ref::rough_dielectric_rt(mu, a, 1 / eta, ref::DielectricShadowing::Beta, ri, ti, 1e-9);
            return std::vector<double>{ro, to, ri, ti};
        });
    };
    return s;
}

}  // namespace

TEST_CASE("honesty sweep: every table kind is swept or listed as not swept, with a reason", "[honesty][quick]") {
    const std::map<std::string, Sweep> swept = sweeps();
    for (const TableKind* k : table_kinds()) {
        INFO("table kind " << k->name << ": add it to the sweep (tests/test_honesty_sweep.cpp) or to kNotSwept");
        CHECK((swept.count(k->name) + kNotSwept.count(k->name)) == 1);
    }
    for (const auto& [name, reason] : kNotSwept) {
        INFO(name);
        CHECK(find_table_kind(name) != nullptr);
        CHECK(!reason.empty());
    }
    for (const auto& kv : swept) CHECK(find_table_kind(kv.first) != nullptr);
}

TEST_CASE("honesty sweep: each kind's texels within their error channel of an independent reference",
          "[honesty][device]") {
    for (const auto& [name, sweep] : sweeps()) {
        DYNAMIC_SECTION(name) { sweep(); }
    }
}

TEST_CASE("honesty sweep: the dielectric-eavg references recorded for CI, by quadrature (minutes)",
          "[.][reference][dielectric-eavg]") {
    for (const auto& [eta, recorded] : {std::pair{1.5, kEavgOutside}, std::pair{1 / 1.5, kEavgInside}}) {
        const double coarse = dielectric_eavg_reference(0.64, eta, 0), fine = dielectric_eavg_reference(0.64, eta, 1);
        INFO("eta " << eta << ": " << std::setprecision(15) << fine << ", with panels twice as wide " << coarse
                     << ", recorded " << recorded);
        CHECK(std::fabs(fine - coarse) < 2e-8);    // measured outside: 6.9e-9
        CHECK(std::fabs(fine - recorded) < 2e-8);  // recorded to 1e-12 outside; inside from halvings 0
    }
}

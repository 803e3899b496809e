// Stability at the extremes (issue 7): the device albedo over a grid of extreme parameters, in
// float and double, and the shared host functions at the same extremes.
//
// Device: for every model (and, for GGX, every Fresnel term) one compute_albedo request per
// precision holds all cells, so each kernel is built and launched once. Every cell must be
// finite (compute_albedo refuses non-finite samples; the test then names every offending cell),
// non-negative, at most 1 + its error estimate where the model conserves energy, with a finite
// error estimate, and float and double must agree within the sum of their error estimates.
//
// Host: Fresnel terms for eta in [1.0001, 3] and 1/1.5, k in [0, 100], up to theta = 89.999 deg
// and beyond, finite and in [0, 1]; D, Lambda, G1 and G2 of GGX and Beckmann finite (and G in
// [0, 1]) at alpha = 1e-4 and mu = 1e-5.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "support.h"

using namespace brdfbake;

namespace {

const std::vector<double> kMu = {1e-5, 1e-3, 0.01, 0.5, 1.0};
const std::vector<double> kAlpha = {1e-4, 1e-3, 0.01, 0.5, 1.0};
// 2^14 samples per cell: 16 replicas of 1024 points (a multiple of every vector width).
constexpr std::uint64_t kSamples = 1u << 14;

struct Cell {
    std::string label;  // the model spec and the direction, for messages
    AlbedoCell cell;
    bool conserving;    // E <= 1 must hold (energy-conserving model, F <= 1)
};

struct Group {
    std::string name;  // model family and Fresnel term
    int model = 0;
    FresnelConfig fresnel;
    std::vector<Cell> cells;
    unsigned vector_width = 0;  // AlbedoRequest::vector_width: 0 the device's choice, 1 scalar
};

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

/// Adds spec at every mu of kMu (and every phi of `phis_deg`) to the group.
void add(Group& g, const std::string& spec, bool conserving, const std::vector<double>& phis_deg = {0.0}) {
    const ModelConfig m = resolve_model(spec);
    if (g.cells.empty() && g.model == 0) g.model = m.id;
    REQUIRE(m.id == g.model);
    for (double phi : phis_deg)
        for (double mu : kMu)
            g.cells.push_back({m.canonical + " mu=" + fmt(mu) + " phi=" + fmt(phi) + "deg",
                               AlbedoCell{mu, phi * M_PI / 180.0, m.params}, conserving});
}

Group group(const std::string& name, const std::string& fresnel = "none", double wavelength = 0.0) {
    Group g;
    g.name = name + ", Fresnel " + fresnel;
    g.fresnel = resolve_fresnel(fresnel, wavelength);
    return g;
}

AlbedoRequest request(const Group& g, Precision p, const std::vector<AlbedoCell>& cells) {
    AlbedoRequest r;
    r.model = g.model;
    r.fresnel = g.fresnel;
    r.cells = cells;
    r.samples = kSamples;
    r.precision = p;
    r.vector_width = g.vector_width;
    return r;
}

/// Runs the group's cells in one request. On non-finite samples, runs each cell alone to name
/// every offending cell (the kernel is already built), fails the test, and returns nothing.
bool run(const Group& g, Precision p, std::vector<AlbedoValue>& out) {
    std::vector<AlbedoCell> cells;
    for (const auto& c : g.cells) cells.push_back(c.cell);
    try {
        out = compute_albedo(testing::engine(), request(g, p, cells)).values;
        REQUIRE(out.size() == g.cells.size());
        return true;
    } catch (const NonFiniteError& e) {
        std::ostringstream bad;
        bad << g.name << " (" << precision_name(p) << "): non-finite samples; first at cell " << e.cell << " ["
            << g.cells.at(e.cell).label << "], " << e.count << " samples. Every offending cell:";
        for (size_t i = 0; i < g.cells.size(); ++i) {
            try {
                compute_albedo(testing::engine(), request(g, p, {g.cells[i].cell}));
            } catch (const NonFiniteError& one) {
                bad << "\n  " << g.cells[i].label << " (" << one.count << " samples)";
            }
        }
        FAIL_CHECK(bad.str());
        return false;
    }
}

/// The checks of the issue over one group, in both precisions; logs the worst float/double
/// difference relative to the allowed one.
void check_group(const Group& g) {
    std::vector<AlbedoValue> vf, vd;
    const bool ok_f = run(g, Precision::Float, vf);
    const bool ok_d = run(g, Precision::Double, vd);
    int problems = 0;
    double worst_ratio = 0.0;
    std::string worst;
    for (size_t i = 0; i < g.cells.size(); ++i) {
        const Cell& c = g.cells[i];
        std::ostringstream msg;
        auto check_one = [&](const AlbedoValue& v, const char* prec) {
            if (!std::isfinite(v.value)) msg << " " << prec << " albedo not finite (" << v.value << ");";
            if (!(std::isfinite(v.error) && v.error >= 0)) msg << " " << prec << " error estimate " << v.error << ";";
            if (!(v.value >= 0.0)) msg << " " << prec << " albedo " << v.value << " < 0;";
            if (c.conserving && !(v.value <= 1.0 + v.error))
                msg << " " << prec << " albedo " << v.value << " > 1 + error " << v.error << ";";
        };
        if (ok_f) check_one(vf[i], "float");
        if (ok_d) check_one(vd[i], "double");
        if (ok_f && ok_d) {
            const double diff = std::fabs(vf[i].value - vd[i].value), allowed = vf[i].error + vd[i].error;
            if (!(diff <= allowed))
                msg << " float " << vf[i].value << " +- " << vf[i].error << " and double " << vd[i].value << " +- "
                    << vd[i].error << " differ by " << diff << ";";
            if (allowed > 0 && diff / allowed > worst_ratio) {
                worst_ratio = diff / allowed;
                worst = c.label;
            }
        }
        if (!msg.str().empty()) {
            ++problems;
            FAIL_CHECK(g.name << ": " << c.label << ":" << msg.str());
        }
    }
    CHECK(problems == 0);
    std::cout << "  " << g.name << ": " << g.cells.size() << " cells, worst |float - double| / (sum of errors) "
              << worst_ratio << " (" << worst << ")\n";
}

const std::vector<std::string> kShadowing = {"separable", "correlated"};

/// GGX or Beckmann: every alpha and both shadowings, isotropic, and three anisotropic pairs at
/// three azimuths.
Group smith_group(const std::string& model) {
    Group g = group(model);
    for (const auto& sh : kShadowing) {
        for (double a : kAlpha) add(g, model + ":alpha=" + fmt(a) + ",shadowing=" + sh, true);
        for (const char* aniso : {"alpha_x=0.0001,alpha_y=1", "alpha_x=1,alpha_y=0.001", "alpha_x=0.01,alpha_y=0.5"})
            add(g, model + ":" + aniso + ",shadowing=" + sh, true, {0.0, 45.0, 90.0});
    }
    return g;
}

}  // namespace

TEST_CASE("extremes: ggx finite, <= 1, float agrees with double", "[extremes][device]") {
    check_group(smith_group("ggx"));
    // GGX also has a vector path (the default on CPUs); the scalar kernel is what GPUs run.
    Group scalar = smith_group("ggx");
    scalar.vector_width = 1;
    scalar.name += ", scalar kernel";
    check_group(scalar);
}

TEST_CASE("extremes: beckmann finite, <= 1, float agrees with double", "[extremes][device]") {
    check_group(smith_group("beckmann"));
}

TEST_CASE("extremes: torrance-sparrow finite, <= 1, float agrees with double", "[extremes][device]") {
    Group g = group("torrance-sparrow");
    for (double n : {1.0, 100.0, 1e3, 1e4}) add(g, "torrance-sparrow:d=blinn,n=" + fmt(n), true);
    for (const char* d : {"beckmann", "ggx"}) {
        for (double a : kAlpha) add(g, std::string("torrance-sparrow:d=") + d + ",alpha=" + fmt(a), true);
        add(g, std::string("torrance-sparrow:d=") + d + ",alpha_x=0.0001,alpha_y=1", true, {0.0, 45.0, 90.0});
    }
    check_group(g);
}

TEST_CASE("extremes: blinn-phong and phong finite, float agrees with double", "[extremes][device]") {
    // Blinn-Phong is not energy conserving: normalized=1 normalises D, not the BRDF (E > 1), and
    // ks = 1 unnormalised has E up to pi for small exponents.
    Group bp = group("blinn-phong");
    for (double n : {1.0, 100.0, 1e3, 1e4})
        for (int norm : {0, 1}) add(bp, "blinn-phong:n=" + fmt(n) + ",normalized=" + std::to_string(norm), false);
    check_group(bp);
    // Normalised Phong conserves energy (Lewis 1994); unnormalised with n = 1e4 has E < 2 pi/1e4.
    Group ph = group("phong");
    for (double n : {1.0, 100.0, 1e3, 1e4}) add(ph, "phong:n=" + fmt(n) + ",normalized=1", true);
    add(ph, "phong:n=10000,ks=1", true);
    check_group(ph);
}

TEST_CASE("extremes: oren-nayar to sigma = 1.5 and lambert finite, <= 1, float agrees with double",
          "[extremes][device]") {
    Group on = group("oren-nayar");
    for (double s : {0.0, 0.5, 1.0, 1.5}) add(on, "oren-nayar:sigma=" + fmt(s) + ",rho=1", true);
    check_group(on);
    Group l = group("lambert");
    add(l, "lambert:rho=1", true);
    check_group(l);
}

TEST_CASE("extremes: ggx with dielectric, conductor and measured Fresnel terms", "[extremes][device]") {
    auto with_fresnel = [](const std::string& fresnel, double wavelength = 0.0) {
        Group g = group("ggx", fresnel, wavelength);
        for (double a : {1e-4, 0.01, 0.5, 1.0}) add(g, "ggx:alpha=" + fmt(a) + ",shadowing=correlated", true);
        add(g, "ggx:alpha=0.001,shadowing=separable", true);
        return g;
    };
    for (double eta : {1.0001, 1.5, 3.0, 1.0 / 1.5}) check_group(with_fresnel("dielectric:eta=" + fmt(eta)));
    for (double eta : {0.2, 1.0, 3.0})
        for (double k : {0.0, 1.0, 10.0, 100.0}) {
            check_group(with_fresnel("conductor:eta=" + fmt(eta) + ",k=" + fmt(k)));
            check_group(with_fresnel("conductor-approx:eta=" + fmt(eta) + ",k=" + fmt(k)));
        }
    check_group(with_fresnel("metal:Al", 550.0));
    for (double f0 : {0.0, 1.0}) check_group(with_fresnel("schlick:f0=" + fmt(f0)));
}

// ------------------------------------------------------------------------------ host, double

namespace {

// Angles in degrees up to grazing: 89.999 deg has cos = 1.7e-5.
const std::vector<double> kTheta = {0.0, 1e-3, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.9, 89.99, 89.999, 89.9999, 90.0};

bool unit_interval(double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; }

/// kTheta plus the angles where a reflectance of the conductor forms vanishes for k = 0:
/// cos = eta (r_perp of the approximate form, eta < 1), cos = 1/eta (its r_par, eta > 1; Brewster's
/// angle of the exact form is atan(eta)), where their numerators cancel.
std::vector<double> angles_with_zeros(double eta) {
    std::vector<double> t = kTheta;
    const double deg = 180.0 / M_PI;
    if (eta < 1.0) t.push_back(std::acos(eta) * deg);
    if (eta > 1.0) t.push_back(std::acos(1.0 / eta) * deg);
    t.push_back(std::atan(eta) * deg);
    return t;
}

}  // namespace

TEST_CASE("extremes: Fresnel terms finite and in [0, 1] on the host", "[extremes][fresnel][quick]") {
    int checked = 0;
    std::vector<double> etas = {1.0001, 1.001, 1.01, 1.1, 1.5, 2.0, 3.0, 1.0 / 1.5, 1.0 / 1.0001, 1.0 / 3.0};
    for (double eta : etas)
        for (double t : kTheta) {
            const double c = std::cos(t * M_PI / 180.0);
            for (double cs : {c, -c}) {  // -c: seen from the other side
                const bb_fresnel_sp d = bb_fresnel_dielectric_sp(cs, eta);
                const double f = bb_fresnel_dielectric(cs, eta);
                INFO(std::setprecision(17) << "dielectric eta = " << eta << " cos = " << cs << ": Rs " << d.rs << " Rp " << d.rp << " F " << f);
                CHECK(unit_interval(d.rs));
                CHECK(unit_interval(d.rp));
                CHECK(unit_interval(f));
                checked += 3;
            }
        }
    for (double eta : {0.2, 0.5, 1.0, 1.0001, 1.5, 2.0, 3.0, 1.0 / 1.5})
        for (double k : {0.0, 1e-4, 0.1, 1.0, 10.0, 30.0, 100.0})
            for (double t : angles_with_zeros(eta)) {
                const double c = std::cos(t * M_PI / 180.0);
                const bb_fresnel_sp e = bb_fresnel_conductor_sp(c, eta, k);
                const bb_fresnel_sp a = bb_fresnel_conductor_approx_sp(c, eta, k);
                INFO(std::setprecision(17) << "conductor eta = " << eta << " k = " << k << " theta = " << t << " deg: exact Rs " << e.rs << " Rp "
                                        << e.rp << ", approx Rs " << a.rs << " Rp " << a.rp);
                CHECK(unit_interval(e.rs));
                CHECK(unit_interval(e.rp));
                CHECK(unit_interval(bb_fresnel_conductor(c, eta, k)));
                CHECK(unit_interval(a.rs));
                CHECK(unit_interval(a.rp));
                CHECK(unit_interval(bb_fresnel_conductor_approx(c, eta, k)));
                checked += 6;
            }
    for (double f0 : {0.0, 0.04, 1.0})
        for (double t : kTheta) CHECK(unit_interval(bb_fresnel_schlick(std::cos(t * M_PI / 180.0), f0)));
    CHECK(checked > 1000);
}

TEST_CASE("extremes: D, Lambda, G1, G2 finite at alpha = 1e-4 and mu = 1e-5 on the host",
          "[extremes][microfacet][quick]") {
    const std::vector<double> mus = {1e-5, 1e-4, 1e-3, 0.01, 0.5, 1.0};
    const std::vector<std::pair<double, double>> alphas = {{1e-4, 1e-4}, {1e-3, 1e-3}, {1e-4, 1.0}, {1.0, 1e-4}, {1.0, 1.0}};
    auto dir = [](double mu, double phi) {
        const double s = std::sqrt((1 - mu) * (1 + mu));
        return bb_v3(s * std::cos(phi), s * std::sin(phi), mu);
    };
    int checked = 0;
    for (const auto& a : alphas)
        for (double mu : mus)
            for (double phi : {0.0, M_PI / 4, M_PI / 2, 2.0}) {
                const bb_vec3 w = dir(mu, phi);
                const double lg = bb_ggx_lambda(w, a.first, a.second), lb = bb_beckmann_lambda(w, a.first, a.second);
                const double gg = bb_ggx_g1(w, a.first, a.second), gb = bb_beckmann_g1(w, a.first, a.second);
                const double dg = bb_ggx_d(w, a.first, a.second), db = bb_beckmann_d(w, a.first, a.second);
                const double bl = bb_blinn_d(w, 1e4);
                INFO("alpha = (" << a.first << ", " << a.second << ") mu = " << mu << " phi = " << phi << ": GGX Lambda "
                                 << lg << " G1 " << gg << " D " << dg << "; Beckmann Lambda " << lb << " G1 " << gb
                                 << " D " << db << "; Blinn(1e4) D " << bl);
                CHECK((std::isfinite(lg) && lg >= 0));
                CHECK((std::isfinite(lb) && lb >= 0));
                CHECK(unit_interval(gg));
                CHECK(unit_interval(gb));
                CHECK((std::isfinite(dg) && dg >= 0));
                CHECK((std::isfinite(db) && db >= 0));
                CHECK((std::isfinite(bl) && bl >= 0));
                // Lambda and G1 describe the same masking: G1 = 1/(1 + Lambda).
                CHECK(gg == Approx(1.0 / (1.0 + lg)).epsilon(1e-12));
                CHECK(gb == Approx(1.0 / (1.0 + lb)).epsilon(1e-10));
                for (double mi : mus) {
                    const bb_vec3 wi = dir(mi, phi + 1.0);
                    const double ggi = bb_ggx_g1(wi, a.first, a.second), gbi = bb_beckmann_g1(wi, a.first, a.second);
                    for (double g2 : {bb_g2_separable_from_g1(gg, ggi), bb_g2_correlated_from_g1(gg, ggi),
                                      bb_g2_separable_from_g1(gb, gbi), bb_g2_correlated_from_g1(gb, gbi)}) {
                        INFO("wi mu = " << mi << ": G2 " << g2);
                        CHECK(unit_interval(g2));
                    }
                }
                checked += 9;
            }
    CHECK(checked > 1000);
}

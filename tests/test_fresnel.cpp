// Fresnel terms (include/brdfbake/brdf/fresnel.h), the fresnel_curve kernel, measured n,k data
// and the `fresnel` command, against physics and an independent implementation: the textbook
// amplitude coefficients in std::complex<long double> (Born & Wolf 1.5.2 eq. 21 with the complex
// index of 14.2), written here without looking at the shared header's algebra.
#include <catch2/catch.hpp>

#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/spec.h"
#include "engine/device_buffer.h"
#include "models/nk_data.h"
#include "image_readers.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

using ld = long double;
using cld = std::complex<ld>;
const ld kPiL = 3.141592653589793238462643383279502884L;

struct RsRp {
    ld rs, rp;
    ld f() const { return (rs + rp) / 2; }
};

/// Independent reference: reflection of light arriving from a medium of index 1 on a medium of
/// complex index n2 = eta + i k. Snell: sin_t = sin_i / n2; of the two roots cos_t = +-sqrt(1 -
/// sin_t^2) the physical one makes the transmitted wave decay (Im(n2 cos_t) >= 0), and for a
/// lossless medium without total reflection it is the one with Re(cos_t) > 0.
///   r_s = (cos_i - n2 cos_t) / (cos_i + n2 cos_t),  r_p = (n2 cos_i - cos_t) / (n2 cos_i + cos_t).
RsRp textbook(ld cos_i, ld eta, ld k) {
    const cld n2(eta, k);
    const ld sin_i = std::sqrt(std::max<ld>(0, 1 - cos_i * cos_i));
    const cld sin_t = sin_i / n2;
    cld cos_t = std::sqrt(cld(1) - sin_t * sin_t);
    const cld wave = n2 * cos_t;
    if (wave.imag() < 0 || (wave.imag() == 0 && wave.real() < 0)) cos_t = -cos_t;
    const cld rs = (cos_i - n2 * cos_t) / (cos_i + n2 * cos_t);
    const cld rp = (n2 * cos_i - cos_t) / (n2 * cos_i + cos_t);
    return {std::norm(rs), std::norm(rp)};
}

/// Independent reference for the approximate form of the course notes (pbrt 2nd ed. eq. 8.3).
RsRp textbook_approx(ld c, ld eta, ld k) {
    const ld t = eta * eta + k * k;
    return {(t - 2 * eta * c + c * c) / (t + 2 * eta * c + c * c),
            (t * c * c - 2 * eta * c + 1) / (t * c * c + 2 * eta * c + 1)};
}

double cos_deg(double theta) { return double(std::cos((ld)theta * kPiL / 180)); }

bb_params params(double eta, double k) {
    bb_params p{};
    p.v[BB_FRESNEL_ETA] = eta;
    p.v[BB_FRESNEL_K] = k;
    return p;
}

/// Points that are not within a degree or so of a critical angle (for the summary figure).
bool t_ok_for_worst(int kind, double e, double c, bool fl) {
    return !(fl && kind == BB_FRESNEL_DIELECTRIC && std::fabs((e - 1) * (e + 1) + c * c) < 1e-2);
}

/// x rounded to float, as the kernel's buffers hold it.
double to_float(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

/// F, Rs, Rp of the fresnel_curve kernel.
std::vector<double> kernel_values(int kind, const bb_params& p, const std::vector<double>& cosines, Precision prec) {
    Engine& engine = testing::engine();
    BuildRequest build;
    build.kernel_file = "fresnel.cl";
    build.precision = prec;
    build.fresnel = kind;
    cl::Program& program = engine.program(build);
    RealBuffers bufs(engine, prec);
    cl::Buffer b_cos = bufs.input(cosines);
    cl::Buffer b_p = bufs.input(std::vector<double>(p.v, p.v + BB_MAX_PARAMS));
    cl::Buffer b_out = bufs.output(3 * cosines.size());
    cl::Kernel kernel(program, "fresnel_curve");
    kernel.setArg(0, b_cos);
    kernel.setArg(1, b_p);
    kernel.setArg(2, cl_uint(cosines.size()));
    kernel.setArg(3, b_out);
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(cosines.size()), cl::NullRange);
    return bufs.read(b_out, 3 * cosines.size());
}

const std::vector<double> kDoneAngles = {0, 30, 60, 75, 85, 89, 89.9};

/// The sweep of the finiteness tests: eta log-spaced over [1.0001, 10], k over [0, 100].
std::vector<double> eta_sweep() {
    std::vector<double> v;
    for (int i = 0; i <= 24; ++i) v.push_back(1.0001 * std::pow(10.0 / 1.0001, i / 24.0));
    v.back() = 10.0;
    return v;
}
const std::vector<double> kKSweep = {0.0, 1e-4, 0.01, 0.5, 1.0, 3.0, 10.0, 30.0, 100.0};
std::vector<double> angle_sweep() {
    std::vector<double> v;
    for (int i = 0; i <= 89; ++i) v.push_back(i);
    for (double t : {89.5, 89.9, 89.99, 89.999, 90.0}) v.push_back(t);
    return v;
}

}  // namespace

TEST_CASE("Fresnel at normal incidence equals the closed forms", "[fresnel][quick]") {
    for (double eta : {0.2, 1.0 / 1.5, 1.0001, 1.33, 1.5, 2.4, 10.0}) {
        const double expect = std::pow((eta - 1) / (eta + 1), 2);
        INFO("eta = " << eta);
        CHECK(bb_fresnel_dielectric(1.0, eta) == Approx(expect).margin(1e-15));
        CHECK(bb_fresnel_dielectric_rs(1.0, eta) == Approx(bb_fresnel_dielectric_rp(1.0, eta)).margin(1e-16));
        for (double k : {0.0, 0.5, 6.69, 100.0}) {
            const double ec = ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
            INFO("k = " << k);
            CHECK(bb_fresnel_conductor(1.0, eta, k) == Approx(ec).epsilon(1e-13).margin(1e-15));
            CHECK(bb_fresnel_conductor_approx(1.0, eta, k) == Approx(ec).epsilon(1e-13).margin(1e-15));
            CHECK(bb_fresnel_conductor_rs(1.0, eta, k) == Approx(bb_fresnel_conductor_rp(1.0, eta, k)).epsilon(1e-13).margin(1e-15));
        }
    }
}

TEST_CASE("eta = 1.5: 0.04 at normal incidence, 0.05024 at 45 deg, Rp = 0 at Brewster's angle", "[fresnel][quick]") {
    CHECK(bb_fresnel_dielectric(1.0, 1.5) == Approx(0.04).margin(1e-16));
    // 45 deg by hand: cos_t = sqrt(1 - 0.5/2.25) = 0.881917103688197, r_s = -0.303337..., r_p =
    // 0.0920...; F = 0.0502399. At 45 deg r_p = r_s^2 for every index (Abeles' condition), a
    // second check that does not go through Snell's law.
    const double c45 = std::sqrt(0.5);
    CHECK(bb_fresnel_dielectric(c45, 1.5) == Approx(0.0502399).margin(1e-7));
    CHECK(std::fabs(bb_fresnel_dielectric(c45, 1.5) - 0.05024) < 5e-6);
    const double rs = bb_fresnel_dielectric_rs(c45, 1.5);
    CHECK(bb_fresnel_dielectric_rp(c45, 1.5) == Approx(rs * rs).epsilon(1e-13));
    // Brewster: tan(theta_B) = eta, theta_B = 56.3099 deg; Rp vanishes there, from both sides.
    const double tb = std::atan(1.5);
    CHECK(tb * 180 / M_PI == Approx(56.3099).margin(1e-4));
    CHECK(bb_fresnel_dielectric_rp(std::cos(tb), 1.5) < 1e-30);
    CHECK(bb_fresnel_dielectric_rp(std::cos(tb + 0.01), 1.5) > 1e-6);
    CHECK(bb_fresnel_dielectric_rp(std::cos(std::atan(1 / 1.5)), 1 / 1.5) < 1e-30);
    CHECK(bb_fresnel_conductor_rp(std::cos(tb), 1.5, 0.0) < 1e-30);
}

TEST_CASE("Total internal reflection from inside beyond the critical angle", "[fresnel][quick]") {
    const double eta = 1 / 1.5;
    const double crit = std::asin(eta);  // 41.81 deg
    CHECK(crit * 180 / M_PI == Approx(41.8103).margin(1e-4));
    for (double t = crit + 1e-9; t <= M_PI / 2; t += 0.01) {
        INFO("theta = " << t * 180 / M_PI);
        CHECK(bb_fresnel_dielectric(std::cos(t), eta) == 1.0);
        CHECK(bb_fresnel_dielectric_rs(std::cos(t), eta) == 1.0);
        CHECK(bb_fresnel_dielectric_rp(std::cos(t), eta) == 1.0);
        CHECK(bb_fresnel_conductor(std::cos(t), eta, 0.0) == Approx(1.0).epsilon(1e-14));
    }
    CHECK(bb_fresnel_dielectric(std::cos(crit - 1e-3), eta) < 1.0);
    // Reaching the interface from the far side (cos < 0) is the same as inverting eta.
    for (double c : {0.1, 0.5, 0.74, 0.9, 1.0})
        CHECK(bb_fresnel_dielectric(-c, 1.5) == Approx(bb_fresnel_dielectric(c, eta)).epsilon(1e-14));
}

TEST_CASE("A conductor with k = 0 equals the dielectric, eta = 1 gives 0", "[fresnel][quick]") {
    for (double eta : {0.5, 1 / 1.5, 0.999, 1.0001, 1.5, 2.4, 10.0})
        for (double t : angle_sweep()) {
            const double c = cos_deg(t);
            INFO("eta = " << eta << " theta = " << t);
            CHECK(bb_fresnel_conductor_rs(c, eta, 0.0) == Approx(bb_fresnel_dielectric_rs(c, eta)).margin(1e-13));
            CHECK(bb_fresnel_conductor_rp(c, eta, 0.0) == Approx(bb_fresnel_dielectric_rp(c, eta)).margin(1e-13));
        }
    for (double t : angle_sweep()) {
        const double c = cos_deg(t);
        CHECK(bb_fresnel_dielectric(c, 1.0) == 0.0);
        CHECK(bb_fresnel_dielectric_rs(c, 1.0) == 0.0);
        CHECK(bb_fresnel_dielectric_rp(c, 1.0) == 0.0);
        CHECK(bb_fresnel_conductor(c, 1.0, 0.0) == 0.0);
        CHECK(bb_fresnel_eval(BB_FRESNEL_DIELECTRIC, params(1.0, 0.0), c) == 0.0);
    }
}

TEST_CASE("F tends to 1 at grazing incidence", "[fresnel][quick]") {
    for (double eta : {0.3, 1 / 1.5, 1.0001, 1.5, 10.0})
        for (double k : {0.0, 0.1, 6.69, 100.0}) {
            INFO("eta = " << eta << " k = " << k);
            CHECK(bb_fresnel_conductor(0.0, eta, k) == 1.0);
            CHECK(bb_fresnel_conductor_approx(0.0, eta, k) == 1.0);
            CHECK(1.0 - bb_fresnel_conductor(1e-9, eta, k) < 1e-3);
            // Monotone approach over the last tenth of a degree.
            CHECK(bb_fresnel_conductor(cos_deg(89.999), eta, k) >= bb_fresnel_conductor(cos_deg(89.9), eta, k));
        }
    for (double eta : {1 / 1.5, 1.0001, 1.5, 10.0}) CHECK(bb_fresnel_dielectric(0.0, eta) == Approx(1.0).epsilon(1e-15));
    CHECK(bb_fresnel_schlick(0.0, 0.04) == 1.0);
}

TEST_CASE("Done-when: exact and approximate values match the textbook formulas to 1e-6", "[fresnel][quick]") {
    struct Case {
        double eta, k;
    };
    for (Case cs : {Case{0.958, 6.69}, Case{1.5, 0.0}, Case{1 / 1.5, 0.0}})
        for (double t : kDoneAngles) {
            const double c = cos_deg(t);
            const RsRp ref = textbook(c, cs.eta, cs.k);
            const RsRp apx = textbook_approx(c, cs.eta, cs.k);
            INFO("eta = " << cs.eta << " k = " << cs.k << " theta = " << t << " reference F = " << double(ref.f()));
            CHECK(std::fabs(bb_fresnel_conductor(c, cs.eta, cs.k) - double(ref.f())) < 1e-6);
            CHECK(std::fabs(bb_fresnel_conductor_rs(c, cs.eta, cs.k) - double(ref.rs)) < 1e-6);
            CHECK(std::fabs(bb_fresnel_conductor_rp(c, cs.eta, cs.k) - double(ref.rp)) < 1e-6);
            if (cs.k == 0.0) {
                CHECK(std::fabs(bb_fresnel_dielectric(c, cs.eta) - double(ref.f())) < 1e-6);
                CHECK(std::fabs(bb_fresnel_dielectric_rs(c, cs.eta) - double(ref.rs)) < 1e-6);
                CHECK(std::fabs(bb_fresnel_dielectric_rp(c, cs.eta) - double(ref.rp)) < 1e-6);
            }
            CHECK(std::fabs(bb_fresnel_conductor_approx(c, cs.eta, cs.k) - double(apx.f())) < 1e-6);
            // Much tighter in fact: the forms are accurate to a few ulps in double.
            CHECK(std::fabs(bb_fresnel_conductor(c, cs.eta, cs.k) - double(ref.f())) < 1e-13);
            // The dispatch gives the same as the direct calls.
            CHECK(bb_fresnel_eval(BB_FRESNEL_CONDUCTOR, params(cs.eta, cs.k), c) == bb_fresnel_conductor(c, cs.eta, cs.k));
        }
}

TEST_CASE("Every value is finite and in [0, 1] over eta, k and angles on the host", "[fresnel][quick]") {
    int checked = 0;
    for (double eta : eta_sweep())
        for (double k : kKSweep)
            for (double t : angle_sweep()) {
                const double c = cos_deg(t);
                const bb_fresnel_sp e = bb_fresnel_conductor_sp(c, eta, k);
                const bb_fresnel_sp a = bb_fresnel_conductor_approx_sp(c, eta, k);
                const bb_fresnel_sp d = bb_fresnel_dielectric_sp(c, eta);
                const bb_fresnel_sp di = bb_fresnel_dielectric_sp(c, 1 / eta);
                for (double v : {e.rs, e.rp, a.rs, a.rp, d.rs, d.rp, di.rs, di.rp}) {
                    if (!(std::isfinite(v) && v >= 0.0 && v <= 1.0 + 1e-15)) {
                        INFO("eta = " << eta << " k = " << k << " theta = " << t << " value " << v);
                        FAIL();
                    }
                    ++checked;
                }
            }
    CHECK(checked > 100000);
}

TEST_CASE("The fresnel_curve kernel is finite everywhere and agrees with the host", "[fresnel][device]") {
    // The host evaluates the kernel's own inputs: for a float kernel the cosines and eta, k
    // rounded to float, so that the comparison measures the kernel's arithmetic and not the
    // rounding of its inputs (eta = 1.0001 in float is 1.00010001659, which moves F near
    // grazing by 2e-5).
    std::vector<double> cos_d;
    for (double t : angle_sweep()) cos_d.push_back(cos_deg(t));
    for (Precision prec : {Precision::Float, Precision::Double}) {
        const bool fl = prec == Precision::Float;
        const double tol = fl ? 2e-5 : 1e-12;
        std::vector<double> cosines;
        for (double c : cos_d) cosines.push_back(fl ? to_float(c) : c);
        double worst = 0.0;
        for (int kind : {BB_FRESNEL_DIELECTRIC, BB_FRESNEL_CONDUCTOR, BB_FRESNEL_CONDUCTOR_APPROX})
            for (double eta : eta_sweep())
                for (double k : kind == BB_FRESNEL_DIELECTRIC ? std::vector<double>{0.0} : kKSweep)
                    for (double e : kind == BB_FRESNEL_DIELECTRIC ? std::vector<double>{eta, 1 / eta}
                                                                  : std::vector<double>{eta}) {
                        const bb_params p = fl ? params(to_float(e), to_float(k)) : params(e, k);
                        const auto out = kernel_values(kind, p, cosines, prec);
                        for (size_t i = 0; i < cosines.size(); ++i) {
                            const double host[3] = {bb_fresnel_eval(kind, p, cosines[i]),
                                                    bb_fresnel_eval_rs(kind, p, cosines[i]),
                                                    bb_fresnel_eval_rp(kind, p, cosines[i])};
                            for (int j = 0; j < 3; ++j) {
                                const double v = out[3 * i + j];
                                if (t_ok_for_worst(kind, e, cosines[i], fl)) worst = std::max(worst, std::fabs(v - host[j]));
                                // Within a degree or so of the critical angle the result depends on
                                // eta^2 - sin^2 = (eta cos_t)^2, which a float holds only to ~6e-8
                                // absolute: the float kernel is allowed a larger error there.
                                const double q = (e - 1) * (e + 1) + cosines[i] * cosines[i];
                                const double t = (fl && kind == BB_FRESNEL_DIELECTRIC && std::fabs(q) < 1e-2) ? 3e-4 : tol;
                                if (!std::isfinite(v) || std::fabs(v - host[j]) > t) {
                                    INFO(precision_name(prec) << " kind " << kind << " eta = " << std::setprecision(12) << p.v[BB_FRESNEL_ETA] << " k = " << k
                                                              << " cos = " << cosines[i] << " component " << j
                                                              << ": device " << v << " host " << host[j]);
                                    FAIL();
                                }
                            }
                        }
                    }
        INFO(precision_name(prec) << " worst |device - host| = " << worst);
        CHECK(worst <= tol);
        WARN(precision_name(prec) << ": max |kernel - host double| over the sweep = " << worst);
    }
}

TEST_CASE("Tabulated n,k: presets, interpolation, files and their errors", "[fresnel][quick]") {
    // Aluminium at 550 nm lies between the rows 0.5166 um (0.8734, 6.2418) and 0.56357 um
    // (1.0728, 6.7839) of Rakic 1995 (data/nk/Al-Rakic.yml).
    const double t = (0.550 - 0.5166) / (0.56357 - 0.5166);
    const NkValue al = interpolate_nk(load_nk_preset("Al"), 550.0);
    CHECK(al.n == Approx(0.8734 + t * (1.0728 - 0.8734)).epsilon(1e-12));
    CHECK(al.k == Approx(6.2418 + t * (6.7839 - 6.2418)).epsilon(1e-12));
    const FresnelConfig f = resolve_fresnel("metal:Al", 550.0);
    CHECK(f.kind == BB_FRESNEL_CONDUCTOR);
    CHECK(f.params[BB_FRESNEL_ETA] == al.n);
    CHECK(f.params[BB_FRESNEL_K] == al.k);
    for (const char* m : {"Au", "Ag", "Cu"}) {
        const FresnelConfig g = resolve_fresnel(std::string("metal:") + m, 600.0);
        CHECK(g.params[BB_FRESNEL_ETA] > 0.0);
        CHECK(g.params[BB_FRESNEL_K] > 1.0);
    }
    // A row of the table is returned as it is.
    const NkValue au = interpolate_nk(load_nk_preset("Au"), 548.6);
    CHECK(au.n == Approx(0.43).epsilon(1e-12));
    CHECK(au.k == Approx(2.455).epsilon(1e-12));

    CHECK_THROWS_AS(resolve_fresnel("metal:Al", 0.0), Error);
    CHECK_THROWS_WITH(resolve_fresnel("metal:Al", 0.0), Catch::Contains("--wavelength"));
    CHECK_THROWS_WITH(resolve_fresnel("metal:Au", 5000.0), Catch::Contains("outside the range"));
    CHECK_THROWS_WITH(resolve_fresnel("metal:Xx", 550.0), Catch::Contains("unknown metal"));

    // A file of its own: tabulated n only (a dielectric, k = 0), and broken files.
    const std::string path = "/tmp/brdfbake-nk-" + std::to_string(::getpid()) + ".yml";
    {
        std::ofstream out(path);
        out << "REFERENCES: test\nDATA:\n  - type: tabulated n\n    data: |\n        0.4 1.6\n        0.6 1.5\n";
    }
    const FresnelConfig glass = resolve_fresnel("nk:" + path, 500.0);
    CHECK(glass.params[BB_FRESNEL_ETA] == Approx(1.55).epsilon(1e-12));
    CHECK(glass.params[BB_FRESNEL_K] == 0.0);
    {
        std::ofstream out(path);
        out << "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.6 0.1\n        0.3 1.5\n";
    }
    CHECK_THROWS_AS(resolve_fresnel("nk:" + path, 500.0), Error);
    {
        std::ofstream out(path);
        out << "DATA:\n  - type: formula 2\n    coefficients: 0 1 2\n";
    }
    CHECK_THROWS_WITH(resolve_fresnel("nk:" + path, 500.0), Catch::Contains("tabulated"));
    std::remove(path.c_str());
    CHECK_THROWS_WITH(resolve_fresnel("nk:/nonexistent/file.yml", 500.0), Catch::Contains("cannot read"));
}

TEST_CASE("Fresnel specs: canonical forms and bad values", "[fresnel][quick]") {
    CHECK(resolve_fresnel("dielectric:eta=1.5").canonical == "dielectric:eta=1.5");
    CHECK(resolve_fresnel("conductor:eta=0.958,k=6.69").kind == BB_FRESNEL_CONDUCTOR);
    CHECK(resolve_fresnel("conductor-approx:eta=0.958,k=6.69").kind == BB_FRESNEL_CONDUCTOR_APPROX);
    for (const char* bad : {"dielectric:eta=-1", "dielectric:eta=0", "dielectric:eta=nan", "dielectric",
                            "dielectric:eta=1.5,k=2", "conductor:eta=1", "conductor:eta=1,k=-1", "glass:eta=1.5",
                            "schlick:f0=2", "metal:", "nk:"}) {
        INFO(bad);
        CHECK_THROWS_AS(resolve_fresnel(bad, 550.0), Error);
    }
}

TEST_CASE("fresnel --format json: values and the hemispherical average against quadrature", "[fresnel][cli]") {
    const auto r = testing::run_cli(
        "fresnel --fresnel conductor:eta=0.958,k=6.69 --theta 0,30,60,75,85,89,89.9 --precision double --format json");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j.at("results").size() == kDoneAngles.size());
    for (size_t i = 0; i < kDoneAngles.size(); ++i) {
        const auto& e = j["results"][i];
        const RsRp ref = textbook(cos_deg(kDoneAngles[i]), 0.958, 6.69);
        CHECK(e.at("theta_deg").get<double>() == kDoneAngles[i]);
        CHECK(std::fabs(e.at("F").get<double>() - double(ref.f())) < 1e-6);
        CHECK(std::fabs(e.at("Rs").get<double>() - double(ref.rs)) < 1e-6);
        CHECK(std::fabs(e.at("Rp").get<double>() - double(ref.rp)) < 1e-6);
    }
    const double avg = j.at("hemispherical_average").at("value").get<double>();
    const double err = j.at("hemispherical_average").at("error").get<double>();
    const double expect = ref::integrate([](double mu) { return double(2 * textbook(mu, 0.958, 6.69).f() * mu); }, 0.0, 1.0, 1e-13);
    INFO("average " << avg << " +- " << err << ", quadrature " << expect);
    CHECK(std::fabs(avg - expect) <= err + 1e-13);
    CHECK(err < 1e-12);
    // The approximate form's deviation, scanned by the command, against a scan of the references.
    double dev = 0.0;
    for (int i = 0; i <= 9000; ++i) {
        const ld c = cos_deg(i * 0.01);
        dev = std::max(dev, double(std::fabs(textbook_approx(c, 0.958, 6.69).f() - textbook(c, 0.958, 6.69).f())));
    }
    const double got = j.at("deviations").at("conductor_approx").at("max_abs").get<double>();
    CHECK(got >= dev - 1e-12);
    CHECK(got <= dev * 1.001);
}

TEST_CASE("fresnel: hemispherical average of a dielectric from inside, with total reflection", "[fresnel][cli]") {
    const auto r = testing::run_cli("fresnel --fresnel dielectric:eta=0.6666666666666666 --theta 0 --format json");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    const double avg = j.at("hemispherical_average").at("value").get<double>();
    const double err = j.at("hemispherical_average").at("error").get<double>();
    // Split at the critical cosine, where the integrand has a square-root corner.
    const double eta = 0.6666666666666666, mu_c = std::sqrt(1 - eta * eta);
    auto g = [&](double mu) { return double(2 * textbook(mu, eta, 0).f() * mu); };
    const double expect = ref::integrate(g, 0.0, mu_c, 1e-13) + ref::integrate(g, mu_c, 1.0, 1e-13);
    INFO("average " << avg << " +- " << err << ", quadrature " << expect);
    CHECK(std::fabs(avg - expect) <= err + 1e-10);
    // Energy balance across the interface (Stokes/reciprocity): 1 - avg_in = (1 - avg_out) / eta_out^2.
    const auto o = nlohmann::json::parse(testing::run_cli("fresnel --fresnel dielectric:eta=1.5 --theta 0 --format json").out);
    const double avg_out = o.at("hemispherical_average").at("value").get<double>();
    CHECK(1 - avg == Approx((1 - avg_out) / 2.25).epsilon(1e-12));
}

TEST_CASE("fresnel --compare --plot writes the comparison figure atomically", "[fresnel][cli]") {
    const std::string dir = "/tmp/brdfbake-fresnel-plot-" + std::to_string(::getpid());
    REQUIRE(std::system(("mkdir -p " + dir).c_str()) == 0);
    for (const char* name : {"compare.png", "compare.svg"}) {
        const std::string path = dir + "/" + name;
        const auto r = testing::run_cli("fresnel --compare --plot " + path);
        INFO(r.err);
        REQUIRE(r.status == 0);
        const std::string bytes = testing::slurp(path);
        REQUIRE(bytes.size() > 1000);
        if (std::string(name).find("png") != std::string::npos) {
            CHECK(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
            CHECK(testing::png_colours(path) > 16);  // libpng reads a figure with its curves
        } else {
            // Well-formed XML (Python's own parser), an <svg> root, and the figure's curves and
            // axes as paths (more than a frame's few).
            const auto xml = testing::run_shell(
                "/usr/bin/python3 -c \"import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
                "print(r.tag.split('}')[-1], sum(1 for e in r.iter() if e.tag.endswith('path')))\" " + path);
            INFO(xml.err);
            REQUIRE(xml.status == 0);
            std::istringstream words(xml.out);
            std::string root;
            int paths = 0;
            words >> root >> paths;
            CHECK(root == "svg");
            CHECK(paths > 20);
        }
        CHECK(r.out.find("metal:Al at 550 nm") != std::string::npos);
    }
    const auto single = testing::run_cli("fresnel --fresnel dielectric:eta=1.5 --plot " + dir + "/glass.png");
    CHECK(single.status == 0);
    const auto bad = testing::run_cli("fresnel --fresnel dielectric:eta=1.5 --plot " + dir + "/glass.gif");
    CHECK(bad.status == 2);
    const auto nodir = testing::run_cli("fresnel --fresnel dielectric:eta=1.5 --plot /nonexistent/dir/x.png");
    CHECK(nodir.status == 2);
    CHECK(testing::count_lines(nodir.err) == 1);
    // Only the three figures: no temporary files left behind.
    FILE* p = popen(("ls " + dir + " | wc -l").c_str(), "r");
    int files = -1;
    REQUIRE(p);
    CHECK(std::fscanf(p, "%d", &files) == 1);
    pclose(p);
    CHECK(files == 3);
    std::system(("rm -rf " + dir).c_str());
}

TEST_CASE("albedo of ggx with metal:Al at 550 nm matches an independent quadrature", "[fresnel][cli]") {
    const auto r = testing::run_cli(
        "albedo --model ggx:alpha=0.5 --fresnel metal:Al --wavelength 550 --mu 0.2,0.6,1 --format json");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    // n, k of Al at 550 nm interpolated by hand from the two rows of Rakic 1995.
    const ld t = (0.550L - 0.5166L) / (0.56357L - 0.5166L);
    const ld eta = 0.8734L + t * (1.0728L - 0.8734L), k = 6.2418L + t * (6.7839L - 6.2418L);
    for (const auto& e : j.at("results")) {
        const double mu = e.at("mu").get<double>();
        const double expect = ref::albedo_halfvector(
            [&](ref::Dir wo, ref::Dir wi) {
                const ref::Dir wh = ref::normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
                return ref::ggx_f(wo, wi, 0.5, 0.5, true) * textbook(ref::dot(wo, wh), eta, k).f();
            },
            mu, 0.0);
        const double got = e.at("albedo").get<double>(), err = e.at("error").get<double>();
        INFO("mu = " << mu << ": " << got << " +- " << err << ", quadrature " << expect);
        CHECK(std::fabs(got - expect) <= err);
        CHECK(err < 1e-3);
    }
}

TEST_CASE("fresnel and albedo reject bad Fresnel input with one clear message", "[fresnel][cli]") {
    struct Bad {
        const char* args;
        const char* says;
    };
    for (Bad b : {Bad{"fresnel --fresnel unknownthing", "unknown Fresnel term 'unknownthing'"},
                  Bad{"fresnel --fresnel dielectric:eta=-1", "out of range"},
                  Bad{"fresnel --fresnel conductor:eta=1,k=nan", "not a finite number"},
                  Bad{"fresnel --fresnel dielectric:eta=1.5,colour=red", "no key 'colour'"},
                  Bad{"fresnel --fresnel metal:Al", "needs --wavelength"},
                  Bad{"fresnel --fresnel metal:Al --wavelength 100000000", "outside the range"},
                  Bad{"fresnel --fresnel nk:/nonexistent.yml --wavelength 500", "cannot read n,k file"},
                  Bad{"fresnel --fresnel dielectric:eta=1.5 --theta 95", "out of range"},
                  Bad{"fresnel --fresnel dielectric:eta=1.5 --compare --plot /tmp/x.png", "needs a conductor"},
                  Bad{"fresnel --compare", "--plot"},
                  // Without --wavelength, albedo gives a metal's colour (test_spectral_albedo.cpp); the
                  // random walk takes one wavelength.
                  Bad{"albedo --model ggx:alpha=0.5,scattering=multiple --fresnel metal:Al", "give --wavelength"},
                  Bad{"albedo --model ggx:alpha=0.5 --fresnel metal:Al --wavelength 100000000", "outside the range"},
                  Bad{"albedo --model ggx:alpha=0.5 --fresnel dielectric:eta=-1", "out of range"}}) {
        const auto r = testing::run_cli(b.args);
        INFO(b.args << " -> " << r.err);
        CHECK(r.status == 2);
        CHECK(r.out.empty());
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.find(b.says) != std::string::npos);
    }
}

TEST_CASE("every Fresnel term of the registry is in the --fresnel help and in docs/fresnel.md", "[fresnel][cli]") {
    // __FILE__ is relative to the build folder, where the test binary is, when the build gave it so.
    std::filesystem::path here = __FILE__;
    if (here.is_relative()) here = std::filesystem::canonical("/proc/self/exe").parent_path() / here;
    const std::filesystem::path docs = here.parent_path().parent_path() / "docs" / "fresnel.md";
    std::ifstream in(docs);
    REQUIRE(in);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The docs' table of Fresnel specs: its rows, one per term.
    const size_t table = text.find("### Fresnel specs");
    REQUIRE(table != std::string::npos);
    const std::string rows = text.substr(table, text.find("\n\n", text.find("| spec |", table)) - table);
    REQUIRE(fresnel_terms().size() >= 10);
    for (const char* command : {"fresnel", "albedo", "lobe"}) {
        const auto help = testing::run_cli(std::string(command) + " --help");
        REQUIRE(help.status == 0);
        for (const FresnelTerm& t : fresnel_terms()) {
            INFO(command << " --help, " << t.form);
            CHECK(help.out.find(t.form) != std::string::npos);
        }
    }
    for (const FresnelTerm& t : fresnel_terms()) {
        INFO("docs/fresnel.md, " << t.form);
        // A term with keys is written as its form; a measured one as name:ARGUMENT rows.
        CHECK(rows.find("| `" + (t.measured ? t.name + ":" : t.form)) != std::string::npos);
    }
    // And the other way: every row of the docs' table names a term of the registry.
    size_t at = rows.find("\n| `");
    int documented = 0;
    while (at != std::string::npos) {
        const size_t start = at + 4, end = rows.find_first_of(":`", start);
        const std::string name = rows.substr(start, end - start);
        bool known = false;
        for (const FresnelTerm& t : fresnel_terms()) known = known || t.name == name;
        INFO("docs/fresnel.md row " << name);
        CHECK(known);
        ++documented;
        at = rows.find("\n| `", end);
    }
    CHECK(documented == int(fresnel_terms().size()));
}

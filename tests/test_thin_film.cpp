// The thin-film Fresnel term (include/brdfbake/brdf/thin_film.h, issue 36) against wave optics
// computed another way: the characteristic (transfer) matrix of Born & Wolf 1.6.2-1.6.3, eq. (55a),
// in std::complex<long double>, which never forms the Airy sum the header evaluates; and against
// closed forms: the quarter-wave and half-wave layers at normal incidence, thickness 0 and a film of
// index 1 as the bare substrate. The fresnel_curve kernel (float and double) through `fresnel`.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <complex>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "checks.h"
#include "image_readers.h"
#include "support.h"

using namespace brdfbake;

namespace {

using ld = long double;
using cld = std::complex<ld>;
const ld kPiL = 3.141592653589793238462643383279502884L;

/// A film (index n1, thickness d nm) on a substrate n2, light from index 1 at cos_i, wavelength lambda nm.
struct Stack {
    cld n1, n2;
    ld d, lambda;
};

/// n cos(theta) in a medium of index n for light arriving at sin_i from index 1: the root whose
/// imaginary part is >= 0 (the wave decays into an absorbing or evanescent medium, exp(-i w t)).
cld n_cos(cld n, ld sin_i) {
    cld w = std::sqrt(n * n - sin_i * sin_i);
    if (w.imag() < 0 || (w.imag() == 0 && w.real() < 0)) w = -w;
    return w;
}

/// Reflectance of one polarisation by the characteristic matrix [BW 1.6 eq. (35), (55a)]:
///   M = [[cos b, -(i/p1) sin b], [-i p1 sin b, cos b]],  b = (2 pi / lambda) n1 d cos_1,
///   r = ((m11 + m12 pl) p0 - (m21 + m22 pl)) / ((m11 + m12 pl) p0 + (m21 + m22 pl)),
/// with p = n cos (TE) or q = cos / n (TM) in each medium.
ld matrix_reflectance(const Stack& s, ld cos_i, bool tm) {
    const ld sin_i = std::sqrt(1 - cos_i * cos_i);
    const cld w0 = cos_i, w1 = n_cos(s.n1, sin_i), w2 = n_cos(s.n2, sin_i);
    // p = n cos = w; q = cos / n = w / n^2.
    const cld p0 = tm ? w0 : w0, p1 = tm ? w1 / (s.n1 * s.n1) : w1, pl = tm ? w2 / (s.n2 * s.n2) : w2;
    const cld b = 2 * kPiL / s.lambda * s.d * w1;
    const cld i(0, 1);
    const cld m11 = std::cos(b), m12 = -i / p1 * std::sin(b), m21 = -i * p1 * std::sin(b), m22 = std::cos(b);
    const cld a = (m11 + m12 * pl) * p0, c = m21 + m22 * pl;
    return std::norm((a - c) / (a + c));
}

bb_fresnel_sp header(const Stack& s, double cos_i) {
    return bb_fresnel_thin_film_sp(cos_i, double(s.n1.real()), double(s.n1.imag()), double(s.d), double(s.n2.real()),
                                   double(s.n2.imag()), double(s.lambda));
}

/// The conductor term of fresnel.h for the bare substrate (tested against Born & Wolf in test_fresnel.cpp).
bb_fresnel_sp bare(const Stack& s, double cos_i) {
    return bb_fresnel_conductor_sp(cos_i, double(s.n2.real()), double(s.n2.imag()));
}

const std::vector<Stack> kStacks = {
    {{1.33, 0}, {1.5, 0}, 300, 550},       // a soap-like film on glass
    {{1.38, 0}, {1.52, 0}, 99.6, 550},     // MgF2 anti-reflection coating (quarter wave)
    {{1.5, 0}, {0.958, 6.69}, 250, 550},   // a dielectric film on aluminium (Rakic 1995 at 550 nm)
    {{2.0, 0.3}, {0.2, 3.5}, 80, 450},     // an absorbing oxide on gold-like metal
    {{1.2, 0}, {1.8, 0}, 1000, 650},       // thick: many fringes over the angle
    {{0.8, 0}, {1.5, 0}, 120, 500},        // film index below 1: evanescent beyond 53 deg
    {{1.33, 0}, {1.5, 0}, 30000, 550},     // 30 micrometres
};

}  // namespace

TEST_CASE("thin film: the Airy sum equals the characteristic-matrix reflectance, s and p", "[fresnel][thin-film]") {
    for (const Stack& s : kStacks)
        for (double theta : {0.0, 10.0, 30.0, 45.0, 53.0, 60.0, 75.0, 85.0, 89.0}) {
            const double c = std::cos(theta * double(kPiL) / 180.0);
            const bb_fresnel_sp r = header(s, c);
            INFO("film " << double(s.n1.real()) << "+" << double(s.n1.imag()) << "i, " << double(s.d)
                         << " nm, substrate " << double(s.n2.real()) << "+" << double(s.n2.imag()) << "i, theta "
                         << theta);
            CHECK(std::fabs(r.rs - double(matrix_reflectance(s, c, false))) < 1e-11);
            CHECK(std::fabs(r.rp - double(matrix_reflectance(s, c, true))) < 1e-11);
            CHECK(r.rs >= 0.0);
            CHECK(r.rs <= 1.0);
            CHECK(r.rp >= 0.0);
            CHECK(r.rp <= 1.0);
        }
}

TEST_CASE("thin film: quarter- and half-wave layers at normal incidence in closed form", "[fresnel][thin-film]") {
    const double n1 = 1.38, n2 = 1.52, lambda = 550;
    // A quarter-wave layer: R = ((n0 n2 - n1^2) / (n0 n2 + n1^2))^2 [Heavens; Macleod 3.2].
    const double quarter = std::pow((n2 - n1 * n1) / (n2 + n1 * n1), 2);
    const Stack q{{n1, 0}, {n2, 0}, lambda / (4 * n1), lambda};
    CHECK(header(q, 1.0).rs == Approx(quarter).epsilon(1e-12));
    CHECK(header(q, 1.0).rp == Approx(quarter).epsilon(1e-12));
    // A half-wave layer is absent: the substrate's own R = ((n2 - 1)/(n2 + 1))^2.
    const Stack h{{n1, 0}, {n2, 0}, lambda / (2 * n1), lambda};
    CHECK(header(h, 1.0).rs == Approx(std::pow((n2 - 1) / (n2 + 1), 2)).epsilon(1e-12));
}

TEST_CASE("thin film: thickness 0 and a film of index 1 are the bare substrate", "[fresnel][thin-film]") {
    for (const Stack& base : kStacks)
        for (double c : {1.0, 0.8, 0.5, 0.2, 0.05, 0.0}) {
            Stack zero = base;
            zero.d = 0;
            Stack vacuum = base;
            vacuum.n1 = 1;
            for (const Stack& s : {zero, vacuum}) {
                CHECK(header(s, c).rs == Approx(bare(s, c).rs).margin(1e-12));
                CHECK(header(s, c).rp == Approx(bare(s, c).rp).margin(1e-12));
            }
        }
}

TEST_CASE("thin film: the kernel in float and double through `fresnel`", "[fresnel][thin-film][cli]") {
    const Stack s = kStacks[2];
    for (const char* precision : {"float", "double"}) {
        const auto r = testing::run_cli(
            "fresnel --fresnel thin-film:eta=1.5,thickness=250,base_eta=0.958,base_k=6.69 --wavelength 550 "
            "--theta 0,20,40,60,80,89 --format json --precision " + std::string(precision));
        INFO(r.err);
        REQUIRE(r.status == 0);
        const auto j = nlohmann::json::parse(r.out);
        CHECK(j.at("kind") == "thin-film");
        const double tol = std::string(precision) == "float" ? 2e-6 : 1e-12;
        for (const auto& e : j.at("results")) {
            const double c = e.at("cos_theta").get<double>();
            const double rs = double(matrix_reflectance(s, c, false)), rp = double(matrix_reflectance(s, c, true));
            CHECK(std::fabs(e.at("Rs").get<double>() - rs) < tol);
            CHECK(std::fabs(e.at("Rp").get<double>() - rp) < tol);
            CHECK(std::fabs(e.at("F").get<double>() - (rs + rp) / 2) < tol);
        }
    }
}

TEST_CASE("thin film: a spec without a wavelength, thickness or a valid key is refused with one line", "[fresnel][thin-film][cli]") {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"thin-film:eta=1.33,thickness=300,base_eta=1.5", "needs --wavelength"},
        {"thin-film:eta=1.33,base_eta=1.5 --wavelength 550", "thickness"},
        {"thin-film:eta=1.33,thickness=-1,base_eta=1.5 --wavelength 550", "thickness"},
        {"thin-film:eta=1.33,thicknes=300,base_eta=1.5 --wavelength 550", "did you mean 'thickness'"},
        {"thin-film:eta=1.33,thickness=300 --wavelength 550", "base_eta"},
    };
    for (const auto& [spec, mention] : cases) {
        const auto r = testing::run_cli("fresnel --fresnel " + spec);
        testing::check_usage_error(r);
        CHECK(r.err.find(mention) != std::string::npos);
    }
}

TEST_CASE("thin film: base=metal:Au is gold's n, k at each wavelength under the film", "[fresnel][thin-film]") {
    // Gold's tabulated n, k (data/nk, Johnson & Christy) are the input; the film on it is held to
    // the characteristic-matrix method, and thickness 0 to the bare conductor.
    for (double nm : {450.0, 550.0, 650.0}) {
        const FresnelConfig au = resolve_fresnel("metal:Au", nm);
        const cld n2(au.params[BB_FRESNEL_ETA], au.params[BB_FRESNEL_K]);
        for (double d : {0.0, 120.0, 400.0}) {
            const FresnelConfig f =
                resolve_fresnel("thin-film:eta=1.38,thickness=" + std::to_string(d) + ",base=metal:Au", nm);
            INFO(f.canonical);
            CHECK(f.canonical.find("base=metal:Au") != std::string::npos);
            const Stack s{{1.38, 0}, n2, ld(d), ld(nm)};
            const bb_params p = [&] {
                bb_params b;
                for (int k = 0; k < BB_MAX_PARAMS; ++k) b.v[k] = f.params[size_t(k)];
                return b;
            }();
            for (double c : {1.0, 0.7, 0.3, 0.05}) {
                CHECK(bb_fresnel_eval_rs(f.kind, p, c) == Approx(double(matrix_reflectance(s, c, false))).margin(1e-11));
                CHECK(bb_fresnel_eval_rp(f.kind, p, c) == Approx(double(matrix_reflectance(s, c, true))).margin(1e-11));
                if (d == 0.0) CHECK(bb_fresnel_eval(f.kind, p, c) == Approx(bare(s, c).rs * 0.5 + bare(s, c).rp * 0.5).margin(1e-12));
            }
        }
    }
    // The substrate is named once: base with base_eta, or an unmeasured base, is refused.
    for (const char* spec : {"thin-film:eta=1.38,thickness=100,base=metal:Au,base_eta=1.5",
                             "thin-film:eta=1.38,thickness=100,base=dielectric:eta=1.5", "thin-film:eta=1.38,thickness=100,base=metal:Xx"}) {
        INFO(spec);
        CHECK_THROWS_AS(resolve_fresnel(spec, 550.0), Error);
    }
}

TEST_CASE("thin film: a conductor table accepts it", "[fresnel][thin-film][lut]") {
    // Its F depends on the wavelength as a measured metal's does: without --wavelength the
    // conductor table holds its colour R, G, B (test_fresnel_tables.cpp).
    const FresnelConfig g = resolve_fresnel("thin-film:eta=1.33,thickness=300,base_eta=1.5", 550.0);
    CHECK(g.kind == BB_FRESNEL_THIN_FILM);
    CHECK(g.params[BB_THIN_FILM_WAVELENGTH] == 550.0);
    CHECK(g.canonical.find("at 550 nm") != std::string::npos);
    const auto r = testing::run_cli(
        "lut conductor --model ggx --fresnel thin-film:eta=1.33,thickness=300,base_eta=1.5 --size 4x4 "
        "--samples 4096 -o /tmp/brdfbake-thin-film-" + std::to_string(::getpid()) + ".csv");
    INFO(r.err);
    CHECK(r.status == 0);
    std::remove(("/tmp/brdfbake-thin-film-" + std::to_string(::getpid()) + ".csv").c_str());
}

/// Pixels within `tol` (8-bit) of the colour (r, g, b).
size_t pixels_of(const testing::Png& p, int r, int g, int b, int tol) {
    size_t n = 0;
    for (size_t i = 0; i + 2 < p.samples.size(); i += size_t(p.channels))
        n += std::abs(int(p.samples[i]) - r) <= tol && std::abs(int(p.samples[i + 1]) - g) <= tol &&
             std::abs(int(p.samples[i + 2]) - b) <= tol;
    return n;
}

TEST_CASE("thin film: --rgb --plot draws the R, G and B curves in their colours", "[fresnel][thin-film][cli][pictures]") {
    const std::string png = "/tmp/brdfbake-thin-film-rgb-" + std::to_string(::getpid()) + ".png";
    const auto r = testing::run_cli("fresnel --fresnel thin-film:eta=1.33,thickness=400,base_eta=1.5 --rgb --theta 0 --plot " + png);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const testing::Png p = testing::read_png8(png);
    CHECK(p.width > 400);
    // Each curve in its pen's pure colour (MathGL's r, g, b): many pixels of each.
    CHECK(pixels_of(p, 255, 0, 0, 60) > 200);
    CHECK(pixels_of(p, 0, 255, 0, 60) > 200);
    CHECK(pixels_of(p, 0, 0, 255, 60) > 200);
    std::remove(png.c_str());
}

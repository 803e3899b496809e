// The volumetric sheen layer of Zeltner, Burley and Chiang 2022 by random walks
// (brdf/sheen_volume.h, integrate/sheen_volume.h), checked from outside: the SGGX fiber normals
// and their visible-normal sampler against quadrature of the textbook SGGX D of Heitz et al. 2015
// (written here from the paper's matrix form, not the header's), energy (R + T + cut-off = 1 with
// albedo 1), Beer-Lambert transmission without scattering, the first scattering order against
// Boost quadrature of the single-scattering integral in the slab, and the isotropic limit
// (sigma = 1: SGGX with S = I scatters isotropically) against an independent host simulation of
// an isotropically scattering slab.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "brdfbake/brdf/sheen_volume.h"
#include "brdfbake/lut.h"
#include "integrate/sheen_volume.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

// SGGX [HDCD15 eq. 8, 9] for S = diag(1, 1, s^2), from the matrix form:
// D(m) = 1 / (pi sqrt(det S) (m^T S^-1 m)^2), sigma(w) = sqrt(w^T S w).
long double sggx_d(ref::Dir m, long double s) {
    const long double q = m.x * m.x + m.y * m.y + m.z * m.z / (s * s);  // m^T S^-1 m
    return 1.0L / (M_PI * s * q * q);                                   // sqrt(det S) = s
}
long double sggx_sigma(ref::Dir w, long double s) { return std::sqrt(w.x * w.x + w.y * w.y + s * s * w.z * w.z); }

// The first order by quadrature: over the upper hemisphere, the specular microflake phase
// function D(h)/(4 sigma(wo)) times the slab's depth integral k_o (1 - exp(-(k_o + k)))/(k_o + k).
double first_order(double mu, double alpha) {
    const long double s = alpha * alpha;
    const ref::Dir wo = ref::dir_mu(mu, 0);
    const long double ko = sggx_sigma(wo, s) / mu;
    const auto f = [&](double th, double ph) {
        const ref::Dir w = ref::dir(th, ph);
        ref::Dir h{wo.x + w.x, wo.y + w.y, wo.z + w.z};
        const long double n = std::sqrt(ref::dot(h, h));
        h = {h.x / n, h.y / n, h.z / n};
        const long double p = sggx_d(h, s) / (4 * sggx_sigma(wo, s));
        const long double k = sggx_sigma(w, s) / w.z;
        return double(p * ko * -std::expm1(-(ko + k)) / (ko + k) * std::sin(th));
    };
    return 2 * ref::integrate2(f, 1e-9, M_PI / 2, 0, M_PI, 1e-8);
}

/// Reflectance of an isotropically scattering slab of optical thickness 1, albedo 1, lit at mu:
/// photons traced on the host with uniform directions on the sphere (std::mt19937_64), no SGGX;
/// the value and 3 standard errors.
std::pair<double, double> isotropic_slab(double mu, int n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int top = 0;
    for (int i = 0; i < n; ++i) {
        double t = 0, wz = -mu;
        for (;;) {
            t -= -std::log1p(-u(rng)) * wz;
            if (t < 0 || t > 1) break;
            wz = 2 * u(rng) - 1;
        }
        top += t < 0;
    }
    const double p = double(top) / n;
    return {p, 3 * std::sqrt(p * (1 - p) / n)};
}

SheenVolumeRequest request(const std::vector<std::pair<double, double>>& mu_alpha, std::uint64_t walks) {
    SheenVolumeRequest req;
    for (auto [mu, a] : mu_alpha) req.cells.push_back({mu, a, BB_SHEEN_VOLUME_DEFAULT_BOUNCES});
    req.walks = walks;
    return req;
}

}  // namespace

TEST_CASE("sheen volume: the fiber SGGX's projected area and visible normals against quadrature of D",
          "[sheen-volume]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (double alpha : {0.3, 0.7, 1.0})
        for (double vz : {0.95, 0.4, -0.6}) {
            const double s = alpha * alpha;
            const ref::Dir v{std::sqrt(1 - vz * vz), 0, vz};
            // integral of <v, m>+ D(m) over the sphere = sigma(v) [HDCD15 eq. 3]; phi in [0, pi] twice
            const auto moment = [&](int k) {
                return 2 * ref::integrate2(
                               [&](double th, double ph) {
                                   const ref::Dir m = ref::dir(th, ph);
                                   const long double c = std::max<long double>(0, ref::dot(v, m));
                                   return double(std::pow(c, k) * sggx_d(m, s) * std::sin(th));
                               },
                               0, M_PI, 0, M_PI, 1e-8);
            };
            const double area = moment(1), mean_c = moment(2) / area;
            INFO("alpha " << alpha << " v.z " << vz);
            CHECK(bb_sggx_fiber_area(bb_v3(v.x, v.y, v.z), s) == Approx(area).epsilon(1e-6));
            const int n = 1 << 16;
            double sum_c = 0, sum_c2 = 0;
            for (int i = 0; i < n; ++i) {
                const bb_vec3 m = bb_sggx_fiber_sample_vndf(bb_v3(v.x, v.y, v.z), s, u(rng), u(rng));
                const double c = m.x * v.x + m.y * v.y + m.z * v.z;
                REQUIRE(c >= -1e-6);
                sum_c += c;
                sum_c2 += c * c;
            }
            const double mean = sum_c / n, se = std::sqrt((sum_c2 / n - mean * mean) / n);
            CHECK(std::fabs(mean - mean_c) <= 4 * se);
        }
}

TEST_CASE("sheen volume: energy, Beer-Lambert transmission and the first order against quadrature",
          "[sheen-volume]") {
    std::vector<std::pair<double, double>> cells;
    for (double a : {0.5, 0.8, 1.0})
        for (double mu : {0.3, 0.7, 1.0}) cells.push_back({mu, a});
    const SheenVolumeResult r = sheen_volume_walks(testing::engine(), request(cells, 1 << 20));
    for (size_t c = 0; c < cells.size(); ++c) {
        const auto [mu, a] = cells[c];
        const SheenVolumeValue& v = r.values[c];
        const double s = a * a, sig = std::sqrt((1 - mu * mu) + s * s * mu * mu);
        const double t0 = std::exp(-sig / mu), r1 = first_order(mu, a);
        INFO("mu " << mu << " alpha " << a << ": R " << v.reflectance.value << " +- " << v.reflectance.error << ", T "
                   << v.transmittance.value << ", cutoff " << v.cutoff.value << ", T0 " << v.direct.value
                   << " (Beer-Lambert " << t0 << "), R1 " << v.single.value << " +- " << v.single.error
                   << " (quadrature " << r1 << ")");
        CHECK(std::fabs(v.reflectance.value + v.transmittance.value + v.cutoff.value - 1.0) <=
              v.reflectance.error + v.transmittance.error + 1e-6);
        CHECK(v.cutoff.value == 0.0);
        CHECK(std::fabs(v.direct.value - t0) <= v.direct.error + 1e-6);
        CHECK(std::fabs(v.single.value - r1) <= v.single.error + 1e-6);
        CHECK(v.reflectance.value - v.reflectance.error > v.single.value);  // higher orders add
    }
}

TEST_CASE("sheen volume: sigma = 1 is the isotropically scattering slab (independent simulation)",
          "[sheen-volume]") {
    // Unit optical thickness, albedo 1, isotropic phase function (isotropic_slab).
    const std::vector<double> mus = {0.2, 0.6, 1.0};
    std::vector<std::pair<double, double>> cells;
    for (double mu : mus) cells.push_back({mu, 1.0});
    const SheenVolumeResult r = sheen_volume_walks(testing::engine(), request(cells, 1 << 20));
    for (size_t c = 0; c < mus.size(); ++c) {
        const auto [p, err] = isotropic_slab(mus[c], 1 << 20, 11 + c);
        const SheenVolumeValue& v = r.values[c];
        INFO("mu " << mus[c] << ": walk R " << v.reflectance.value << " +- " << v.reflectance.error
                   << ", isotropic slab " << p << " +- " << err);
        CHECK(std::fabs(v.reflectance.value - p) <= v.reflectance.error + err);
    }
}

TEST_CASE("lut sheen-ltc: R at roughness 1 is the isotropic slab's, the LTC's lobe is a density, and refusals",
          "[sheen-volume]") {
    // Edge texels: roughness 0 (floored at 0.01) and 1 (sigma = 1, the isotropic slab) at mu 0.5 and 1.
    LutRequest r;
    r.kind = "sheen-ltc";
    r.model = "sheen";
    r.alpha_map = "roughness";
    r.texels = Texels::Edge;
    r.mu_lo = 0.5;
    r.width = 2;
    r.height = 2;
    r.samples = 1 << 18;
    const Table t = compute_lut(testing::engine(), r);
    REQUIRE(t.channels == std::vector<std::string>{"a", "b", "R", "distance", "distance_error"});
    for (int i = 0; i < 2; ++i) {
        const size_t c = 2 + i;  // row roughness 1
        const auto [p, err] = isotropic_slab(t.x.parameter[i], 1 << 20, 5 + i);
        INFO("mu " << t.x.parameter[i] << ": R " << t.values[2][c] << " +- " << t.error[c] << ", slab " << p);
        CHECK(std::fabs(t.values[2][c] - p) <= t.error[c] + err);
        CHECK(t.values[0][c] > 0.0);  // a > 0: M^-1 invertible
        CHECK(t.values[3][c] >= 0.0);
        CHECK(t.values[3][c] < 2.0);  // an L1 distance between two densities is below 2
    }
    for (const std::string& args : {std::string("lut sheen-ltc --model ggx --size 2x2 -o /tmp/sheen-refused.npy"),
                                    std::string("lut sheen-ltc --model sheen --tolerance 1e-3 --size 2x2 -o /tmp/sheen-refused.npy")}) {
        const auto e = testing::run_cli(args);
        INFO(args << "\n" << e.err);
        CHECK(e.status == 2);
        CHECK(testing::count_lines(e.err) == 1);
        CHECK(e.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(e.err.find("sheen-ltc") != std::string::npos);
    }
}

TEST_CASE("sheen volume: the histogram holds the higher orders, the first order's density is its quadrature's",
          "[sheen-volume]") {
    // One cell whose higher orders leave the top often (roughness 0.6, mu 0.5): the analog histogram
    // of the exits after two or more scatterings integrates to R - R1, the walks' own counts (the
    // next-flight estimator's expectation is that histogram's: tests/test_sheen_next_flight.cpp).
    const double mu = 0.5, alpha = 0.6;
    SheenVolumeRequest req = request({{mu, alpha}}, 1 << 18);
    req.lobe = true;
    req.next_flight = false;
    const SheenVolumeValue v = sheen_volume_walks(testing::engine(), req).values[0];
    REQUIRE(v.lobe.size() == size_t(SheenLobeBins::theta() * SheenLobeBins::phi()));
    double integral = 0;
    for (size_t b = 0; b < v.lobe.size(); ++b)
        integral += 2 * SheenLobeBins::solid_angle(int(b) / SheenLobeBins::phi()) * v.lobe[b];
    const double higher = v.reflectance.value - v.single.value;
    INFO("higher orders: walks " << higher << ", histogram " << integral);
    CHECK(higher > 0.05);  // the case has higher orders
    CHECK(integral == Approx(higher).epsilon(1e-5));

    // The first order's density in closed form against the quadrature integrand written here, and
    // its integral against the quadrature of the first order.
    const long double s = alpha * alpha;
    const ref::Dir wo = ref::dir_mu(mu, 0);
    for (double th : {0.1, 0.7, 1.3, 1.55})
        for (double ph : {0.0, 1.0, 2.5}) {
            const ref::Dir w = ref::dir(th, ph);
            ref::Dir h{wo.x + w.x, wo.y + w.y, wo.z + w.z};
            const long double n = std::sqrt(ref::dot(h, h));
            h = {h.x / n, h.y / n, h.z / n};
            const long double ko = sggx_sigma(wo, s) / mu, k = sggx_sigma(w, s) / w.z;
            const double want = double(sggx_d(h, s) / (4 * sggx_sigma(wo, s)) * ko * -std::expm1(-(ko + k)) / (ko + k));
            CHECK(sheen_single_density(mu, alpha, double(w.x), double(w.y), double(w.z)) == Approx(want).epsilon(1e-9));
        }
    CHECK(std::fabs(v.single.value - first_order(mu, alpha)) <= v.single.error + 1e-6);
}

// Belcour and Barla 2017's spectral antialiasing (host/models/iridescence_bb17.h; issue 36, item
// 5). Checked from outside: the Fourier series of the Airy reflectance, summed far, is the
// closed-form Airy term of brdf/thin_film.h (Born & Wolf's sum, another formula); a film of index
// 1 has no interference, so BB17 gives the bare substrate's Fresnel (Born & Wolf 1.5.2) in every
// channel. The hidden [reference] case measures BB17 against brute-force spectral integration
// (docs/fresnel.md, benchmarks/results/iridescence-bb17-amd-epyc-2c.md).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "brdfbake/brdf/fresnel.h"
#include "models/iridescence_bb17.h"
#include "models/spectrum.h"

using namespace brdfbake;

namespace {

double airy(double c, double film, double d, double base_eta, double base_k, double nm) {
    const bb_fresnel_sp r = bb_fresnel_thin_film_sp(c, film, 0.0, d, base_eta, base_k, nm);
    return 0.5 * (r.rs + r.rp);
}

}  // namespace

TEST_CASE("BB17: the Fourier series of the Airy reflectance sums to the closed-form Airy term",
          "[fresnel][thin-film][quick]") {
    struct Case { double film, base_eta, base_k; };
    for (const Case k : {Case{1.33, 1.5, 0.0}, Case{1.8, 1.5, 0.0}, Case{1.3, 1.2, 0.0}, Case{1.5, 0.47, 2.4}})
        for (double c : {1.0, 0.8, 0.5, 0.2, 0.05})
            for (double d : {0.0, 120.0, 350.0, 900.0})
                for (double nm : {400.0, 550.0, 700.0}) {
                    INFO("film " << k.film << " base " << k.base_eta << "+" << k.base_k << "i cos " << c << " d " << d
                                 << " nm " << nm);
                    const auto f = airy_fourier(c, k.film, d, k.base_eta, k.base_k);
                    // (R12 R23)^(m/2) falls below 1e-12 well before 400 terms for these interfaces.
                    CHECK(airy_series(f, nm, 400) == Approx(airy(c, k.film, d, k.base_eta, k.base_k, nm)).margin(1e-9));
                }
}

TEST_CASE("BB17: a film of index 1 gives the bare substrate in every channel", "[fresnel][thin-film][quick]") {
    for (double c : {1.0, 0.7, 0.3})
        for (double d : {100.0, 400.0}) {
            const auto rgb = bb17_iridescence_srgb(c, 1.0, d, 1.5, 0.0);
            const double bare = bb_fresnel_dielectric(c, 1.5);
            for (double v : rgb) CHECK(v == Approx(bare).margin(1e-12));
        }
}

TEST_CASE("BB17 against brute-force spectral integration over angle and thickness 100-1000 nm",
          "[.][reference][thin-film]") {
    // Measured on amd-epyc-2c (2 shared cores, load ~18), 2026-12-03; recorded in
    // benchmarks/results/iridescence-bb17-amd-epyc-2c.md and docs/fresnel.md.
    struct Case { double film, base; };
    const SpectralWeights& d65 = srgb_weights(1);
    for (const Case k : {Case{1.3, 1.5}, Case{1.33, 1.5}, Case{1.8, 1.5}, Case{1.5, 1.2}}) {
        const auto start = std::chrono::steady_clock::now();
        double max_e = 0, sum_e = 0, max_d = 0, sum_d = 0, worst_theta = 0, worst_d = 0;
        int n = 0;
        for (int deg = 0; deg < 90; ++deg)
            for (int d = 100; d <= 1000; d += 10) {
                const double c = std::cos(deg * 3.14159265358979323846 / 180.0);
                const auto bb = bb17_iridescence_srgb(c, k.film, d, k.base, 0.0);
                const auto e = illuminant_e_srgb([&](double nm) { return airy(c, k.film, d, k.base, 0.0, nm); });
                std::array<double, 3> w{};
                for (size_t i = 0; i < d65.nm.size(); ++i) {
                    const double r = airy(c, k.film, d, k.base, 0.0, d65.nm[i]);
                    for (int ch = 0; ch < 3; ++ch) w[size_t(ch)] += d65.rgb[i][size_t(ch)] * r;
                }
                for (int ch = 0; ch < 3; ++ch) {
                    const double de = std::fabs(bb[size_t(ch)] - e[size_t(ch)]);
                    const double dd = std::fabs(bb[size_t(ch)] - w[size_t(ch)]);
                    if (de > max_e) {
                        max_e = de;
                        worst_theta = deg;
                        worst_d = d;
                    }
                    sum_e += de;
                    max_d = std::max(max_d, dd);
                    sum_d += dd;
                    ++n;
                }
            }
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("film %.2f on %.2f: BB17 vs brute force (illuminant E, same matrix): max %.4f (theta %g, d %g nm), "
                    "mean %.4f; vs brdfbake's colour (D65 weights): max %.4f, mean %.4f; %d values, %.2f s\n",
                    k.film, k.base, max_e, worst_theta, worst_d, sum_e / n, max_d, sum_d / n, n, s);
        CHECK(std::isfinite(max_e));
        CHECK(std::isfinite(max_d));
    }
}

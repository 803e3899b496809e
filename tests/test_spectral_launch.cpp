// fresnel_rgb_on_device launches the fresnel_curve kernel once for the whole spectrum (401
// wavelengths x the cosines); before, it launched once per wavelength. Checked: the one launch
// gives the colour of the per-wavelength launches summed with the weights (to rounding), and, in
// a hidden benchmark, how much faster it is (figures in benchmarks/results/fresnel_rgb_launch.txt).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "brdfbake/fresnel_curve.h"
#include "brdfbake/spec.h"
#include "models/spectrum.h"
#include "support.h"

using namespace brdfbake;

namespace {

/// The colour by one fresnel_on_device launch per wavelength (what fresnel_rgb_on_device did).
std::vector<std::array<double, 3>> per_wavelength(const std::string& spec, const std::vector<double>& cosines) {
    const SpectralWeights& w = srgb_weights(1);
    const auto at = fresnel_over_wavelengths(spec);
    std::vector<std::array<double, 3>> rgb(cosines.size(), {0.0, 0.0, 0.0});
    for (size_t k = 0; k < w.nm.size(); ++k) {
        const FresnelCurves f = fresnel_on_device(testing::engine(), at(w.nm[k]), Precision::Double, cosines);
        for (size_t j = 0; j < cosines.size(); ++j)
            for (int ch = 0; ch < 3; ++ch) rgb[j][ch] += w.rgb[k][ch] * f.f[j];
    }
    return rgb;
}

std::vector<double> cosines_of(int n) {
    std::vector<double> c;
    for (int i = 0; i < n; ++i) c.push_back(double(i) / (n - 1));
    return c;
}

}  // namespace

TEST_CASE("fresnel rgb: one launch for the spectrum equals a launch per wavelength", "[fresnel][colour]") {
    const std::vector<double> cosines = cosines_of(33);
    for (const std::string spec : {"metal:Cu", "thin-film:eta=1.3,thickness=500,base=metal:Au"}) {
        INFO(spec);
        const FresnelColour one = fresnel_rgb_on_device(testing::engine(), spec, Precision::Double, cosines);
        CHECK(one.launches == 1);
        CHECK(one.wavelengths == 401);
        const auto ref = per_wavelength(spec, cosines);
        for (size_t j = 0; j < cosines.size(); ++j)
            for (int ch = 0; ch < 3; ++ch) CHECK(std::fabs(one.rgb[j][ch] - ref[j][ch]) < 1e-12);
    }
}

TEST_CASE("fresnel rgb: one launch against a launch per wavelength, timed", "[.][benchmark]") {
    for (int n : {91, 2049}) {
        const std::vector<double> cosines = cosines_of(n);
        for (const std::string spec : {"metal:Au", "thin-film:eta=1.3,thickness=400,base=metal:Au"}) {
            fresnel_rgb_on_device(testing::engine(), spec, Precision::Double, cosines);  // builds the program
            auto cpu = [] { return double(std::clock()) / CLOCKS_PER_SEC; };
            const int reps = 5;
            double c0 = cpu();
            auto t0 = std::chrono::steady_clock::now();
            for (int r = 0; r < reps; ++r) fresnel_rgb_on_device(testing::engine(), spec, Precision::Double, cosines);
            const double one_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / reps;
            const double one_cpu = (cpu() - c0) / reps;
            c0 = cpu();
            t0 = std::chrono::steady_clock::now();
            for (int r = 0; r < reps; ++r) per_wavelength(spec, cosines);
            const double many_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / reps;
            const double many_cpu = (cpu() - c0) / reps;
            std::printf("%-48s %5d cosines: one launch %.4f s wall %.4f s CPU; 401 launches %.4f s wall %.4f s CPU; "
                        "x%.1f wall x%.1f CPU\n",
                        spec.c_str(), n, one_wall, one_cpu, many_wall, many_cpu, many_wall / one_wall, many_cpu / one_cpu);
        }
    }
}

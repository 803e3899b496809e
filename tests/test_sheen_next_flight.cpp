// The next-flight estimator of the sheen layer's lobe (brdf/sheen_volume.h bb_sheen_next_flight,
// kernels/sheen_volume.cl) against the analog counts of the walks' actual exits. Both estimate the
// same thing, the distribution of the exits through the top after two or more scatterings: after
// the n-th scattering the next-flight tally is the probability exp(-sigma(w) t / w.z) that the next
// free flight leaves the top (Beer-Lambert), the expectation of the analog count given the walk so
// far. So with independent walks (another seed) the two histograms agree bin by bin within their
// errors, and the differences in units of their combined standard error have a mean square near 1:
// an estimator with a bias (the first order tallied too, the wrong depth or cosine in the
// transmittance, the paper's stopped walks weighed by their transmittance) fails the first, an
// error estimate that is too large or too small fails the second (the replicas' errors are honest).
// Checked for walks to the end and under the paper's rule (bounces = -16, a stopped walk going up
// counts as reflected: its tally is 1), and the next-flight errors are smaller where the analog
// counts are few (the reason for the estimator).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "brdfbake/brdf/sheen_volume.h"
#include "integrate/sheen_volume.h"
#include "support.h"

using namespace brdfbake;

namespace {

SheenVolumeResult walk(const std::vector<SheenVolumeCell>& cells, std::uint64_t walks, bool next_flight,
                       std::uint64_t seed) {
    SheenVolumeRequest req;
    req.cells = cells;
    req.walks = walks;
    req.lobe = true;
    req.next_flight = next_flight;
    req.seed = seed;
    return sheen_volume_walks(testing::engine(), req);
}

/// The probability of a bin (both sides of phi = 0) from its mean density.
double bin_mass(const std::vector<double>& lobe, size_t b) {
    return 2.0 * SheenLobeBins::solid_angle(int(b) / SheenLobeBins::phi()) * lobe[b];
}

}  // namespace

TEST_CASE("sheen volume: the next-flight lobe equals the analog exits' within honest errors", "[sheen-volume]") {
    // (mu, roughness, bounces): a rough layer, a smoother one at a grazing view, the paper's rule.
    const std::vector<SheenVolumeCell> cells = {{0.5, 0.6, 1000}, {0.3, 0.3, 1000}, {0.2, 0.25, -16}};
    const std::uint64_t walks = 1u << 20;
    const SheenVolumeResult nf = walk(cells, walks, true, 11), an = walk(cells, walks, false, 12);
    for (size_t c = 0; c < cells.size(); ++c) {
        const SheenVolumeValue &x = nf.values[c], &y = an.values[c];
        double z2 = 0.0, zmax = 0.0, total_x = 0.0, total_y = 0.0, var_x = 0.0;
        int bins = 0;
        for (size_t b = 0; b < x.lobe.size(); ++b) {
            total_x += bin_mass(x.lobe, b);
            total_y += bin_mass(y.lobe, b);
            var_x += std::pow(bin_mass(x.lobe_error, b) / 3.0, 2);
            // bins with at least ~400 analog exits, where both are near normal
            if (bin_mass(y.lobe, b) * double(walks) < 400.0) continue;
            const double se = std::hypot(x.lobe_error[b], y.lobe_error[b]) / 3.0;
            REQUIRE(se > 0.0);
            const double z = (x.lobe[b] - y.lobe[b]) / se;
            z2 += z * z;
            zmax = std::max(zmax, std::fabs(z));
            ++bins;
        }
        const double higher = y.reflectance.value - y.single.value;
        const double total_se = std::hypot(std::sqrt(var_x), std::hypot(y.reflectance.error, y.single.error) / 3.0);
        INFO("mu " << cells[c].mu << " roughness " << cells[c].alpha << " bounces " << cells[c].bounces << ": " << bins
                   << " bins, mean z^2 " << z2 / std::max(bins, 1) << ", max |z| " << zmax << "; orders >= 2: next flight "
                   << total_x << ", analog " << total_y << " (R - R1 " << higher << "), se " << total_se);
        CHECK(bins >= 40);
        CHECK(higher > 0.01);
        CHECK(total_y == Approx(higher).epsilon(1e-5));  // the analog histogram holds exactly the exits
        CHECK(std::fabs(total_x - total_y) <= 4.0 * total_se);
        CHECK(zmax < 4.5);
        CHECK(z2 / bins > 0.6);
        CHECK(z2 / bins < 1.8);
    }
}

// The paper's precomputation rule for the sheen layer's walks (brdf/sheen_volume.h, bounces = -L;
// `lut sheen-ltc --estimator cycles` walks with L = 16): a walk is stopped right after its L-th
// scattering and counts as reflected when its direction points up. With L = 1 that is closed form:
// a walk collides with probability 1 - T0 (T0 = exp(-sigma(wo)/mu), Beer-Lambert) and is then
// stopped, reflected with the probability that the specular microflake phase function
// p(wo -> w) = D(h) / (4 sigma(wo)) sends it up, P_up = integral over w.z > 0 of p: checked here
// against Boost quadrature of the SGGX D written from its matrix form (Heitz et al. 2015 eq. 8),
// not the header's code. The stopped share is reported as the cut-off (1 - T0), never dropped.
#include <catch2/catch.hpp>

#include <cmath>

#include "brdfbake/brdf/sheen_volume.h"
#include "integrate/sheen_volume.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

// P_up: the phase function's mass over the upper hemisphere, for the view wo at mu, S = diag(1, 1, s^2).
double phase_up(double mu, double alpha) {
    const long double s = alpha * alpha;
    const ref::Dir wo = ref::dir_mu(mu, 0);
    const long double sig_o = std::sqrt(wo.x * wo.x + wo.y * wo.y + s * s * wo.z * wo.z);
    const auto f = [&](double th, double ph) {
        const ref::Dir w = ref::dir(th, ph);
        ref::Dir h{wo.x + w.x, wo.y + w.y, wo.z + w.z};
        const long double n = std::sqrt(ref::dot(h, h));
        h = {h.x / n, h.y / n, h.z / n};
        const long double q = h.x * h.x + h.y * h.y + h.z * h.z / (s * s);  // h^T S^-1 h
        return double(1.0L / (M_PI * s * q * q) / (4 * sig_o) * std::sin(th));
    };
    return 2 * ref::integrate2(f, 1e-9, M_PI / 2, 0, M_PI, 1e-9);
}

}  // namespace

TEST_CASE("sheen volume: the paper's rule (stop after L scatterings, count by direction) at L = 1 is closed form",
          "[sheen-volume]") {
    SheenVolumeRequest req;
    const std::vector<std::pair<double, double>> cells = {{0.2, 0.3}, {0.5, 0.5}, {0.9, 1.0}};
    for (auto [mu, a] : cells) req.cells.push_back({mu, a, -1});
    req.walks = 1 << 20;
    const SheenVolumeResult r = sheen_volume_walks(testing::engine(), req);
    for (size_t c = 0; c < cells.size(); ++c) {
        const auto [mu, a] = cells[c];
        const SheenVolumeValue& v = r.values[c];
        const double s = a * a, t0 = std::exp(-std::sqrt((1 - mu * mu) + s * s * mu * mu) / mu);
        const double up = phase_up(mu, a), expect = (1 - t0) * up;
        INFO("mu " << mu << " alpha " << a << ": R " << v.reflectance.value << " +- " << v.reflectance.error
                   << " (closed form " << expect << ", P_up " << up << "), cut-off " << v.cutoff.value << " (1 - T0 "
                   << 1 - t0 << ")");
        CHECK(up > 0.05);
        CHECK(up < 0.95);  // a rule that counted every stopped walk, or none, fails
        CHECK(std::fabs(v.reflectance.value - expect) <= v.reflectance.error + 1e-6);
        CHECK(std::fabs(v.cutoff.value - (1 - t0)) <= v.cutoff.error + 1e-6);
        CHECK(std::fabs(v.reflectance.value + v.transmittance.value - 1.0) <= 1e-6);
        CHECK(v.single.value == Approx(v.reflectance.value).margin(1e-12));  // every reflected walk scattered once
    }
}

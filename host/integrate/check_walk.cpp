// `brdfbake check` of a simulated model (scattering=multiple, integrate/random_walk.h): the white
// furnace by the walks' albedo (R + T for the dielectric), reciprocity by the walks' next-event
// estimates of f(a, b) and f(b, a) (each from walks of its own: a violation is a difference beyond
// the estimates' noise), and the values' scan over the same pairs.
#include <algorithm>
#include <cmath>

#include "brdfbake/check.h"
#include "brdfbake/progress.h"
#include "integrate/random_walk.h"
#include "integrate/sheen_volume.h"

namespace brdfbake {

namespace {

Vec3 unit_at(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

/// The reciprocity pairs: theta texel centres (at most kWalkThetas), theta_i <= theta_o, at most
/// kWalkPhis azimuth differences (and two outgoing azimuths for an anisotropic model), each pair
/// twice: (a, b) then (b, a).
constexpr int kWalkThetas = 6, kWalkPhis = 4;

void scan_walk_reciprocity(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                           const CheckOptions& o, CheckReport& r) {
    const int n_theta = std::min(o.resolution, kWalkThetas), n_phi = std::min(o.phi_resolution, kWalkPhis);
    WalkEvalRequest req;
    req.model = model.id;
    req.fresnel = fresnel;
    req.samples = std::max<std::uint64_t>(o.samples / 4, 256);
    req.precision = o.precision;
    std::vector<std::array<double, 3>> where;  // theta_i, theta_o, dphi of each pair
    for (int po = 0; po < (model.anisotropic ? 2 : 1); ++po)
        for (int i = 0; i < n_theta; ++i)
            for (int j = i; j < n_theta; ++j)
                for (int p = 0; p < n_phi; ++p) {
                    const double ti = (i + 0.5) / n_theta * M_PI / 2, to = (j + 0.5) / n_theta * M_PI / 2;
                    const double phi_o = po * M_PI / 3, dphi = (p + 0.5) / n_phi * M_PI;
                    const Vec3 a = unit_at(to, phi_o), b = unit_at(ti, phi_o + dphi);
                    req.pairs.push_back({a, b, model.params});
                    req.pairs.push_back({b, a, model.params});
                    where.push_back({ti, to, dphi});
                }
    r.pairs = where.size();
    r.reciprocity_noise = true;
    try {
        const WalkEvalResult w = walk_eval(engine, req);
        r.min_value = w.f[0].value;
        for (size_t k = 0; k < where.size(); ++k) {
            const AlbedoValue &ab = w.f[2 * k], &ba = w.f[2 * k + 1];
            r.min_value = std::min({r.min_value, ab.value, ba.value});
            const double d = std::fabs(ab.value - ba.value), noise = std::hypot(ab.error, ba.error) / 3.0;
            const double sigmas = noise > 0.0 ? d / noise : (d > 0.0 ? HUGE_VAL : 0.0);
            if (k == 0 || sigmas > r.reciprocity_sigmas) {
                r.reciprocity_sigmas = sigmas;
                r.max_rel = d / std::max({ab.value, ba.value, 1e-300});
                r.max_rel_theta_i = where[k][0];
                r.max_rel_theta_o = where[k][1];
                r.max_rel_dphi = where[k][2];
            }
            const double allowed = kReciprocitySigmas * noise + o.reciprocity_tolerance * std::max(ab.value, ba.value);
            r.reciprocity_violation = r.reciprocity_violation || d > allowed;
        }
    } catch (const NonFiniteError& e) {
        r.scan_nonfinite = r.nonfinite = e.count;
    }
}

}  // namespace

CheckReport run_check_walk(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                           const CheckOptions& o) {
    CheckReport r;
    r.options = o;
    r.model = model.canonical;
    r.fresnel = fresnel.canonical;
    r.reciprocity_tolerance = o.reciprocity_tolerance;
    ProgressStage stage("check of " + model.canonical, 2);
    stage.update(0, "reciprocity and values by walk estimates", 1);
    if (model.traits().layer_walk)
        scan_layer_reciprocity(engine, model, o, r);  // no pointwise f: band fluxes (integrate/sheen_volume.h)
    else
        scan_walk_reciprocity(engine, model, fresnel, o, r);

    const AlbedoRequest req = furnace_request(model, fresnel, o);
    r.furnace_directions = int(req.cells.size());
    stage.update(1, "white furnace by walks of " + std::to_string(req.cells.size()) + " directions", 1);
    try {
        const WalkResult w = walk_albedo(engine, req);
        r.furnace_samples = w.walks_per_cell;
        std::vector<AlbedoValue> total;  // R + T of the dielectric, E of the conductor
        for (const WalkAlbedo& v : w.values) total.push_back(v.total);
        record_furnace(r, total, req);
    } catch (const NonFiniteError& e) {
        r.nonfinite += e.count;
        r.nonfinite_where = "random walks at mu = " + std::to_string(req.cells[e.cell].mu);
    }
    r.value_violation = r.nonfinite > 0 || r.min_value < 0.0;
    return r;
}

}  // namespace brdfbake

// The average albedo of a rough dielectric interface, R + T averaged over mu, from outside (eta)
// and from inside (1/eta), over (alpha, eta): the Eavg of the multiple-scattering compensation of
// rough glass (Kulla and Conty, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH
// 2017), which Blender Cycles ships as ggx_glass_Eavg and ggx_glass_inv_Eavg
// (intern/cycles/app/cycles_precompute.cpp).
#include <boost/math/quadrature/gauss.hpp>

#include <cmath>
#include <limits>

#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/error.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

/// Gauss-Legendre nodes on [0, 1]: the 32-node rule (weights32) and the 16-node rule
/// (weights16) on one list, as the eavg kind integrates E(mu) mu.
struct MuRule {
    std::vector<double> nodes, weights32, weights16;
};

MuRule mu_rule() {
    using G32 = boost::math::quadrature::gauss<double, 32>;
    using G16 = boost::math::quadrature::gauss<double, 16>;
    MuRule q;
    auto add = [&](const auto& x, const auto& w, bool is32) {
        for (size_t i = 0; i < x.size(); ++i)
            for (int s : {-1, 1}) {
                if (x[i] == 0.0 && s == 1) continue;
                q.nodes.push_back(0.5 + 0.5 * s * x[i]);
                q.weights32.push_back(is32 ? 0.5 * w[i] : 0.0);
                q.weights16.push_back(is32 ? 0.0 : 0.5 * w[i]);
            }
    };
    add(G32::abscissa(), G32::weights(), true);
    add(G16::abscissa(), G16::weights(), false);
    return q;
}

// Eavg = 2 int_0^1 (R + T)(mu) mu dmu per (alpha, eta) and side, by the 32-node rule; its error is
// the sampling errors of R and T weighted as the rule weights them (added linearly: the cells
// share their point sets) plus |Q32 - Q16|.
Table compute_dielectric_eavg(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    Table t;
    t.kind = r.kind;
    bool clamped = false;
    t.quantity = "average albedo of a rough dielectric interface, Eavg = 2 integral_0^1 (R + T)(mu) mu dmu, for light "
                 "from outside (relative index eta) and from inside (Eavg_inside, relative index 1/eta)";
    t.x = alpha_axis(r, r.width, clamped);
    t.y = make_axis("-", "-", 0.0, 1.0, 1);
    t.y.parameter = {0.5};
    t.z = eta_axis(r, r.depth);  // the request's eta mapping and texel placement, as the dielectric table's
    const MuRule q = mu_rule();
    DielectricRequest dr;
    dr.correlated = m.params[BB_GGX_SHADOWING] > 0.5;
    dr.cycles_transmission = m.params[BB_GGX_SHADOWING] == BB_DIELECTRIC_SHADOWING_CYCLES;
    dr.samples = r.samples;
    dr.precision = r.precision;
    // As in the dielectric table, a texel at alpha = 0 is the smooth interface, whose R + T is 1
    // at every mu (Fresnel's equations conserve energy; total internal reflection gives R = 1),
    // and one at eta = 1 is no interface at all (T = 1): Eavg = 1 on both sides, in closed form.
    // The others integrate their mu nodes on the device.
    const size_t texels = t.x.parameter.size() * t.z.parameter.size(), none = size_t(-1);
    std::vector<size_t> first_cell(2 * texels, none);
    for (int side = 0; side < 2; ++side)
        for (size_t e = 0; e < t.z.parameter.size(); ++e)
            for (size_t a = 0; a < t.x.parameter.size(); ++a) {
                const double eta = t.z.parameter[e], alpha = t.x.parameter[a];
                if (alpha == 0.0 || eta == 1.0) continue;
                first_cell[side * texels + e * t.x.parameter.size() + a] = dr.cells.size();
                for (double mu : q.nodes) dr.cells.push_back({mu, alpha, side == 0 ? eta : 1.0 / eta});
            }
    DielectricResult res;
    if (!dr.cells.empty())
        res = compute_dielectric(engine, dr);
    else
        res.method = "closed form (the smooth interface at alpha = 0, no interface at eta = 1)";
    t.channels = {"Eavg", "Eavg_inside"};
    t.values.assign(2, std::vector<double>(texels));
    t.error.assign(texels, 0.0);
    for (int side = 0; side < 2; ++side)
        for (size_t k = 0; k < texels; ++k) {
            const size_t first = first_cell[side * texels + k];
            if (first == none) {  // the smooth interface, or none
                t.values[side][k] = 1.0;
                t.error[k] = std::max(t.error[k], 4 * std::numeric_limits<double>::epsilon());
                continue;
            }
            double e32 = 0, e16 = 0, err = 0;
            for (size_t i = 0; i < q.nodes.size(); ++i) {
                const size_t c = first + i;
                const double rt = res.reflected[c].value + res.transmitted[c].value;
                e32 += 2 * q.weights32[i] * q.nodes[i] * rt;
                e16 += 2 * q.weights16[i] * q.nodes[i] * rt;
                err += 2 * q.weights32[i] * q.nodes[i] * (res.reflected[c].error + res.transmitted[c].error);
            }
            t.values[side][k] = e32;
            t.error[k] = std::max(t.error[k], err + std::fabs(e32 - e16));
        }
    describe(t, r, m, "dielectric (exact, unpolarised) at each texel's eta", res.method, res.samples_per_cell, clamped);
    t.attributes["mu_quadrature"] = "Gauss-Legendre, 32 nodes (16-node rule for the error estimate)";
    return t;
}

void validate_dielectric_eavg(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    if (m.id != BB_MODEL_GGX) throw Error("the dielectric-eavg table is computed for GGX microfacets; use --model ggx");
    if (f.kind != BB_FRESNEL_NONE)
        throw Error("the dielectric-eavg table uses the exact dielectric Fresnel term; drop --fresnel");
    if (r.method != Method::Importance || r.tolerance.tolerance > 0.0)
        throw Error("the dielectric-eavg table is computed by importance sampling with --samples; it takes no "
                    "--tolerance or --method");
    if (r.depth < 1 || r.depth > 1024 || double(r.width) * r.depth * 48 > kMaxTexels)
        throw Error("dielectric-eavg table depth must be 1 to 1024 and width x depth x 48 mu nodes at most 4M cells");
    if (!(r.eta_lo >= 1.0))
        throw Error("--eta-range must start at eta >= 1 for the dielectric-eavg table (the inside view is Eavg_inside)");
}

int two(const LutRequest&) { return 2; }

}  // namespace

TableKind dielectric_eavg_kind() {
    // The dielectric table integrated over mu: its programs, Fresnel, lobe requirement and cost
    // per sample; one dimension fewer, two channels, 48 mu nodes a texel per side.
    TableKind k = variant_of(dielectric_kind(), TableKindId::DielectricEavg, "dielectric-eavg",
                             "rough dielectric (GGX) average albedo Eavg = 2 integral of (R + T) mu dmu from outside "
                             "(eta) and Eavg_inside from inside (1/eta) over (alpha, eta) (1D in alpha, slices of eta)",
                             compute_dielectric_eavg);
    k.one_dimensional = true;
    k.cells_per_texel = 2 * 48;  // both sides, 32 + 16 Gauss-Legendre nodes in mu
    k.lobe_requirement = "a dielectric-eavg table needs an index of refraction (fresnel dielectric:eta=E or 'eta')";
    k.value_channels = two;
    k.validate = validate_dielectric_eavg;
    return k;
}

}  // namespace tables
}  // namespace brdfbake

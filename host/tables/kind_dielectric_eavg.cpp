// The average albedo of a rough dielectric interface, R + T averaged over mu, from outside (eta)
// and from inside (1/eta), over (alpha, eta): the Eavg of the multiple-scattering compensation of
// rough glass (Kulla and Conty, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH
// 2017), which Blender Cycles ships as ggx_glass_Eavg and ggx_glass_inv_Eavg
// (intern/cycles/app/cycles_precompute.cpp).
#include <cmath>
#include <limits>

#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/error.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"
#include "tables/mu_average.h"

namespace brdfbake {
namespace tables {
namespace {

// Eavg = 2 int_0^1 (R + T)(mu) mu dmu per (alpha, eta) and side, by the composite mu rule of
// average_over_mu; the error of (R + T)(mu) is the sum of R's and T's. With a tolerance each R and
// T gets a quarter of it (their sum, weighted by the rule, half), the mu rule the other half; a
// texel that still misses it is an error (exit status 1) naming it.
Table compute_dielectric_eavg(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    bool clamped = false;
    Table t = roughness_table(r,
                              "average albedo of a rough dielectric interface, Eavg = 2 integral_0^1 (R + T)(mu) mu "
                              "dmu, for light from outside (relative index eta) and from inside (Eavg_inside, "
                              "relative index 1/eta)",
                              clamped);
    t.z = eta_axis(r, r.depth);  // the request's eta mapping and texel placement, as the dielectric table's
    DielectricRequest dr = dielectric_request(r, m);
    const double tolerance = r.tolerance.tolerance;
    // As in the dielectric table, a texel at alpha = 0 is the smooth interface, whose R + T is 1
    // at every mu (Fresnel's equations conserve energy; total internal reflection gives R = 1),
    // and one at eta = 1 is no interface at all (T = 1): Eavg = 1 on both sides, in closed form.
    // The others integrate their mu nodes on the device: integral i is (side, texel) of `sides`.
    const size_t texels = t.x.parameter.size() * t.z.parameter.size();
    struct Integral {
        int side;
        size_t texel;
        double alpha, eta;
    };
    std::vector<Integral> integrals;
    for (int side = 0; side < 2; ++side)
        for (size_t e = 0; e < t.z.parameter.size(); ++e)
            for (size_t a = 0; a < t.x.parameter.size(); ++a) {
                const double eta = t.z.parameter[e], alpha = t.x.parameter[a];
                if (alpha == 0.0 || eta == 1.0) continue;
                integrals.push_back({side, e * t.x.parameter.size() + a, alpha, side == 0 ? eta : 1.0 / eta});
            }
    MuAverage avg;
    avg.method = "closed form (the smooth interface at alpha = 0, no interface at eta = 1)";
    avg.rule = "none (closed form)";
    if (!integrals.empty())
        avg = average_over_mu(integrals.size(), tolerance, [&](const std::vector<double>& mus) {
            DielectricRequest req = dr;
            for (const Integral& i : integrals)
                for (double mu : mus) req.cells.push_back({mu, i.alpha, i.eta});
            ToleranceRequest share = r.tolerance;
            share.tolerance = 0.25 * tolerance;
            const DielectricResult res = tolerance > 0.0 ? compute_dielectric_to_tolerance(engine, req, share)
                                                         : compute_dielectric(engine, req);
            MuSamples out;
            out.method = res.method;
            out.samples = res.samples_per_cell;
            for (size_t c = 0; c < req.cells.size(); ++c) {
                AlbedoValue v = res.reflected[c];
                v.value += res.transmitted[c].value;
                v.error += res.transmitted[c].error;
                out.values.push_back(v);
            }
            return out;
        });
    t.channels = {"Eavg", "Eavg_inside"};
    t.values.assign(2, std::vector<double>(texels, 1.0));
    t.error.assign(texels, 4 * std::numeric_limits<double>::epsilon());
    for (size_t i = 0; i < integrals.size(); ++i) {
        t.values[integrals[i].side][integrals[i].texel] = avg.value[i];
        t.error[integrals[i].texel] = std::max(t.error[integrals[i].texel], avg.error[i]);
    }
    if (tolerance > 0.0) require_tolerance_met(t, tolerance, avg.panels);
    describe(t, r, m, "dielectric (exact, unpolarised) at each texel's eta", avg.method, avg.samples, clamped);
    t.attributes["mu_quadrature"] = avg.rule;
    return t;
}

void validate_dielectric_eavg(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    validate_rough_dielectric(r, m, f);
    if (r.depth < 1 || r.depth > 1024 || double(r.width) * r.depth * 48 > kMaxTexels)
        throw Error("dielectric-eavg table depth must be 1 to 1024 and width x depth x 48 mu nodes at most 4M cells");
    if (!(r.eta_lo >= 1.0))
        throw Error("--eta-range must start at eta >= 1 for the dielectric-eavg table (the inside view is Eavg_inside)");
}

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
    k.value_channels = [](const LutRequest&) { return std::vector<std::string>{"Eavg", "Eavg_inside"}; };
    k.validate = validate_dielectric_eavg;
    return k;
}

}  // namespace tables
}  // namespace brdfbake

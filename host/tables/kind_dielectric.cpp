// The rough dielectric interface (GGX): energy reflected and transmitted from outside (eta) and
// from inside (1/eta), over (mu_o, alpha, eta).
#include <algorithm>
#include <limits>

#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/error.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {

DielectricRequest dielectric_request(const LutRequest& r, const ModelConfig& m) {
    DielectricRequest dr;
    dr.shadowing = Shadowing(int(m.params[BB_GGX_SHADOWING]));
    dr.transmission_shadowing = TransmissionShadowing(int(m.params[BB_GGX_TRANSMISSION_SHADOWING]));
    dr.method = r.method;
    dr.samples = r.samples;
    dr.precision = r.precision;
    return dr;
}

void validate_rough_dielectric(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    const std::string table = "the " + r.kind + " table";
    if (r.method != Method::Importance && r.method != Method::Quadrature)
        throw Error(table + " is computed by importance sampling or quadrature; use --method auto, importance or "
                    "quadrature");
    if (m.id != BB_MODEL_GGX) throw Error(table + " is computed for GGX microfacets; use --model ggx");
    if (m.params[BB_GGX_SHADOWING] == BB_SHADOWING_MASKING)
        throw Error(table + " has no masking-only form: its transmitted lobe needs shadowing; use "
                    "shadowing=correlated or separable");
    if (f.kind != BB_FRESNEL_NONE) throw Error(table + " uses the exact dielectric Fresnel term; drop --fresnel");
}

namespace {

Table compute_dielectric_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    Table t;
    t.kind = r.kind;
    bool clamped = false;
    t.x = mu_axis(r, r.width);
    t.y = alpha_axis(r, r.height, clamped);
    t.quantity = "rough dielectric interface: energy fractions reflected (R) and transmitted (T) for light "
                 "from outside (relative index eta), and R_inside, T_inside from inside (relative index 1/eta); "
                 "transmitted radiance is T times (eta_t/eta_i)^2";
    t.z = eta_axis(r, r.depth);
    DielectricRequest dr = dielectric_request(r, m);
    for (int side = 0; side < 2; ++side)
        for (double eta : t.z.parameter)
            for (double alpha : t.y.parameter)
                for (double mu : t.x.parameter) dr.cells.push_back({mu, alpha, side == 0 ? eta : 1.0 / eta});
    // Cells with a closed form stay off the device: alpha = 0 is the smooth interface, R = F(mu,
    // eta) and T = 1 - R (Fresnel's equations; total internal reflection gives R = 1); eta = 1 is
    // no interface at all, R = 0 and T = 1.
    std::vector<size_t> device_cells;
    DielectricRequest on_device = dr;
    on_device.cells.clear();
    for (size_t c = 0; c < dr.cells.size(); ++c)
        if (!(dr.cells[c].alpha == 0.0 || dr.cells[c].eta == 1.0)) {
            device_cells.push_back(c);
            on_device.cells.push_back(dr.cells[c]);
        }
    DielectricResult res;
    if (!on_device.cells.empty()) {
        const DielectricResult part = r.tolerance.tolerance > 0.0 ? compute_dielectric_to_tolerance(engine, on_device, r.tolerance)
                                                                  : compute_dielectric(engine, on_device);
        res = part;
        res.reflected.assign(dr.cells.size(), AlbedoValue{});
        res.transmitted.assign(dr.cells.size(), AlbedoValue{});
        for (size_t k = 0; k < device_cells.size(); ++k) {
            res.reflected[device_cells[k]] = part.reflected[k];
            res.transmitted[device_cells[k]] = part.transmitted[k];
        }
    } else {
        res.method = "closed form (smooth interface or eta = 1)";
        res.reflected.assign(dr.cells.size(), AlbedoValue{});
        res.transmitted.assign(dr.cells.size(), AlbedoValue{});
    }
    bool smooth = false;
    for (size_t c = 0; c < dr.cells.size(); ++c) {
        const DielectricCell& cell = dr.cells[c];
        if (!(cell.alpha == 0.0 || cell.eta == 1.0)) continue;
        const double f = cell.eta == 1.0 ? 0.0 : bb_fresnel_dielectric(cell.mu, cell.eta);
        smooth = smooth || cell.alpha == 0.0;
        res.reflected[c].value = f;
        res.transmitted[c].value = 1.0 - f;
        res.reflected[c].error = res.transmitted[c].error = 4 * std::numeric_limits<double>::epsilon();
    }
    const size_t n = dr.cells.size() / 2;
    t.channels = {"R", "T", "R_inside", "T_inside"};
    t.values.assign(4, std::vector<double>(n));
    t.error.assign(n, 0.0);
    for (size_t k = 0; k < n; ++k) {
        t.values[0][k] = res.reflected[k].value;
        t.values[1][k] = res.transmitted[k].value;
        t.values[2][k] = res.reflected[n + k].value;
        t.values[3][k] = res.transmitted[n + k].value;
        t.error[k] = std::max({res.reflected[k].error, res.transmitted[k].error, res.reflected[n + k].error,
                               res.transmitted[n + k].error});
    }
    // The dielectric table has never carried the alpha floor note: it is left out here too, so
    // that its files stay as they were.
    describe(t, r, m, "dielectric (exact, unpolarised) at each texel's eta", res.method, res.samples_per_cell,
             false);
    if (smooth) t.attributes["alpha_zero"] = "texels at alpha = 0 hold the smooth interface: R = F(mu, eta), T = 1 - R";
    bool no_interface = false;
    for (double eta : t.z.parameter) no_interface = no_interface || eta == 1.0;
    if (no_interface) t.attributes["eta_one"] = "texels at eta = 1 have no interface: R = 0, T = 1";
    return t;
}

void validate_dielectric(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    validate_rough_dielectric(r, m, f);
    if (r.depth < 1 || r.depth > 1024 || double(r.width) * r.height * r.depth > kMaxTexels)
        throw Error("dielectric table depth must be 1 to 1024 and the table at most 4M texels");
}

std::vector<std::string> four_names(const LutRequest&) { return {"R", "T", "R_inside", "T_inside"}; }
std::vector<std::string> dielectric_program(const LutRequest& r) { return {"dielectric|" + r.model}; }

}  // namespace

TableKind dielectric_kind() {
    TableKind k(TableKindId::Dielectric, "dielectric",
                "rough dielectric (GGX) reflected and transmitted energy R, T from outside (eta) and "
                "R_inside, T_inside from inside (1/eta) over (mu_o, alpha, eta) (3D, slices stacked along y)",
                dielectric_program, compute_dielectric_table);
    k.eta_axis = true;
    k.cells_per_texel = 2;  // both sides of the interface
    k.plan_fresnel = "exact dielectric at each eta";
    k.lobe_requirement = "a dielectric table needs an index of refraction (fresnel dielectric:eta=E or 'eta')";
    // A dielectric sample (microfacet normal, exact Fresnel, reflect or refract) costs about 10
    // albedo samples (idle-core seconds: 56.6 M samples in 0.27-0.30 s against GGX albedo's 2.1e9
    // samples/s on the same 2 cores; benchmarks/results/plan-estimates-2c-shared.md).
    k.sample_cost = 10.0;
    k.value_channels = four_names;
    k.validate = validate_dielectric;
    return k;
}

}  // namespace tables
}  // namespace brdfbake

// Blender Cycles' generalized-Schlick tables (intern/cycles/app/cycles_precompute.cpp,
// ggx_gen_schlick_s and ggx_gen_schlick_ior_s; read in bsdf_microfacet_estimate_albedo of
// intern/cycles/kernel/closure/bsdf_microfacet.h): the factor s(mu_o, roughness, z) with which
// the lobe's albedo under F = f0 + (f90 - f0) w(cos) is E mix(f0, f90, s), E its albedo at F = 1.
// Since F is linear in f0 and f90, s = E_w / E is exact, with E_w the albedo weighted by w:
//   gen-schlick:      w = (1 - cos)^exponent, exponent = 5 (1 - z) / z  (z = 1/2: Schlick's 5),
//   gen-schlick-ior:  w = clamp((F_dielectric(cos, eta) - F0) / (1 - F0), 0, 1), F0 = ((eta - 1)/(eta + 1))^2,
//                     eta = (1 + z^2) / (1 - z^2)  (z = sqrt((eta - 1)/(eta + 1))),
// z clamped to [1e-4, 0.99] as Cycles computes its texels.
// Cycles' own tables hold another quantity, which --estimator cycles writes: its Monte-Carlo
// estimator (precompute_ggx_gen_schlick_s) averages w(wo.wh) over the visible normals wh of wo,
// a reflection below the horizon counting 0, i.e. E_w of the lobe with G2 = G1(wo) (the
// masking-only Smith form, brdf/smith.h), not divided by E: at roughness 1, mu 1, z 0.99 it is
// 0.445 where E_w / E is 0.874.
//
// dfg-f82: the split sum of an F82-tint metal (Kutz et al. 2021; the OpenPBR Surface
// specification; Hoffman 2019), whose F = F0 + (1 - F0)(1 - cos)^5 - b cos (1 - cos)^6 needs a
// third channel beside Karis' A and B: C, the lobe weighted by cos (1 - cos)^6; specular =
// F0 A + B - b C. (Cycles reads its ggx_gen_schlick_s at exponent 5 for F82-tint and leaves the
// b term out of its albedo estimate: bsdf_microfacet.h marks it as a TODO.)
#include <algorithm>
#include <cmath>
#include <sstream>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "integrate/refine.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

/// The name of the kinds' own z axis (their registry entries state it).
const char* const kZAxisName = "cycles_z";

/// Whether a gen-schlick-ior texel sits at z = 0: eta = 1, no interface, so that F_dielectric = F0
/// = 0 and w = 0 at every angle: s = 0 in closed form (E_w = 0 for --estimator cycles too), what
/// Cycles' table holds there (it computes z = 1e-4, where eta rounds to 1 in float). Computing it
/// at eta = 1 + 2e-8 instead would give the 0/0 limit of the remapped Fresnel, not the texel.
bool no_interface(double z) { return z == 0.0; }

/// The z axis (the kind's own, named by its registry entry; --eta-map and --eta-range do not
/// apply): z over [0, 1] with the request's texel placement, the parameter clamped as Cycles
/// computes it.
Axis cycles_z_axis(const LutRequest& r, bool ior) {
    Axis a = make_axis(kZAxisName,
                       ior ? "eta = (1 + z^2) / (1 - z^2), z clamped to [1e-4, 0.99] (Cycles' ggx_gen_schlick_ior_s); "
                             "z = 0 is eta = 1, no interface: s = 0 in closed form"
                           : "exponent = 5 (1 - z) / z, z clamped to [1e-4, 0.99] (Cycles' ggx_gen_schlick_s)",
                       0.0, 1.0, r.depth, r.texels);
    a.parameter_name = ior ? "eta" : "exponent";
    for (double z : a.coordinate) {
        const double zc = std::clamp(z, kCyclesZLo, kCyclesZHi), z2 = zc * zc;
        if (ior && no_interface(z)) a.parameter.push_back(1.0);
        else a.parameter.push_back(ior ? (1.0 + z2) / (1.0 - z2) : 5.0 * (1.0 - zc) / zc);
    }
    return a;
}

/// The weight w's Fresnel term at a texel's exponent or eta: f0 = 0, f90 = 1.
FresnelConfig weight_fresnel(bool ior, double parameter, double eta_m1) {
    FresnelConfig f;
    f.kind = ior ? BB_FRESNEL_GEN_SCHLICK_IOR : BB_FRESNEL_GEN_SCHLICK;
    f.params[BB_GEN_SCHLICK_F0] = 0.0;
    f.params[BB_GEN_SCHLICK_F90] = 1.0;
    if (ior) {
        f.params[BB_GEN_SCHLICK_IOR_ETA] = parameter;
        f.params[BB_GEN_SCHLICK_IOR_ETA_M1] = eta_m1;
        f.canonical = "gen-schlick-ior:f0=0,f90=1,eta=" + format_number(parameter);
    } else {
        f.params[BB_GEN_SCHLICK_EXPONENT] = parameter;
        f.canonical = "gen-schlick:f0=0,f90=1,exponent=" + format_number(parameter);
    }
    return f;
}

/// The weighted albedo E_w of slice k of the z axis; a missed tolerance names the slice ("slice
/// cycles_z = 0.96875 (exponent 0.16)") beside the cell's mu and alpha.
AlbedoResult integrate_slice(Engine& engine, const LutRequest& r, const ModelConfig& m, bool ior, const Axis& z,
                             size_t k, double eta_m1, const std::vector<AlbedoCell>& cells, double share) {
    try {
        return integrate(engine, r, m, weight_fresnel(ior, z.parameter[k], eta_m1), cells, share);
    } catch (const ToleranceNotMet& e) {
        std::ostringstream where;
        where << "slice " << z.name << " = " << z.coordinate[k] << " (" << z.parameter_name << " " << z.parameter[k] << ")";
        throw e.restated(0.0, where.str());
    }
}

/// s = E_w / E per texel and its error (err_w + s err_E) / E. With a tolerance, E is first found
/// at half of it to learn its smallest value E_min; then both integrals go to E_min / 2 of it,
/// which keeps that error within (1 + s) / 2 of it.
/// --estimator cycles: Cycles' estimator E_w of the masking-only lobe (validate_gen_schlick
/// checks the model), each texel to the whole tolerance.
Table cycles_estimator_table(Engine& engine, const LutRequest& r, const ModelConfig& m, bool ior,
                             MuAlphaGrid& g, const std::vector<double>& eta_m1) {
    Table& t = g.table;
    const size_t plane = g.cells.size();
    t.channels = {"s"};
    t.values.assign(1, std::vector<double>(plane * t.z.parameter.size()));
    t.error.assign(plane * t.z.parameter.size(), 0.0);
    AlbedoResult w;
    for (size_t k = 0; k < t.z.parameter.size(); ++k) {
        if (ior && no_interface(t.z.coordinate[k])) continue;  // s = 0, error 0 (no_interface)
        w = integrate_slice(engine, r, m, ior, t.z, k, eta_m1[k], g.cells, 1.0);
        for (size_t c = 0; c < plane; ++c) {
            // E_w lies in [0, 1] (0 <= w <= 1, the masking-only lobe reflects at most 1)
            t.values[0][k * plane + c] = std::clamp(w.values[c].value, 0.0, 1.0);
            t.error[k * plane + c] = w.values[c].error;
        }
    }
    t.quantity = std::string("Blender Cycles' generalized-Schlick estimate s = E_w of the masking-only lobe (G2 = G1(wo)), "
                             "the mean of w over the visible normals of wo with a reflection below the horizon "
                             "counting 0, not divided by E; w = ") +
                 (ior ? "clamp((F_dielectric(cos, eta) - F0) / (1 - F0), 0, 1)" : "(1 - cos)^exponent");
    describe(t, r, m, ior ? "dielectric at each texel's eta, remapped to [0, 1] and clamped" : "(1 - cos)^exponent at each texel",
             w.method, w.samples_per_cell, g.clamped);
    t.attributes["estimator"] = "cycles (E_w of shadowing=masking, not divided by E)";
    return std::move(g.table);
}

Table gen_schlick_table(Engine& engine, const LutRequest& r, const ModelConfig& m, bool ior) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.z = cycles_z_axis(r, ior);
    if (ior && std::any_of(t.z.coordinate.begin(), t.z.coordinate.end(), no_interface))
        t.attributes["eta_one"] = "texels at z = 0 (eta = 1) have no interface: s = 0 in closed form";
    std::vector<double> eta_m1;  // eta - 1 = 2 z^2 / (1 - z^2), exact where eta is near 1
    for (double z : t.z.coordinate) {
        const double zc = std::clamp(z, kCyclesZLo, kCyclesZHi);
        eta_m1.push_back(2 * zc * zc / (1 - zc * zc));
    }
    if (r.estimator == "cycles") return cycles_estimator_table(engine, r, m, ior, g, eta_m1);
    const FresnelConfig none = resolve_fresnel("none");
    AlbedoResult e = integrate(engine, r, m, none, g.cells, 0.5);
    double e_min = 1.0;
    for (const auto& v : e.values) e_min = std::min(e_min, v.value);
    if (!(e_min > 0.0)) throw Error("the lobe reflects nothing at some texel (E = 0): s is undefined there");
    if (r.tolerance.tolerance > 0.0) e = integrate(engine, r, m, none, g.cells, e_min / 2);
    const size_t plane = g.cells.size();
    t.channels = {"s"};
    t.values.assign(1, std::vector<double>(plane * t.z.parameter.size()));
    t.error.assign(plane * t.z.parameter.size(), 0.0);
    for (size_t k = 0; k < t.z.parameter.size(); ++k) {
        if (ior && no_interface(t.z.coordinate[k])) continue;  // s = 0, error 0 (no_interface)
        const AlbedoResult w = integrate_slice(engine, r, m, ior, t.z, k, eta_m1[k], g.cells, e_min / 2);
        for (size_t c = 0; c < plane; ++c) {
            const double ev = e.values[c].value, ee = e.values[c].error;
            if (!(ev > 0.0)) throw Error("the lobe reflects nothing at some texel (E = 0): s is undefined there");
            const double ew = w.values[c].value, ew_err = w.values[c].error;
            const double s = ew / ev;
            // s lies in [0, 1] (0 <= w <= 1); clamping a value off by rounding only moves it closer.
            t.values[0][k * plane + c] = std::clamp(s, 0.0, 1.0);
            t.error[k * plane + c] = (ew_err + std::fabs(s) * ee) / ev;
        }
    }
    t.quantity = ior ? "generalized-Schlick factor s = E_w / E with w = clamp((F_dielectric(cos, eta) - F0) / (1 - F0), 0, "
                       "1): the lobe's albedo under Cycles' dielectric-remapped F from f0 to f90 is E mix(f0, f90, s)"
                     : "generalized-Schlick factor s = E_w / E with w = (1 - cos)^exponent: the lobe's albedo under "
                       "F = f0 + (f90 - f0)(1 - cos)^exponent is E mix(f0, f90, s)";
    describe(t, r, m, ior ? "dielectric at each texel's eta, remapped to [0, 1] and clamped" : "(1 - cos)^exponent at each texel",
             e.method, e.samples_per_cell, g.clamped);
    t.attributes["estimator"] = "ratio (E_w / E of the model's own G2)";
    return std::move(g.table);
}

Table compute_gen_schlick(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    return gen_schlick_table(engine, r, m, false);
}

Table compute_gen_schlick_ior(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    return gen_schlick_table(engine, r, m, true);
}

/// The F82 edge weight alone, F = cos (1 - cos)^6 (f0 = f90 = 0, b = -1).
FresnelConfig f82_edge_weight() {
    FresnelConfig f;
    f.kind = BB_FRESNEL_GEN_SCHLICK;
    f.params[BB_GEN_SCHLICK_EXPONENT] = 5.0;
    f.params[BB_GEN_SCHLICK_B] = -1.0;
    f.canonical = "cos (1 - cos)^6 (the F82 edge term)";
    return f;
}

/// A = E - B, B and C, each integral to a third of the tolerance; the error their sum.
Table compute_dfg_f82(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    const double third = 1.0 / 3.0;
    const AlbedoResult e = integrate(engine, r, m, resolve_fresnel("none"), g.cells, third);
    const AlbedoResult b = integrate(engine, r, m, resolve_fresnel("schlick:f0=0"), g.cells, third);
    const AlbedoResult c = integrate(engine, r, m, f82_edge_weight(), g.cells, third);
    t.channels = {"A", "B", "C"};
    t.values.assign(3, {});
    for (size_t i = 0; i < g.cells.size(); ++i) {
        t.values[0].push_back(e.values[i].value - b.values[i].value);
        t.values[1].push_back(b.values[i].value);
        t.values[2].push_back(c.values[i].value);
        t.error.push_back(e.values[i].error + b.values[i].error + c.values[i].error);
    }
    t.quantity = "split-sum terms of an F82-tint metal: A = integral of (f/F)(1 - (1 - wo.wh)^5) cos, B = integral of "
                 "(f/F)(1 - wo.wh)^5 cos, C = integral of (f/F)(wo.wh)(1 - wo.wh)^6 cos; specular = F0 A + B - b C";
    describe(t, r, m, "factored out (split sum with the F82 term)", e.method, e.samples_per_cell, g.clamped);
    return std::move(g.table);
}

std::vector<std::string> dfg_f82_programs(const LutRequest& r) {
    return {"albedo|" + r.model + "|none", "albedo|" + r.model + "|schlick", "albedo|" + r.model + "|gen-schlick"};
}

int three(const LutRequest&) { return 3; }

/// --estimator cycles integrates E_w alone; the ratio also E.
bool cycles_estimator(const LutRequest& r) { return r.estimator == "cycles"; }

std::vector<std::string> gen_schlick_programs(const LutRequest& r) {
    if (cycles_estimator(r)) return {"albedo|" + r.model + "|gen-schlick"};
    return {"albedo|" + r.model + "|none", "albedo|" + r.model + "|gen-schlick"};
}

std::vector<std::string> gen_schlick_ior_programs(const LutRequest& r) {
    if (cycles_estimator(r)) return {"albedo|" + r.model + "|gen-schlick-ior"};
    return {"albedo|" + r.model + "|none", "albedo|" + r.model + "|gen-schlick-ior"};
}

void validate_gen_schlick(const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    if (!m.uses_fresnel)
        throw Error("the " + r.kind + " table weights the lobe's Fresnel term; model '" + m.name + "' has none");
    if (r.estimator != "ratio" && r.estimator != "cycles")
        throw Error("--estimator '" + r.estimator + "': give ratio (E_w / E) or cycles (Cycles' estimator)");
    const bool masking = m.smith_shadowing_slot >= 0 && m.params[m.smith_shadowing_slot] == BB_SHADOWING_MASKING;
    if (cycles_estimator(r) && !masking)
        throw Error("--estimator cycles is the albedo of the masking-only lobe (Cycles' estimator): the model must be "
                    "ggx or beckmann with shadowing=masking, not '" + m.canonical + "' (--preset cycles sets it)");
    if (r.depth < 1 || r.depth > 1024 || double(r.width) * r.height * r.depth > kMaxTexels)
        throw Error(r.kind + " table depth must be 1 to 1024 and width x height x depth at most 4M texels");
}

int integrations(const LutRequest& r) { return cycles_estimator(r) ? 1 : 2; }

TableKind make_kind(TableKindId id, const std::string& name, const std::string& description, bool ior) {
    TableKind k(id, name, description, ior ? gen_schlick_ior_programs : gen_schlick_programs,
                ior ? compute_gen_schlick_ior : compute_gen_schlick);
    k.eta_axis = true;  // a z axis: sizes WxHxD, --texels edge needs 2 per axis
    k.own_z_axis = kZAxisName;  // Cycles' z, whatever --eta-map says
    k.cycles_estimator = true;  // --estimator cycles: Cycles' own quantity
    k.fresnel_factored_out = true;
    k.plan_fresnel = "factored out (generalized Schlick: E mix(f0, f90, s))";
    k.lobe_requirement = std::string("a ") + name +
                         " table spans its own z axis (Cycles' z: " + (ior ? "the index of refraction" : "the exponent") +
                         "); the lobe's Fresnel must be generalized Schlick (gen-schlick" + (ior ? "-ior" : "") + ":...)";
    k.integrations = integrations;  // per texel: its slice's E_w, and E (shared by the slices, found twice with a tolerance)
    k.validate = validate_gen_schlick;
    k.value_channels = [](const LutRequest&) { return std::vector<std::string>{"s"}; };
    k.pass_names = [](const LutRequest& r) { return z_slice_pass_names(cycles_estimator(r) ? "" : "E (F = 1)", "E_w", r.depth); };
    return k;
}

}  // namespace

TableKind gen_schlick_kind() {
    return make_kind(TableKindId::GenSchlick, "gen-schlick",
                     "generalized-Schlick factor s(mu_o, alpha, z), albedo E mix(f0, f90, s) under F = f0 + (f90 - f0)"
                     "(1 - cos)^exponent, exponent = 5 (1 - z)/z (Cycles' ggx_gen_schlick_s)",
                     false);
}

TableKind gen_schlick_ior_kind() {
    return make_kind(TableKindId::GenSchlickIor, "gen-schlick-ior",
                     "generalized-Schlick factor s(mu_o, alpha, z) of the dielectric remapped to f0..f90, "
                     "eta = (1 + z^2)/(1 - z^2) (Cycles' ggx_gen_schlick_ior_s)",
                     true);
}

TableKind dfg_f82_kind() {
    TableKind k = variant_of(dfg_kind(), TableKindId::DfgF82, "dfg-f82",
                             "split-sum terms A, B and the F82-tint edge term C = integral of (f/F) (wo.wh)(1 - wo.wh)^6 "
                             "cos over (mu_o, alpha); specular = F0 A + B - b C (Kutz et al. 2021, OpenPBR)",
                             compute_dfg_f82);
    k.kernel_programs = dfg_f82_programs;
    k.plan_fresnel = "factored out (split sum with the F82 term)";
    k.value_channels = [](const LutRequest&) { return std::vector<std::string>{"A", "B", "C"}; };
    k.integrations = three;
    k.pass_names = [](const LutRequest&) { return std::vector<std::string>{"E (F = 1)", "B (F = Schlick, f0 = 0)", "C (F82 edge term)"}; };
    return k;
}

}  // namespace tables
}  // namespace brdfbake

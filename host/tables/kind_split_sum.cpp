// The split-sum terms (Karis 2013, "Real Shading in Unreal Engine 4"): A and B with the Fresnel
// term factored out, and their multiple-scattering layout B, E = A + B (Fdez-Aguera 2019, "A
// Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting").
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

int two(const LutRequest&) { return 2; }

std::vector<std::string> split_sum_passes(const LutRequest&) { return {"E (F = 1)", "B (F = Schlick, f0 = 0)"}; }

std::vector<std::string> split_sum_programs(const LutRequest& r) {
    return {"albedo|" + r.model + "|none", "albedo|" + r.model + "|schlick"};
}

/// The split-sum table: E with F = 1 and B with F = (1 - wo.wh)^5 (Schlick with f0 = 0), each to
/// half the tolerance, A = E - B; channels A, B, or B, E in the multiple-scattering layout.
Table split_sum_table(Engine& engine, const LutRequest& r, const ModelConfig& m, bool multiple_scattering_layout) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    const AlbedoResult e = integrate(engine, r, m, resolve_fresnel("none"), g.cells, 0.5);
    const AlbedoResult b = integrate(engine, r, m, resolve_fresnel("schlick:f0=0"), g.cells, 0.5);
    std::vector<double> a_values, b_values, e_values;
    for (size_t i = 0; i < g.cells.size(); ++i) {
        e_values.push_back(e.values[i].value);
        b_values.push_back(b.values[i].value);
        a_values.push_back(e.values[i].value - b.values[i].value);
        t.error.push_back(e.values[i].error + b.values[i].error);
    }
    describe(t, r, m, "factored out (split sum)", e.method, e.samples_per_cell, g.clamped);
    if (multiple_scattering_layout) {
        t.quantity = "split-sum terms, multiple-scattering layout: B = integral of (f/F)(1 - wo.wh)^5 cos and "
                     "E = A + B; F_ss = mix(B, E, f0), energy compensation 1 + f0 (1/E - 1)";
        t.channels = {"B", "E"};
        t.values = {b_values, e_values};
    } else {
        t.quantity = "split-sum terms: A = integral of (f/F)(1 - (1 - wo.wh)^5) cos, B = integral of (f/F)(1 - wo.wh)^5 "
                     "cos; specular = F0 A + B";
        t.channels = {"A", "B"};
        t.values = {a_values, b_values};
    }
    return std::move(g.table);
}

Table compute_dfg(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    return split_sum_table(engine, r, m, false);
}

Table compute_dfg_ms(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    return split_sum_table(engine, r, m, true);
}

}  // namespace

TableKind dfg_kind() {
    TableKind k(TableKindId::Dfg, "dfg",
                "split-sum terms A, B over (mu_o, alpha): f/F weighted by 1 - (1 - wo.wh)^5 and (1 - wo.wh)^5 "
                "(Karis 2013)",
                split_sum_programs, compute_dfg);
    k.fresnel_factored_out = true;
    k.plan_fresnel = "factored out (split sum)";
    k.tileable = true;
    k.value_channels = [](const LutRequest&) { return std::vector<std::string>{"A", "B"}; };
    k.integrations = two;
    k.pass_names = split_sum_passes;
    // Measured: the 1024x1024 lut_ggx's 34.4 G samples in about 11.5 idle-core seconds on 2
    // threads (23.7 CPU s), 3.0e9 samples/s against GGX albedo's 2.1e9
    // (benchmarks/results/plan-estimates-2c-shared.md).
    k.sample_cost = 0.7;
    return k;
}

TableKind dfg_ms_kind() {
    TableKind k = variant_of(dfg_kind(), TableKindId::DfgMs, "dfg-ms",
                             "multiple-scattering layout of the split-sum terms: B and E = A + B; F_ss = mix(B, E, f0), "
                             "energy compensation 1 + f0 (1/E - 1) (Fdez-Aguera 2019)",
                             compute_dfg_ms);
    k.value_channels = [](const LutRequest&) { return std::vector<std::string>{"B", "E"}; };
    return k;
}

}  // namespace tables
}  // namespace brdfbake

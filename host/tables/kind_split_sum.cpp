// The split-sum terms (Karis 2013, "Real Shading in Unreal Engine 4"): A and B with the Fresnel
// term factored out, and their multiple-scattering layout B, E = A + B (Fdez-Aguera 2019, "A
// Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting").
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

int two(const LutRequest&) { return 2; }

std::vector<std::string> split_sum_programs(const LutRequest& r) {
    return {"albedo|" + r.model + "|none", "albedo|" + r.model + "|schlick"};
}

/// E with F = 1 and B with F = (1 - wo.wh)^5 (Schlick with f0 = 0), each to half the tolerance;
/// A = E - B.
struct SplitSum {
    Table table;
    std::vector<double> a, b, e;
};

SplitSum split_sum(Engine& engine, const LutRequest& r, const ModelConfig& m) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    SplitSum s;
    const AlbedoResult e = integrate(engine, r, m, resolve_fresnel("none"), g.cells, 0.5);
    const AlbedoResult b = integrate(engine, r, m, resolve_fresnel("schlick:f0=0"), g.cells, 0.5);
    for (size_t i = 0; i < g.cells.size(); ++i) {
        s.e.push_back(e.values[i].value);
        s.b.push_back(b.values[i].value);
        s.a.push_back(e.values[i].value - b.values[i].value);
        g.table.error.push_back(e.values[i].error + b.values[i].error);
    }
    describe(g.table, r, m, "factored out (split sum)", e, g.clamped);
    s.table = std::move(g.table);
    return s;
}

Table compute_dfg(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    SplitSum s = split_sum(engine, r, m);
    s.table.quantity = "split-sum terms: A = integral of (f/F)(1 - (1 - wo.wh)^5) cos, B = integral of (f/F)(1 - wo.wh)^5 cos; "
                       "specular = F0 A + B";
    s.table.channels = {"A", "B"};
    s.table.values = {s.a, s.b};
    return std::move(s.table);
}

Table compute_dfg_ms(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    SplitSum s = split_sum(engine, r, m);
    s.table.quantity = "split-sum terms, multiple-scattering layout: B = integral of (f/F)(1 - wo.wh)^5 cos and "
                       "E = A + B; F_ss = mix(B, E, f0), energy compensation 1 + f0 (1/E - 1)";
    s.table.channels = {"B", "E"};
    s.table.values = {s.b, s.e};
    return std::move(s.table);
}

TableKind make_dfg() {
    TableKind k;
    k.id = TableKindId::Dfg;
    k.name = "dfg";
    k.description = "split-sum terms A, B over (mu_o, alpha): f/F weighted by 1 - (1 - wo.wh)^5 and (1 - wo.wh)^5 (Karis 2013)";
    k.fresnel_factored_out = true;
    k.plan_fresnel = "factored out (split sum)";
    k.tileable = true;
    k.value_channels = two;
    k.integrations = two;
    k.kernel_programs = split_sum_programs;
    k.fresnel = request_fresnel;
    k.compute = compute_dfg;
    return k;
}

TableKind make_dfg_ms() {
    TableKind k = make_dfg();
    k.id = TableKindId::DfgMs;
    k.name = "dfg-ms";
    k.description = "multiple-scattering layout of the split-sum terms: B and E = A + B; F_ss = mix(B, E, f0), "
                    "energy compensation 1 + f0 (1/E - 1) (Fdez-Aguera 2019)";
    k.compute = compute_dfg_ms;
    return k;
}

}  // namespace

const TableKind& dfg_kind() {
    static const TableKind k = make_dfg();
    return k;
}

const TableKind& dfg_ms_kind() {
    static const TableKind k = make_dfg_ms();
    return k;
}

}  // namespace tables
}  // namespace brdfbake

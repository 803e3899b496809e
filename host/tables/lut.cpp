// validate_lut and compute_lut through the table-kind registry, and what the kinds share.
#include "brdfbake/lut.h"

#include <cmath>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "tables/lut_common.h"
#include "tables/sweep.h"

namespace brdfbake {
namespace tables {

bool is_measured_metal(const std::string& fresnel) {
    const std::string name = fresnel.substr(0, fresnel.find(':'));  // metal:Al is not key=value
    return name == "metal" || name == "nk";
}

Axis mu_axis(const LutRequest& r, int size) {
    Axis a = make_axis("mu", r.mu_map == "sqrt" ? "mu = u^2 (u = sqrt(mu))" : "mu = u", 0.0, 1.0, size);
    for (double u : a.coordinate) a.parameter.push_back(r.mu_map == "sqrt" ? u * u : u);
    return a;
}

Axis alpha_axis(const LutRequest& r, int size, bool& clamped) {
    const bool rough = r.alpha_map == "roughness";
    Axis a = make_axis(rough ? "roughness" : "alpha", rough ? "alpha = r^2 (r = sqrt(alpha))" : "alpha = v",
                       r.alpha_lo, r.alpha_hi, size);
    clamped = false;
    for (double v : a.coordinate) {
        double alpha = rough ? v * v : v;
        if (alpha < BB_ALPHA_MIN) {
            alpha = BB_ALPHA_MIN;
            clamped = true;
        }
        a.parameter.push_back(alpha);
    }
    return a;
}

ParamBlock with_alpha(ParamBlock p, const std::vector<int>& slots, double alpha) {
    for (int s : slots) p[s] = alpha;
    return p;
}

MuAlphaGrid mu_alpha_grid(const LutRequest& r, const ModelConfig& m) {
    MuAlphaGrid g;
    g.table.kind = r.kind;
    g.table.x = mu_axis(r, r.width);
    g.table.y = alpha_axis(r, r.height, g.clamped);
    const std::vector<int> slots = roughness_slots(m);
    for (double alpha : g.table.y.parameter)
        for (double mu : g.table.x.parameter) g.cells.push_back({mu, 0.0, with_alpha(m.params, slots, alpha)});
    return g;
}

AlbedoResult integrate(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                       std::vector<AlbedoCell> cells, double share) {
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = f;
    req.cells = std::move(cells);
    req.samples = r.samples;
    req.method = r.method;
    req.precision = r.precision;
    if (r.tolerance.tolerance > 0.0) {
        ToleranceRequest t = r.tolerance;
        t.tolerance *= share;
        return compute_albedo_to_tolerance(engine, req, t);
    }
    return compute_albedo(engine, req);
}

Table directional_albedo_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                               const std::string& quantity) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.quantity = quantity;
    const AlbedoResult res = integrate(engine, r, m, f, g.cells);
    t.channels = {"E"};
    t.values.assign(1, {});
    for (const auto& v : res.values) {
        t.values[0].push_back(v.value);
        t.error.push_back(v.error);
    }
    describe(t, r, m, f.canonical, res.method, res.samples_per_cell, g.clamped);
    return std::move(g.table);
}

void describe(Table& t, const LutRequest& r, const ModelConfig& m, const std::string& fresnel,
              const std::string& method, std::uint64_t samples_per_cell, bool clamped) {
    t.attributes["model"] = m.canonical;
    t.attributes["fresnel"] = fresnel;
    t.attributes["method"] = method;
    t.attributes["samples"] = std::to_string(samples_per_cell);
    t.attributes["precision"] = precision_name(r.precision);
    if (r.tolerance.tolerance > 0.0) {
        std::ostringstream tol;
        tol << r.tolerance.tolerance;
        t.attributes["tolerance"] = tol.str();
    }
    if (clamped) {
        std::ostringstream s;
        s << "alpha below " << BB_ALPHA_MIN << " was computed at " << BB_ALPHA_MIN;
        t.attributes["alpha_floor"] = s.str();
    }
}

TableKind variant_of(TableKind base, TableKindId id, const std::string& name, const std::string& description,
                     TableKind::Compute compute) {
    base.id = id;
    base.name = name;
    base.description = description;
    base.compute = compute;
    return base;
}

}  // namespace tables

int one_per_request(const LutRequest&) { return 1; }

FresnelConfig request_fresnel(const LutRequest& r) { return resolve_fresnel(r.fresnel, r.wavelength_nm); }

namespace {

/// The request's model with a placeholder alpha that the table sweeps.
ModelConfig swept_model(const LutRequest& r) {
    const Spec spec = parse_spec(r.model);
    for (const auto& kv : spec.keys)
        if (kv.first == "alpha" || kv.first == "roughness" || kv.first == "alpha_x" || kv.first == "alpha_y")
            throw Error("leave " + kv.first + " out of --model: the table sweeps alpha (see --alpha-map, --alpha-range)");
    return sweep_model(r.model);
}

}  // namespace

void validate_lut(const LutRequest& r) {
    const TableKind& kind = table_kind(r.kind);
    const ModelConfig m = swept_model(r);
    const FresnelConfig f = kind.fresnel(r);
    if (kind.fresnel_factored_out && f.kind != BB_FRESNEL_NONE)
        throw Error("the split-sum table factors the Fresnel term out; drop --fresnel");
    if (f.kind != BB_FRESNEL_NONE && !m.uses_fresnel)
        throw Error("model '" + m.name + "' has no Fresnel term; drop --fresnel");
    if (r.width < 1 || r.height < 1 || r.width > 4096 || r.height > 4096 ||
        double(r.width) * r.height > tables::kMaxTexels)
        throw Error("table size " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                    " is out of range (1 to 4096 per side, at most 4M texels)");
    if (r.mu_map != "linear" && r.mu_map != "sqrt") throw Error("--mu-map must be linear or sqrt");
    if (r.alpha_map != "alpha" && r.alpha_map != "roughness") throw Error("--alpha-map must be alpha or roughness");
    if (!(r.alpha_lo >= 0.0 && r.alpha_hi > r.alpha_lo && r.alpha_hi <= 3.0))
        throw Error("--alpha-range must satisfy 0 <= lo < hi <= 3");
    if (r.samples < 16) throw Error("--samples must be at least 16");
    if (kind.validate) kind.validate(r, m, f);
}

Table compute_lut(Engine& engine, const LutRequest& r) {
    validate_lut(r);
    const TableKind& kind = table_kind(r.kind);
    return kind.compute(engine, r, swept_model(r), kind.fresnel(r));
}

}  // namespace brdfbake

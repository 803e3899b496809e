// validate_lut and compute_lut through the table-kind registry, and what the kinds share.
#include "brdfbake/lut.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/progress.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "integrate/random_walk.h"
#include "integrate/refine.h"
#include "models/key_reader.h"
#include "models/params.h"
#include "models/merl_file.h"
#include "tables/lut_common.h"
#include "tables/sweep.h"

namespace brdfbake {
namespace tables {

bool has_mirror_limit(const ModelConfig& m) {
    // The Smith microfacet lobes: as alpha -> 0, D tends to a delta about the normal and G to 1,
    // so E(mu) -> F(mu), the mirror's albedo (Walter et al. 2007, "Microfacet Models for
    // Refraction through Rough Surfaces", eq. 20 with D -> delta).
    return m.smith_shadowing_slot >= 0;
}

std::string table_mu_axis_name(const LutRequest& r) {
    return r.mu_map == "sqrt" ? "sqrt_mu" : r.mu_map == "sqrt-one-minus" ? "sqrt_one_minus_mu" : "mu";
}

std::string min_median_max_text(std::vector<double> v) {
    if (v.empty()) return "none";
    std::sort(v.begin(), v.end());
    std::ostringstream s;
    s.precision(4);
    s << "min " << v.front() << ", median " << v[v.size() / 2] << ", max " << v.back();
    return s.str();
}

Axis mu_axis(const LutRequest& r, int size) {
    // linear: mu = u; sqrt: u = sqrt(mu); sqrt-one-minus: u = sqrt(1 - mu) (three.js's LTC tables)
    const bool sq = r.mu_map == "sqrt", om = r.mu_map == "sqrt-one-minus";
    const std::string of_u = sq ? "u^2" : om ? "1 - u^2" : "u";
    const std::string note = sq ? " (u = sqrt(mu))" : om ? " (u = sqrt(1 - mu))" : "";
    Axis a = make_axis(table_mu_axis_name(r), "mu = " + of_u + note, r.mu_lo, r.mu_hi, size, r.texels);
    a.parameter_name = "mu";
    bool floored = false;
    for (double u : a.coordinate) {
        double mu = sq ? u * u : om ? 1.0 - u * u : u;
        if (mu < r.mu_floor) {
            mu = r.mu_floor;
            floored = true;
        }
        a.parameter.push_back(mu);
    }
    if (floored) {
        std::ostringstream m;
        m << "mu = max(" << of_u << ", " << r.mu_floor << ")" << note << ": mu below " << r.mu_floor
          << " was computed at " << r.mu_floor;
        a.mapping = m.str();
    }
    return a;
}

Axis alpha_axis(const LutRequest& r, int size, bool& clamped) {
    const bool rough = r.alpha_map == "roughness";
    Axis a = make_axis(rough ? "roughness" : "alpha", rough ? "alpha = r^2 (r = sqrt(alpha))" : "alpha = v", r.alpha_lo,
                       r.alpha_hi, size, r.texels);
    a.parameter_name = "alpha";
    const std::optional<ModelConfig> m = try_sweep_model(r.model);
    const bool zero_is_limit = m && has_mirror_limit(*m);
    const double floor = m ? alpha_floor(*m) : double(BB_ALPHA_MIN);
    clamped = false;
    for (double v : a.coordinate) {
        double alpha = rough ? v * v : v;
        if (alpha < floor && !(alpha == 0.0 && zero_is_limit)) {
            alpha = floor;
            clamped = true;
        }
        a.parameter.push_back(alpha);
    }
    return a;
}

double eta_coordinate(const std::string& map, double eta) {
    if (map == "f0") return ((eta - 1) / (eta + 1)) * ((eta - 1) / (eta + 1));
    if (map == "cycles") return std::sqrt((eta - 1) / (eta + 1));
    return eta;
}

double eta_from_coordinate(const std::string& map, double w) {
    if (map == "f0") return (1 + std::sqrt(w)) / (1 - std::sqrt(w));
    if (map == "cycles") return (1 + w * w) / (1 - w * w);
    return w;
}

std::string eta_axis_name(const LutRequest& r) {
    return r.eta_map == "f0" ? "f0" : r.eta_map == "cycles" ? "cycles_z" : "eta";
}

Axis eta_axis(const LutRequest& r, int size) {
    const bool f0 = r.eta_map == "f0", cycles = r.eta_map == "cycles";
    // Cycles' whole z range (validate_lut allows eta_hi = infinity with the cycles map only).
    const bool to_infinity = cycles && std::isinf(r.eta_hi);
    std::string mapping =
        f0       ? "eta = (1 + sqrt(w)) / (1 - sqrt(w)) (w = F0 = ((eta - 1)/(eta + 1))^2, reflectance at normal incidence)"
        : cycles ? "eta = (1 + w^2) / (1 - w^2) (w = sqrt((eta - 1)/(eta + 1)) = F0^(1/4), Cycles' glass tables)"
                 : "eta = w";
    if (to_infinity) {
        std::ostringstream m;
        m << mapping << "; w above " << kCyclesZHi << " was computed at " << kCyclesZHi << ", as Cycles does; w = "
          << kCyclesZHi << " is eta = " << eta_from_coordinate("cycles", kCyclesZHi) << ", w = 1 eta = infinity";
        mapping = m.str();
    }
    Axis a = make_axis(eta_axis_name(r), mapping, eta_coordinate(r.eta_map, r.eta_lo),
                       to_infinity ? 1.0 : eta_coordinate(r.eta_map, r.eta_hi), size, r.texels);
    a.parameter_name = "eta";
    for (size_t i = 0; i < a.coordinate.size(); ++i) {
        // The range's ends exactly as asked (the mapping's round trip may round).
        const bool first = i == 0 && (r.texels == Texels::Edge);
        const bool last = i + 1 == a.coordinate.size() && r.texels == Texels::Edge && !to_infinity;
        const double w = to_infinity ? std::min(a.coordinate[i], kCyclesZHi) : a.coordinate[i];
        a.parameter.push_back(first ? r.eta_lo : last ? r.eta_hi : eta_from_coordinate(r.eta_map, w));
    }
    return a;
}

ParamBlock with_alpha(const ModelConfig& m, ParamBlock p, const std::vector<int>& slots, double alpha) {
    return slots.empty() ? p : with_roughness(m, p, alpha);
}

double alpha_floor(const ModelConfig& m) {
    const RoughnessAxis& axis = m.traits().roughness_axis;
    return axis.value ? axis.alpha_lo : double(BB_ALPHA_MIN);
}

MuAlphaGrid mu_alpha_grid(const LutRequest& r, const ModelConfig& m) {
    MuAlphaGrid g;
    g.table.kind = r.kind;
    g.table.x = mu_axis(r, r.width);
    g.table.y = alpha_axis(r, r.height, g.clamped);
    const std::vector<int> slots = roughness_slots(m);
    for (double alpha : g.table.y.parameter)
        for (double mu : g.table.x.parameter) g.cells.push_back({mu, 0.0, with_alpha(m, m.params, slots, alpha)});
    return g;
}

AlbedoResult integrate(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                       std::vector<AlbedoCell> cells, double share) {
    progress_next_pass();  // each integration is a pass of its table (TableKind::pass_names)
    // Cells at alpha = 0 of a model with a mirror limit hold that limit, F(mu); the others are
    // integrated on the device.
    const std::vector<int> slots = m.traits().alpha_x_slot < 0 ? std::vector<int>{} : roughness_slots(m);
    std::vector<size_t> limit, rest;
    for (size_t c = 0; c < cells.size(); ++c) {
        bool zero = has_mirror_limit(m) && !slots.empty();
        for (int s : slots) zero = zero && cells[c].params[s] == 0.0;
        (zero ? limit : rest).push_back(c);
    }
    AlbedoRequest req;
    req.model = m.id;
    req.fresnel = f;
    req.samples = r.samples;
    req.method = r.method;
    req.precision = r.precision;
    for (size_t c : rest) req.cells.push_back(cells[c]);
    AlbedoResult integrated;
    if (!req.cells.empty() && m.simulated) {
        integrated = walk_albedo_result(engine, req, r.tolerance, share);  // lut albedo of scattering=multiple
    } else if (!req.cells.empty()) {
        if (r.tolerance.tolerance > 0.0) {
            ToleranceRequest t = r.tolerance;
            t.tolerance *= share;
            try {
                integrated = compute_albedo_to_tolerance(engine, req, t);
            } catch (const ToleranceNotMet& e) {
                throw e.restated(r.tolerance.tolerance, "");  // the message names the user's tolerance
            }
        } else {
            integrated = compute_albedo(engine, req);
        }
    } else {
        integrated.method = "closed form (the mirror limit at alpha = 0)";
    }
    if (limit.empty()) return integrated;
    AlbedoResult out = integrated;
    out.values.assign(cells.size(), AlbedoValue{});
    for (size_t k = 0; k < rest.size(); ++k) out.values[rest[k]] = integrated.values[k];
    for (size_t c : limit) {
        AlbedoValue v;
        v.value = fresnel_value(f, cells[c].mu);
        v.error = 4 * std::numeric_limits<double>::epsilon();  // F evaluated in double
        v.method = integrated.values.empty() ? r.method : integrated.values.front().method;
        out.values[c] = v;
    }
    return out;
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
        s << "alpha below " << alpha_floor(m) << " was computed at " << alpha_floor(m);
        t.attributes["alpha_floor"] = s.str();
    }
    const RoughnessAxis& axis = m.traits().roughness_axis;
    if (axis.value) t.attributes["roughness_axis"] = std::string("alpha sets ") + axis.key + ": " + axis.mapping;
    for (const Axis* a : {&t.x, &t.y})
        if (a->parameter_name == "alpha" && has_mirror_limit(m) &&
            std::find(a->parameter.begin(), a->parameter.end(), 0.0) != a->parameter.end())
            t.attributes["alpha_zero"] =
                "texels at alpha = 0 hold the model's delta limit, a mirror (Walter et al. 2007, D -> delta, G -> 1): "
                "albedo E = F(mu) (1 without Fresnel), split sum A = 1 - (1 - mu)^5 and B = (1 - mu)^5, dielectric "
                "R = F(mu, eta) and T = 1 - R";
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

std::vector<std::string> one_value_channel(const LutRequest&) { return {"E"}; }

FresnelConfig request_fresnel(const LutRequest& r) { return resolve_fresnel(r.fresnel, r.wavelength_nm); }

std::vector<std::string> table_axis_names(const TableKind& kind, const LutRequest& r) {
    std::vector<std::string> names;
    if (!kind.one_dimensional) names.push_back(tables::table_mu_axis_name(r));
    names.push_back(r.alpha_map == "roughness" ? "roughness" : "alpha");
    if (kind.eta_axis) names.push_back(kind.own_z_axis.empty() ? tables::eta_axis_name(r) : kind.own_z_axis);
    return names;
}

namespace {

/// Whether the request's model is swept in alpha: all but a measured model (merl), whose albedo
/// and eavg tables are 1D in mu and one texel (kind_albedo.cpp), and which every other kind refuses.
bool sweeps_roughness(const LutRequest& r) {
    const std::string name = parse_spec(r.model).name;
    for (const ModelTraits& t : model_registry())
        if (name == t.name) return !t.measured;
    return true;  // an unknown name: sweep_model names the mistake
}

/// The request's model with a placeholder alpha that the table sweeps (as it is without one).
ModelConfig swept_model(const LutRequest& r) {
    if (!sweeps_roughness(r))  // a merl spec's channel=rgb: the red channel's (kind_albedo.cpp makes all three)
        return resolve_model(merl_rgb_spec(r.model) ? merl_channel_spec(r.model, "r") : r.model);
    const Spec spec = parse_spec(r.model);
    const RoughnessAxis axis = roughness_axis_of_spec(r.model);
    for (const auto& kv : spec.keys) {
        if (kv.first == "alpha" || kv.first == "roughness" || kv.first == "alpha_x" || kv.first == "alpha_y")
            throw Error("leave " + kv.first + " out of --model: the table sweeps alpha (see --alpha-map, --alpha-range)");
        if (axis.value && kv.first == axis.key)
            throw Error("leave " + kv.first + " out of --model: the table's alpha axis sets it (" + axis.mapping +
                        "; see --alpha-map, --alpha-range)");
    }
    const ModelConfig m = sweep_model(r.model, table_kind(r.kind).id == TableKindId::Albedo);
    if (m.dielectric_walk && table_kind(r.kind).id != TableKindId::Albedo)
        throw Error("lut " + r.kind + ": model '" + m.canonical + "' is the rough dielectric's walk (eta=E), whose R "
                    "and T `lut albedo` tabulates; this kind takes the conductor's walk (no eta)");
    return m;
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
    if (r.estimator != "ratio" && r.estimator != "cycles") throw Error("--estimator must be ratio or cycles");
    if (r.estimator != "ratio" && !kind.cycles_estimator)
        throw Error("--estimator " + r.estimator + " is for the gen-schlick, gen-schlick-ior and sheen-ltc tables, not " + r.kind);
    if (r.mu_map != "linear" && r.mu_map != "sqrt" && r.mu_map != "sqrt-one-minus")
        throw Error("--mu-map must be linear, sqrt or sqrt-one-minus");
    if (r.alpha_map != "alpha" && r.alpha_map != "roughness") throw Error("--alpha-map must be alpha or roughness");
    if (!(r.alpha_lo >= 0.0 && r.alpha_hi > r.alpha_lo && r.alpha_hi <= 3.0))
        throw Error("--alpha-range must satisfy 0 <= lo < hi <= 3");
    if (sweeps_roughness(r)) {
        // The largest alpha the table sweeps must be one the model takes (sheen's fit ends at 1).
        const double top = r.alpha_map == "roughness" ? r.alpha_hi * r.alpha_hi : r.alpha_hi;
        const RoughnessAxis& axis = m.traits().roughness_axis;
        if (axis.value && top > axis.alpha_hi)
            throw Error("--alpha-range reaches alpha = " + format_number(top) + ", beyond " + m.name +
                        "'s roughness axis (" + axis.mapping + ")");
        try {
            resolve_model_simulated(r.model + (r.model.find(':') == std::string::npos ? ":" : ",") + axis.key + "=" +
                                    format_number(axis.value ? axis.value(top) : top));
        } catch (const Error& e) {
            throw Error("--alpha-range reaches alpha = " + format_number(top) + ", which " + m.name +
                        " does not take: " + e.what());
        }
    }
    if (!(r.mu_lo >= 0.0 && r.mu_hi > r.mu_lo && r.mu_hi <= 1.0))
        throw Error("--mu-range must satisfy 0 <= lo < hi <= 1");
    if (!(r.mu_floor > 0.0 && r.mu_floor < 1.0)) throw Error("--mu-floor must satisfy 0 < floor < 1");
    if (kind.eta_axis && kind.own_z_axis.empty()) {
        if (r.eta_map != "linear" && r.eta_map != "f0" && r.eta_map != "cycles")
            throw Error("--eta-map must be linear, f0 or cycles, not '" + r.eta_map + "'");
        const bool to_infinity = std::isinf(r.eta_hi) && r.eta_hi > 0.0;
        if (to_infinity && r.eta_map != "cycles")
            throw Error("an eta range up to infinity is Cycles' whole z axis (--preset cycles): it needs --eta-map cycles, "
                        "not " + r.eta_map);
        if (!(r.eta_lo > 0.0 && r.eta_lo <= 100.0 && r.eta_hi > r.eta_lo && (r.eta_hi <= 100.0 || to_infinity)))
            throw Error("--eta-range must satisfy 0 < lo < hi <= 100 (eta below 1: light from the denser side)");
        if (r.eta_map != "linear" && r.eta_lo < 1.0)
            throw Error("--eta-map " + r.eta_map + " covers eta >= 1 (the inside view is the 1/eta channels); "
                        "use --eta-range with lo >= 1 or --eta-map linear");
    }
    if (r.texels == Texels::Edge && (r.width < 2 || (!kind.one_dimensional && r.height < 2) ||
                                     (kind.eta_axis && r.depth < 2)))
        throw Error("--texels edge needs at least 2 texels per axis (one texel cannot sit on both ends of a range)");
    {
        // The axis names that --axes and --flip may use, as the kind's axes will be named.
        const std::vector<std::string> names = table_axis_names(kind, r);
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        auto check = [&](const std::vector<std::string>& list, const char* option) {
            for (size_t i = 0; i < list.size(); ++i) {
                if (std::find(names.begin(), names.end(), list[i]) == names.end())
                    throw Error(std::string(option) + ": the " + r.kind + " table has no axis '" + list[i] +
                                "'; its axes: " + known);
                if (std::find(list.begin(), list.begin() + long(i), list[i]) != list.begin() + long(i))
                    throw Error(std::string(option) + ": '" + list[i] + "' is named twice");
            }
        };
        check(r.axes, "--axes");
        check(r.flip, "--flip");
        if (!r.axes.empty() && r.axes.size() != names.size())
            throw Error("--axes: name each of the " + r.kind + " table's axes once: " + known);
    }
    if (r.samples < 16) throw Error("--samples must be at least 16");
    if (kind.validate) kind.validate(r, m, f);
}

Table lut_table_shape(const LutRequest& r) {
    const TableKind& kind = table_kind(r.kind);
    const ModelConfig m = swept_model(r);
    Table t;
    t.kind = r.kind;
    t.channels = kind.value_channels(r);
    // A merl spec with channel=rgb: its channels' model, named as kind_albedo.cpp's per_colour names it.
    t.attributes["model"] = !kind.table_model.empty() ? kind.table_model
                            : merl_rgb_spec(r.model)   ? merl_channel_spec(m.canonical, "rgb")
                                                       : m.canonical;
    const Axis none = make_axis("-", "-", 0.0, 1.0, 1);
    bool clamped = false;
    if (!sweeps_roughness(r)) {  // a measured model: E(mu) along x, Eavg one texel (kind_albedo.cpp)
        t.x = kind.one_dimensional ? none : tables::mu_axis(r, r.width);
        t.y = none;
    } else if (kind.one_dimensional) {
        t.x = tables::alpha_axis(r, r.width, clamped);
        t.y = none;
    } else {
        t.x = tables::mu_axis(r, r.width);
        t.y = tables::alpha_axis(r, r.height, clamped);
    }
    if (kind.eta_axis)
        t.z = kind.own_z_axis.empty() ? tables::eta_axis(r, r.depth)
                                      : make_axis(kind.own_z_axis, "the kind's own", 0.0, 1.0, r.depth, r.texels);
    arrange_axes(t, r.axes, r.flip);
    return t;
}

Table compute_lut(Engine& engine, const LutRequest& r) {
    validate_lut(r);
    const TableKind& kind = table_kind(r.kind);
    const ProgressPasses passes(kind.pass_names ? kind.pass_names(r) : std::vector<std::string>{});  // integrate() advances
    Table t = kind.compute(engine, r, swept_model(r), kind.fresnel(r));
    // The kind's declared channels are what `lut -o` checked the format against before the compute.
    if (t.channels != kind.value_channels(r))
        throw Error("internal error: the " + r.kind + " table's channels are not the ones its kind declares");
    arrange_axes(t, r.axes, r.flip);
    if (r.texels == Texels::Edge || !r.axes.empty() || !r.flip.empty()) {
        std::string order;
        for (const Axis* a : {&t.x, &t.y, &t.z})
            if (a->size > 1 || a == &t.x) order += (order.empty() ? "" : ", ") + a->name;
        t.attributes["axis_order"] = order + " (x first)";
    }
    return t;
}

}  // namespace brdfbake

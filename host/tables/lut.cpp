#include "brdfbake/lut.h"

#include <boost/math/quadrature/gauss.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "models/key_reader.h"

namespace brdfbake {

std::vector<std::pair<std::string, std::string>> lut_kinds() {
    return {
        {"albedo", "directional albedo E(mu_o, alpha) = integral of f cos(theta_i) dwi (2D)"},
        {"eavg", "average albedo Eavg(alpha) = 2 integral of E(mu) mu dmu (1D)"},
        {"dfg", "split-sum terms A, B over (mu_o, alpha): f/F weighted by 1 - (1 - wo.wh)^5 and (1 - wo.wh)^5 (Karis 2013)"},
        {"dielectric", "rough dielectric (GGX) reflected and transmitted energy R, T from outside (eta) and "
                       "R_inside, T_inside from inside (1/eta) over (mu_o, alpha, eta) (3D, slices stacked along y)"},
        {"conductor", "Fresnel-weighted albedo E(mu_o, alpha) of a conductor: --fresnel conductor:eta=,k= (channel E) or "
                      "metal:X / nk:FILE (channels R, G, B at 650, 550, 450 nm, or E at --wavelength)"},
        {"dfg-ms", "multiple-scattering layout of the split-sum terms: B and E = A + B; F_ss = mix(B, E, f0), "
                   "energy compensation 1 + f0 (1/E - 1) (Fdez-Aguera 2019)"},
    };
}

namespace {

constexpr int kMaxTexels = 1 << 22;
constexpr double kRgbNm[3] = {650.0, 550.0, 450.0};
const char* const kRgbNames[3] = {"R", "G", "B"};

/// A conductor table of a measured metal without --wavelength: one channel per RGB wavelength.
bool rgb_default(const LutRequest& r) {
    if (r.kind != "conductor" || r.wavelength_nm != 0.0) return false;
    const std::string name = r.fresnel.substr(0, r.fresnel.find(':'));
    return name == "metal" || name == "nk";
}

/// The parameter slots that hold alpha_x and alpha_y for a model whose roughness is swept.
std::vector<int> alpha_slots(const ModelConfig& m) {
    switch (m.id) {
    case BB_MODEL_GGX:
        return {BB_GGX_ALPHA_X, BB_GGX_ALPHA_Y};
    case BB_MODEL_BECKMANN:
        return {BB_BECKMANN_ALPHA_X, BB_BECKMANN_ALPHA_Y};
    case BB_MODEL_TORRANCE_SPARROW:
        if (m.params[BB_TORRANCE_SPARROW_DIST] != BB_TS_D_BLINN)
            return {BB_TORRANCE_SPARROW_ALPHA_X, BB_TORRANCE_SPARROW_ALPHA_Y};
        throw Error("torrance-sparrow with d=blinn has an exponent, not alpha, to sweep; use d=beckmann or d=ggx");
    default:
        throw Error("model '" + m.name + "' has no roughness alpha to sweep; tables need a microfacet model");
    }
}

/// The model with a placeholder alpha (the table overwrites it per texel).
ModelConfig sweep_model(const std::string& spec_text) {
    const Spec spec = parse_spec(spec_text);
    for (const auto& kv : spec.keys)
        if (kv.first == "alpha" || kv.first == "roughness" || kv.first == "alpha_x" || kv.first == "alpha_y")
            throw Error("leave " + kv.first + " out of --model: the table sweeps alpha (see --alpha-map, --alpha-range)");
    ModelConfig m = resolve_model(spec_text + (spec.keys.empty() && spec_text.find(':') == std::string::npos ? ":" : ",") +
                                  "alpha=0.5");
    alpha_slots(m);
    // Canonical spec without the placeholder.
    const size_t p = m.canonical.find("alpha=0.5");
    if (p != std::string::npos) {
        std::string c = m.canonical;
        c.erase(p, 9);
        while (c.find(":,") != std::string::npos) c.replace(c.find(":,"), 2, ":");
        while (c.find(",,") != std::string::npos) c.replace(c.find(",,"), 2, ",");
        if (!c.empty() && (c.back() == ',' || c.back() == ':')) c.pop_back();
        m.canonical = c;
    }
    return m;
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

// The albedo of every cell, with the request's method and samples, or to its tolerance times
// `share` (the split-sum table adds two integrals' errors: each gets half).
AlbedoResult integrate(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                       std::vector<AlbedoCell> cells, double share = 1.0) {
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

// The rough dielectric to a tolerance: importance sampling in rounds of 4x the samples over the
// cells whose larger error (R or T) is still above it.
DielectricResult dielectric_to_tolerance(Engine& engine, DielectricRequest req, const ToleranceRequest& tol) {
    if (tol.tolerance < 2.0 * tolerance_floor(req.precision))
        throw Error("--tolerance is below what " + std::string(precision_name(req.precision)) +
                    " arithmetic can certify");
    DielectricResult out;
    const size_t n = req.cells.size();
    out.reflected.assign(n, AlbedoValue{});
    out.transmitted.assign(n, AlbedoValue{});
    std::vector<size_t> todo(n);
    for (size_t c = 0; c < n; ++c) todo[c] = c;
    const std::vector<DielectricCell> all = req.cells;
    for (std::uint64_t s = std::uint64_t(1) << 14; s <= tol.max_samples && !todo.empty(); s *= 4) {
        req.samples = s;
        req.cells.clear();
        for (size_t c : todo) req.cells.push_back(all[c]);
        const DielectricResult part = compute_dielectric(engine, req);
        out.kernel_seconds += part.kernel_seconds;
        out.samples_per_cell = s;
        std::vector<size_t> left;
        for (size_t i = 0; i < todo.size(); ++i) {
            out.reflected[todo[i]] = part.reflected[i];
            out.transmitted[todo[i]] = part.transmitted[i];
            if (std::max(part.reflected[i].error, part.transmitted[i].error) > tol.tolerance) left.push_back(todo[i]);
        }
        todo.swap(left);
    }
    if (!todo.empty()) {
        std::ostringstream e;
        e << "--tolerance " << tol.tolerance << " not met at " << todo.size() << " of " << n << " dielectric texels within "
          << tol.max_samples << " samples per texel (first: mu = " << all[todo[0]].mu << ", alpha = " << all[todo[0]].alpha
          << ", eta = " << all[todo[0]].eta << "); raise --max-samples or loosen the tolerance";
        throw Error(e.str(), kExitViolation);
    }
    std::ostringstream m;
    m << "importance sampling, randomised Hammersley, refined to tolerance " << tol.tolerance << " (at most "
      << out.samples_per_cell << " samples per texel)";
    out.method = m.str();
    return out;
}

void describe(Table& t, const LutRequest& r, const ModelConfig& m, const std::string& fresnel,
              const AlbedoResult& res, bool clamped) {
    t.attributes["model"] = m.canonical;
    t.attributes["fresnel"] = fresnel;
    t.attributes["method"] = res.method;
    t.attributes["samples"] = std::to_string(res.samples_per_cell);
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

}  // namespace

void validate_lut(const LutRequest& r) {
    bool known = false;
    for (const auto& k : lut_kinds()) known = known || k.first == r.kind;
    if (!known) {
        std::string list;
        for (const auto& k : lut_kinds()) list += (list.empty() ? "" : ", ") + k.first;
        throw Error("unknown table kind '" + r.kind + "'; known: " + list);
    }
    const ModelConfig m = sweep_model(r.model);
    const FresnelConfig f = resolve_fresnel(r.fresnel, rgb_default(r) ? kRgbNm[0] : r.wavelength_nm);
    if ((r.kind == "dfg" || r.kind == "dfg-ms") && f.kind != BB_FRESNEL_NONE)
        throw Error("the split-sum table factors the Fresnel term out; drop --fresnel");
    if (f.kind != BB_FRESNEL_NONE && !m.uses_fresnel)
        throw Error("model '" + m.name + "' has no Fresnel term; drop --fresnel");
    if (r.width < 1 || r.height < 1 || r.width > 4096 || r.height > 4096 ||
        double(r.width) * r.height > kMaxTexels)
        throw Error("table size " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                    " is out of range (1 to 4096 per side, at most 4M texels)");
    if (r.mu_map != "linear" && r.mu_map != "sqrt") throw Error("--mu-map must be linear or sqrt");
    if (r.alpha_map != "alpha" && r.alpha_map != "roughness") throw Error("--alpha-map must be alpha or roughness");
    if (!(r.alpha_lo >= 0.0 && r.alpha_hi > r.alpha_lo && r.alpha_hi <= 3.0))
        throw Error("--alpha-range must satisfy 0 <= lo < hi <= 3");
    if (r.samples < 16) throw Error("--samples must be at least 16");
    if (r.kind == "dielectric") {
        if (r.method != Method::Importance || (r.tolerance.tolerance > 0.0 && !r.tolerance.auto_method))
            throw Error("the dielectric table is computed by importance sampling only; use --method importance or auto");
        if (m.id != BB_MODEL_GGX) throw Error("the dielectric table is computed for GGX microfacets; use --model ggx");
        if (f.kind != BB_FRESNEL_NONE) throw Error("the dielectric table uses the exact dielectric Fresnel term; drop --fresnel");
        if (r.depth < 1 || r.depth > 1024 || double(r.width) * r.height * r.depth > kMaxTexels)
            throw Error("dielectric table depth must be 1 to 1024 and the table at most 4M texels");
        if (!(r.eta_lo >= 1.0 && r.eta_hi > r.eta_lo && r.eta_hi <= 10.0))
            throw Error("--eta-range must satisfy 1 <= lo < hi <= 10 (the inside view uses 1/eta)");
    }
    if (r.kind == "conductor") {
        const std::string name = r.fresnel.substr(0, r.fresnel.find(':'));  // metal:Al is not key=value
        const bool measured = name == "metal" || name == "nk";
        if (!(f.kind == BB_FRESNEL_CONDUCTOR || f.kind == BB_FRESNEL_CONDUCTOR_APPROX || measured))
            throw Error("the conductor table needs a conductor Fresnel term: --fresnel conductor:eta=E,k=K, metal:Al or nk:FILE");
    }
}

Table compute_lut(Engine& engine, const LutRequest& r) {
    validate_lut(r);
    const ModelConfig m = sweep_model(r.model);
    const std::vector<int> slots = alpha_slots(m);
    const FresnelConfig f = resolve_fresnel(r.fresnel, rgb_default(r) ? kRgbNm[0] : r.wavelength_nm);
    Table t;
    t.kind = r.kind;
    bool clamped = false;

    if (r.kind == "eavg") {
        // Eavg = 2 int_0^1 E(mu) mu dmu by Gauss-Legendre in mu with 32 nodes; the 16-node rule
        // on the same data's integrand gives the quadrature error estimate.
        t.quantity = "average albedo Eavg(alpha) = 2 integral_0^1 E(mu) mu dmu";
        t.x = alpha_axis(r, r.width, clamped);
        t.y = make_axis("-", "-", 0.0, 1.0, 1);
        t.y.parameter = {0.5};
        using G32 = boost::math::quadrature::gauss<double, 32>;
        using G16 = boost::math::quadrature::gauss<double, 16>;
        std::vector<double> nodes, weights32, weights16;  // on [0, 1]
        auto add_rule = [&](const auto& x, const auto& w, bool is32) {
            for (size_t i = 0; i < x.size(); ++i)
                for (int s : {-1, 1}) {
                    if (x[i] == 0.0 && s == 1) continue;
                    nodes.push_back(0.5 + 0.5 * s * x[i]);
                    weights32.push_back(is32 ? 0.5 * w[i] : 0.0);
                    weights16.push_back(is32 ? 0.0 : 0.5 * w[i]);
                }
        };
        add_rule(G32::abscissa(), G32::weights(), true);
        add_rule(G16::abscissa(), G16::weights(), false);
        std::vector<AlbedoCell> cells;
        for (double alpha : t.x.parameter)
            for (double mu : nodes) cells.push_back({mu, 0.0, with_alpha(m.params, slots, alpha)});
        const AlbedoResult res = integrate(engine, r, m, f, cells);
        t.channels = {"Eavg"};
        t.values.assign(1, {});
        for (size_t a = 0; a < t.x.parameter.size(); ++a) {
            double e32 = 0, e16 = 0, err = 0;
            for (size_t k = 0; k < nodes.size(); ++k) {
                const AlbedoValue& v = res.values[a * nodes.size() + k];
                e32 += 2 * weights32[k] * nodes[k] * v.value;
                e16 += 2 * weights16[k] * nodes[k] * v.value;
                err += 2 * weights32[k] * nodes[k] * v.error;  // errors add linearly: shared point sets
            }
            t.values[0].push_back(e32);
            t.error.push_back(err + std::fabs(e32 - e16));
        }
        describe(t, r, m, f.canonical, res, clamped);
        t.attributes["mu_quadrature"] = "Gauss-Legendre, 32 nodes (16-node rule for the error estimate)";
        return t;
    }

    t.x = mu_axis(r, r.width);
    t.y = alpha_axis(r, r.height, clamped);
    std::vector<AlbedoCell> cells;
    for (double alpha : t.y.parameter)
        for (double mu : t.x.parameter) cells.push_back({mu, 0.0, with_alpha(m.params, slots, alpha)});

    if (r.kind == "dielectric") {
        t.quantity = "rough dielectric interface: energy fractions reflected (R) and transmitted (T) for light "
                     "from outside (relative index eta), and R_inside, T_inside from inside (relative index 1/eta); "
                     "transmitted radiance is T times (eta_t/eta_i)^2";
        t.z = make_axis("eta", "eta = w", r.eta_lo, r.eta_hi, r.depth);
        t.z.parameter = t.z.coordinate;
        DielectricRequest dr;
        dr.correlated = m.params[BB_GGX_SHADOWING] > 0.5;
        dr.samples = r.samples;
        dr.precision = r.precision;
        for (int side = 0; side < 2; ++side)
            for (double eta : t.z.parameter)
                for (double alpha : t.y.parameter)
                    for (double mu : t.x.parameter) dr.cells.push_back({mu, alpha, side == 0 ? eta : 1.0 / eta});
        const DielectricResult res =
            r.tolerance.tolerance > 0.0 ? dielectric_to_tolerance(engine, dr, r.tolerance) : compute_dielectric(engine, dr);
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
        t.attributes["model"] = m.canonical;
        t.attributes["fresnel"] = "dielectric (exact, unpolarised) at each texel's eta";
        t.attributes["method"] = res.method;
        t.attributes["samples"] = std::to_string(res.samples_per_cell);
        t.attributes["precision"] = precision_name(r.precision);
        if (r.tolerance.tolerance > 0.0) {
            std::ostringstream tol;
            tol << r.tolerance.tolerance;
            t.attributes["tolerance"] = tol.str();
        }
        return t;
    }

    if (r.kind == "conductor" && rgb_default(r)) {
        t.quantity = "Fresnel-weighted directional albedo E(mu_o, alpha) of a measured conductor at 650, 550 and 450 nm";
        t.channels = {"R", "G", "B"};
        t.error.assign(cells.size(), 0.0);
        std::string fresnel_text;
        AlbedoResult last;
        for (int c = 0; c < 3; ++c) {
            const FresnelConfig fc = resolve_fresnel(r.fresnel, kRgbNm[c]);
            last = integrate(engine, r, m, fc, cells);
            std::vector<double> v;
            for (size_t k = 0; k < cells.size(); ++k) {
                v.push_back(last.values[k].value);
                t.error[k] = std::max(t.error[k], last.values[k].error);
            }
            t.values.push_back(v);
            fresnel_text += std::string(c ? "; " : "") + kRgbNames[c] + ": " + fc.canonical;
        }
        describe(t, r, m, fresnel_text, last, clamped);
        return t;
    }

    if (r.kind == "albedo" || r.kind == "conductor") {
        t.quantity = r.kind == "albedo" ? "directional albedo E(mu_o, alpha) = integral of f(wo, wi) cos(theta_i) dwi"
                                        : "Fresnel-weighted directional albedo E(mu_o, alpha) of a conductor";
        const AlbedoResult res = integrate(engine, r, m, f, cells);
        t.channels = {"E"};
        t.values.assign(1, {});
        for (const auto& v : res.values) {
            t.values[0].push_back(v.value);
            t.error.push_back(v.error);
        }
        describe(t, r, m, f.canonical, res, clamped);
        return t;
    }

    // Split-sum terms: E with F = 1 and B with F = (1 - wo.wh)^5 (Schlick with f0 = 0); A = E - B.
    const AlbedoResult e = integrate(engine, r, m, resolve_fresnel("none"), cells, 0.5);
    const AlbedoResult b = integrate(engine, r, m, resolve_fresnel("schlick:f0=0"), cells, 0.5);
    std::vector<double> va, vb, ve;
    for (size_t i = 0; i < cells.size(); ++i) {
        ve.push_back(e.values[i].value);
        vb.push_back(b.values[i].value);
        va.push_back(e.values[i].value - b.values[i].value);
        t.error.push_back(e.values[i].error + b.values[i].error);
    }
    if (r.kind == "dfg") {
        t.quantity = "split-sum terms: A = integral of (f/F)(1 - (1 - wo.wh)^5) cos, B = integral of (f/F)(1 - wo.wh)^5 cos; "
                     "specular = F0 A + B";
        t.channels = {"A", "B"};
        t.values = {va, vb};
    } else {
        t.quantity = "split-sum terms, multiple-scattering layout: B = integral of (f/F)(1 - wo.wh)^5 cos and "
                     "E = A + B; F_ss = mix(B, E, f0), energy compensation 1 + f0 (1/E - 1)";
        t.channels = {"B", "E"};
        t.values = {vb, ve};
    }
    describe(t, r, m, "factored out (split sum)", e, clamped);
    return t;
}

}  // namespace brdfbake

// Spec parsing and the model registry: which models exist, their keys, ranges and defaults,
// and how their parameters map onto the slots of the shared headers.
#include "brdfbake/spec.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "models/key_reader.h"

namespace brdfbake {

Spec parse_spec(const std::string& text) {
    Spec spec;
    const size_t colon = text.find(':');
    spec.name = text.substr(0, colon);
    if (spec.name.empty()) throw Error("empty spec '" + text + "': expected name:key=value,...");
    if (colon == std::string::npos) return spec;
    const std::string rest = text.substr(colon + 1);
    size_t start = 0;
    while (start <= rest.size()) {
        size_t comma = rest.find(',', start);
        if (comma == std::string::npos) comma = rest.size();
        const std::string item = rest.substr(start, comma - start);
        const size_t eq = item.find('=');
        if (item.empty() || eq == std::string::npos || eq == 0 || eq + 1 == item.size())
            throw Error("malformed spec '" + text + "': '" + item + "' is not key=value");
        const std::string key = item.substr(0, eq);
        for (const auto& kv : spec.keys)
            if (kv.first == key) throw Error("spec '" + text + "' gives key '" + key + "' twice");
        spec.keys.emplace_back(key, item.substr(eq + 1));
        start = comma + 1;
    }
    return spec;
}

double parse_number(const std::string& text, const std::string& what) {
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (text.empty() || end != begin + text.size())
        throw Error(what + ": '" + text + "' is not a number");
    if (!std::isfinite(v) || errno == ERANGE)
        throw Error(what + ": '" + text + "' is not a finite number");
    return v;
}

namespace {

constexpr Range kPositive{0.0, 1e300, true};
constexpr Range kAlpha{BB_ALPHA_MIN, 10.0};
constexpr Range kRoughness{0.01, 3.1622776601683795};  // roughness^2 within kAlpha

constexpr Range kExponent{0.0, 1e4};         // Phong/Blinn exponents: finite in float up to 1e4
constexpr Range kSpecular{0.0, 1e4};         // ks (phong-original needs (n+1)/2pi for n = 1e4)
constexpr Range kSigma{0.0, 1.5707963267948966};  // Oren-Nayar slope-angle deviation, radians
constexpr Range kEta{0.0, 1e3, true};        // relative index of refraction

/// The separator before the next key of a canonical spec: ':' after the bare name, ',' later.
std::string sep(const std::string& canonical) {
    return canonical.find(':') == std::string::npos ? ":" : ",";
}

/// A key value for a canonical spec: integers as integers ("20", not "2e+01").
std::string fmt(double v) {
    if (v == std::floor(v) && std::fabs(v) < 1e15) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.0f", v);
        return buf;
    }
    return format_number(v);
}

/// Reads normalized=0|1 of the Phong-type lobes.
double read_normalized(KeyReader& keys, std::string& canonical) {
    const std::string s = keys.choice("normalized", "0", {"0", "1"});
    canonical += ",normalized=" + s;
    return s == "1" ? 1.0 : 0.0;
}

/// Reads the Smith shadowing choice shared by the microfacet models.
double read_shadowing(KeyReader& keys, std::string& canonical) {
    const std::string s = keys.choice("shadowing", "correlated", {"correlated", "separable"});
    canonical += ",shadowing=" + s;
    return s == "correlated" ? 1.0 : 0.0;
}

/// Reads alpha (isotropic: alpha or roughness; anisotropic: alpha_x and alpha_y).
void read_alpha(KeyReader& keys, ModelConfig& m, int slot_x, int slot_y) {
    const bool iso = keys.has("alpha") || keys.has("roughness");
    const bool aniso = keys.has("alpha_x") || keys.has("alpha_y");
    if (iso && aniso)
        throw Error("model '" + keys.name() + "': give either alpha (or roughness) or alpha_x and alpha_y, not both");
    if (keys.has("alpha") && keys.has("roughness"))
        throw Error("model '" + keys.name() + "': give alpha or roughness (alpha = roughness^2), not both");
    double ax, ay;
    if (aniso) {
        ax = keys.required_number("alpha_x", kAlpha, "anisotropic roughness along x");
        ay = keys.required_number("alpha_y", kAlpha, "anisotropic roughness along y");
        m.canonical += sep(m.canonical) + "alpha_x=" + format_number(ax) + ",alpha_y=" + format_number(ay);
        m.anisotropic = ax != ay;
    } else {
        if (auto r = keys.optional_number("roughness", kRoughness)) {
            ax = *r * *r;
        } else {
            ax = keys.required_number("alpha", kAlpha, "or roughness=R with alpha = R^2");
        }
        ay = ax;
        m.canonical += sep(m.canonical) + "alpha=" + format_number(ax);
    }
    m.params[slot_x] = ax;
    m.params[slot_y] = ay;
}

ModelConfig resolve_lambert(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_LAMBERT;
    const double rho = keys.number("rho", 1.0, {0.0, 1e6});
    m.params[BB_LAMBERT_RHO] = rho;
    m.canonical = "lambert:rho=" + format_number(rho);
    return m;
}

ModelConfig resolve_ggx(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_GGX;
    m.uses_fresnel = true;
    m.canonical = "ggx";
    read_alpha(keys, m, BB_GGX_ALPHA_X, BB_GGX_ALPHA_Y);
    m.params[BB_GGX_SHADOWING] = read_shadowing(keys, m.canonical);
    return m;
}

ModelConfig resolve_oren_nayar(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_OREN_NAYAR;
    const double sigma = keys.required_number("sigma", kSigma, "facet slope deviation in radians");
    const double rho = keys.number("rho", 1.0, {0.0, 1e6});
    m.params[BB_OREN_NAYAR_SIGMA] = sigma;
    m.params[BB_OREN_NAYAR_RHO] = rho;
    m.canonical = "oren-nayar:sigma=" + format_number(sigma) + ",rho=" + format_number(rho);
    return m;
}

ModelConfig resolve_phong(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_PHONG;
    const double n = keys.required_number("n", kExponent, "the lobe exponent");
    const double ks = keys.number("ks", 1.0, kSpecular);
    m.params[BB_PHONG_N] = n;
    m.params[BB_PHONG_KS] = ks;
    m.canonical = "phong:n=" + fmt(n) + ",ks=" + format_number(ks);
    m.params[BB_PHONG_NORMALIZED] = read_normalized(keys, m.canonical);
    return m;
}

ModelConfig resolve_phong_original(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_PHONG_ORIGINAL;
    const double n = keys.required_number("n", kExponent, "the lobe exponent");
    const double ks = keys.number("ks", 1.0, kSpecular);
    m.params[BB_PHONG_N] = n;
    m.params[BB_PHONG_KS] = ks;
    m.canonical = "phong-original:n=" + fmt(n) + ",ks=" + format_number(ks);
    return m;
}

ModelConfig resolve_blinn_phong(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_BLINN_PHONG;
    const double n = keys.required_number("n", kExponent, "the lobe exponent");
    const double ks = keys.number("ks", 1.0, kSpecular);
    m.params[BB_BLINN_PHONG_N] = n;
    m.params[BB_BLINN_PHONG_KS] = ks;
    m.canonical = "blinn-phong:n=" + fmt(n) + ",ks=" + format_number(ks);
    m.params[BB_BLINN_PHONG_NORMALIZED] = read_normalized(keys, m.canonical);
    return m;
}

ModelConfig resolve_torrance_sparrow(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_TORRANCE_SPARROW;
    m.uses_fresnel = true;
    const std::string d = keys.choice("d", "beckmann", {"blinn", "beckmann", "ggx"});
    m.canonical = "torrance-sparrow:d=" + d;
    if (d == "blinn") {
        if (keys.has("alpha") || keys.has("roughness") || keys.has("alpha_x") || keys.has("alpha_y"))
            throw Error("model 'torrance-sparrow': d=blinn takes the exponent n=N, not alpha");
        const double n = keys.required_number("n", kExponent, "the Blinn exponent of d=blinn");
        m.params[BB_TORRANCE_SPARROW_DIST] = BB_TS_D_BLINN;
        m.params[BB_TORRANCE_SPARROW_N] = n;
        m.canonical += ",n=" + fmt(n);
    } else {
        if (keys.has("n")) throw Error("model 'torrance-sparrow': d=" + d + " takes alpha=A, not the exponent n");
        m.params[BB_TORRANCE_SPARROW_DIST] = d == "beckmann" ? BB_TS_D_BECKMANN : BB_TS_D_GGX;
        read_alpha(keys, m, BB_TORRANCE_SPARROW_ALPHA_X, BB_TORRANCE_SPARROW_ALPHA_Y);
    }
    return m;
}

ModelConfig resolve_beckmann(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_BECKMANN;
    m.uses_fresnel = true;
    m.canonical = "beckmann";
    read_alpha(keys, m, BB_BECKMANN_ALPHA_X, BB_BECKMANN_ALPHA_Y);
    m.params[BB_BECKMANN_SHADOWING] = read_shadowing(keys, m.canonical);
    return m;
}

ModelConfig resolve_mirror(KeyReader&) {
    ModelConfig m;
    m.id = BB_MODEL_MIRROR;
    m.uses_fresnel = true;  // albedo = F(mu) of --fresnel
    m.canonical = "mirror";
    return m;
}

ModelConfig resolve_dielectric_specular(KeyReader& keys) {
    ModelConfig m;
    m.id = BB_MODEL_DIELECTRIC_SPECULAR;
    const double eta = keys.required_number("eta", kEta, "relative index of refraction, e.g. 1.5");
    m.params[BB_DIELECTRIC_SPECULAR_ETA] = eta;
    m.canonical = "dielectric-specular:eta=" + format_number(eta);
    return m;
}

struct ModelEntry {
    const char* name;
    std::function<ModelConfig(KeyReader&)> resolve;
};

const std::vector<ModelEntry>& registry() {
    static const std::vector<ModelEntry> entries = {
        {"lambert", resolve_lambert},
        {"ggx", resolve_ggx},
        {"beckmann", resolve_beckmann},
        {"oren-nayar", resolve_oren_nayar},
        {"phong", resolve_phong},
        {"phong-original", resolve_phong_original},
        {"blinn-phong", resolve_blinn_phong},
        {"torrance-sparrow", resolve_torrance_sparrow},
        {"mirror", resolve_mirror},
        {"dielectric-specular", resolve_dielectric_specular},
    };
    return entries;
}

}  // namespace

std::vector<std::string> model_names() {
    std::vector<std::string> names;
    for (const auto& e : registry()) names.push_back(e.name);
    return names;
}

ModelConfig resolve_model(const std::string& text) {
    const Spec spec = parse_spec(text);
    for (const auto& e : registry()) {
        if (spec.name != e.name) continue;
        KeyReader keys(spec, "model");
        ModelConfig m = e.resolve(keys);
        keys.finish();
        m.name = e.name;
        return m;
    }
    std::string list;
    for (const auto& n : model_names()) list += (list.empty() ? "" : ", ") + n;
    throw Error("unknown model '" + spec.name + "'; known models: " + list);
}

}  // namespace brdfbake

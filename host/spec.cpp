// Spec parsing and the model registry: which models exist, their keys, ranges and defaults,
// and how their parameters map onto the slots of the shared headers.
#include "brdfbake/spec.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "key_reader.h"

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
        m.canonical += ":alpha_x=" + format_number(ax) + ",alpha_y=" + format_number(ay);
        m.anisotropic = ax != ay;
    } else {
        if (auto r = keys.optional_number("roughness", kRoughness)) {
            ax = *r * *r;
        } else {
            ax = keys.required_number("alpha", kAlpha, "or roughness=R with alpha = R^2");
        }
        ay = ax;
        m.canonical += ":alpha=" + format_number(ax);
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

struct ModelEntry {
    const char* name;
    std::function<ModelConfig(KeyReader&)> resolve;
};

const std::vector<ModelEntry>& registry() {
    static const std::vector<ModelEntry> entries = {
        {"lambert", resolve_lambert},
        {"ggx", resolve_ggx},
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

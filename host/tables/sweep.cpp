#include "tables/sweep.h"

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"

namespace brdfbake {

std::vector<int> sweep_slots(const ModelConfig& m) {
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

ModelConfig sweep_model(const std::string& spec_text) {
    const Spec spec = parse_spec(spec_text);
    ModelConfig m = resolve_model(spec_text + (spec.keys.empty() && spec_text.find(':') == std::string::npos ? ":" : ",") +
                                  "alpha=0.5");
    sweep_slots(m);
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

std::optional<ModelConfig> try_sweep_model(const std::string& spec_text) {
    try {
        return sweep_model(spec_text);
    } catch (const Error&) {
        return std::nullopt;
    }
}

}  // namespace brdfbake

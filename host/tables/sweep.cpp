#include "tables/sweep.h"

#include "brdfbake/error.h"

namespace brdfbake {

ModelConfig sweep_model(const std::string& spec_text, bool simulated) {
    const Spec spec = parse_spec(spec_text);
    const std::string text =
        spec_text + (spec.keys.empty() && spec_text.find(':') == std::string::npos ? ":" : ",") + "alpha=0.5";
    ModelConfig m = simulated ? resolve_model_simulated(text) : resolve_model(text);
    roughness_slots(m);
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

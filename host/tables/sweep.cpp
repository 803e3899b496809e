#include "tables/sweep.h"

#include "brdfbake/error.h"
#include "models/key_reader.h"

namespace brdfbake {

ModelConfig sweep_model(const std::string& spec_text, bool simulated) {
    const Spec spec = parse_spec(spec_text);
    // The placeholder in the key the model's roughness axis drives (alpha, or oren-nayar's sigma
    // and the Phong lobes' n at alpha = 0.5: RoughnessAxis).
    const RoughnessAxis axis = roughness_axis_of_spec(spec_text);
    if (!axis.key) roughness_slots(resolve_model(spec_text));  // names the unknown model, or that it has no roughness
    const std::string key = axis.key ? axis.key : "alpha";
    const std::string text = spec_text + (spec.keys.empty() && spec_text.find(':') == std::string::npos ? ":" : ",") +
                             key + "=" + format_number(axis.value ? axis.value(0.5) : 0.5);
    ModelConfig m = simulated ? resolve_model_simulated(text) : resolve_model(text);
    roughness_slots(m);
    // Canonical spec without the placeholder: the key's token, whatever its spelling.
    const size_t colon = m.canonical.find(':');
    if (colon != std::string::npos) {
        std::string rest = m.canonical.substr(colon + 1), kept;
        size_t b = 0;
        while (b <= rest.size()) {
            size_t e = rest.find(',', b);
            if (e == std::string::npos) e = rest.size();
            const std::string token = rest.substr(b, e - b);
            if (token.rfind(key + "=", 0) != 0) kept += (kept.empty() ? "" : ",") + token;
            b = e + 1;
        }
        m.canonical = m.canonical.substr(0, colon) + (kept.empty() ? "" : ":" + kept);
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

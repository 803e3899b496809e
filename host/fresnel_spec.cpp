// The Fresnel registry: which Fresnel terms exist, their keys and ranges.
#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "key_reader.h"

namespace brdfbake {

FresnelConfig resolve_fresnel(const std::string& text, double wavelength_nm) {
    (void)wavelength_nm;  // used by measured metals
    const Spec spec = parse_spec(text);
    KeyReader keys(spec, "Fresnel");
    FresnelConfig f;
    if (spec.name == "none") {
        f.kind = BB_FRESNEL_NONE;
        f.canonical = "none";
    } else if (spec.name == "schlick") {
        f.kind = BB_FRESNEL_SCHLICK;
        const double f0 = keys.required_number("f0", {0.0, 1.0}, "reflectance at normal incidence");
        f.params[BB_SCHLICK_F0] = f0;
        f.canonical = "schlick:f0=" + format_number(f0);
    } else {
        throw Error("unknown Fresnel term '" + spec.name + "'; known: none, schlick");
    }
    keys.finish();
    return f;
}

}  // namespace brdfbake

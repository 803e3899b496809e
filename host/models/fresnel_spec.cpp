// The Fresnel registry: which Fresnel terms exist, their keys, ranges and defaults, and what each
// means; the help texts, the "known:" message and the canonical specs are generated from it
// (docs/fresnel.md lists the same terms; tests/test_fresnel.cpp holds the two together).
#include <cmath>
#include <cstdio>
#include <limits>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/spec.h"
#include "models/key_reader.h"
#include "models/nk_data.h"
#include "models/params.h"

namespace brdfbake {

namespace {

// eta is a ratio of indices: positive. The upper bounds keep every shared-math expression far
// from float overflow (see the edge-case policy in brdf/fresnel.h).
constexpr Range kEta{0.0, kMaxOpticalConstant, true};
constexpr Range kExtinction{0.0, kMaxOpticalConstant};
constexpr Range kReflectance{0.0, 1.0};
// The index whose dielectric curve drives gen-schlick-ior: >= 1.
constexpr Range kEtaAboveOne{1.0, kMaxOpticalConstant};

// The generalized Schlick exponent: 0 (F = f90 everywhere) to far beyond Cycles' largest table
// texel (exponent 5 (1 - z)/z at z = 1e-4: about 5e4).
constexpr Range kSchlickExponent{0.0, 1e6};

// A film's thickness in nanometres: 0 (the bare substrate) to 100 micrometres, far beyond the
// coherence length of daylight (about 1 micrometre), where interference averages out.
constexpr Range kFilmThickness{0.0, 1e5};

constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();

/// A key of a Fresnel term: its value goes to params[slot] (-1: only the term's derive hook reads
/// it); a required key has fallback kRequired, its hint in the message when it is missing.
struct FresnelKey {
    const char* key;
    const char* placeholder;  // in the spec form: schlick:f0=F0
    double fallback;
    Range range;
    const char* hint;
    int slot;
};

/// A registry entry. A term with keys is read as name:key=value,...; a measured term (load set)
/// as name:ARGUMENT, the exact conductor at the tabulated n, k of --wavelength.
struct FresnelEntry {
    FresnelTerm term;  // name, form, description, measured, kind (form filled in from the keys)
    std::vector<FresnelKey> keys;
    /// Sets the slots that follow from the keys (their values in key order) and checks the
    /// combination; nullptr: none.
    void (*derive)(FresnelConfig& f, const std::vector<double>& keys) = nullptr;
    /// Measured terms: loads the table the argument names, and says what the argument is.
    NkTable (*load)(const std::string& argument) = nullptr;
    const char* argument_needed = nullptr;  // "a metal, e.g. metal:Al"
    /// A term with keys whose F depends on the wavelength (thin-film): the slot --wavelength NM
    /// fills; -1: none.
    int wavelength_slot = -1;
};

/// eta - 1 beside eta: exact here, which a float kernel could not recover from eta.
void dielectric_eta_m1(FresnelConfig& f, const std::vector<double>& keys) {
    f.params[BB_FRESNEL_ETA_M1] = keys[0] - 1.0;
}
void gen_schlick_ior_eta_m1(FresnelConfig& f, const std::vector<double>& keys) {
    f.params[BB_GEN_SCHLICK_IOR_ETA_M1] = keys[2] - 1.0;
}

/// F82-tint [Kutz et al. 2021, "Novel aspects of the Adobe Standard Material"; the OpenPBR Surface
/// specification, metal]: Schlick's F(mu) with f0 less b mu (1 - mu)^6, b chosen so that F at
/// mu_bar = 1/7 (about 82 degrees) is tint times Schlick's value there:
///   b = (1 - tint) F_schlick(mu_bar) / (mu_bar (1 - mu_bar)^6).
/// As the term is not clamped (so that tables stay linear in f0 and b), a pair whose F dips below 0
/// is rejected (small f0 with a dark tint: F82-tint is a metal's Fresnel).
void f82_tint(FresnelConfig& f, const std::vector<double>& keys) {
    const double f0 = keys[0], tint = keys[1];
    const double b = bb_f82_tint_b(f0, tint);
    f.params[BB_GEN_SCHLICK_F0] = f0;
    f.params[BB_GEN_SCHLICK_F90] = 1.0;
    f.params[BB_GEN_SCHLICK_EXPONENT] = 5.0;
    f.params[BB_GEN_SCHLICK_B] = b;
    double lowest = 1.0, at = 0.0;
    for (int i = 0; i <= 4000; ++i) {
        const double mu = i / 4000.0, v = bb_fresnel_gen_schlick(mu, f0, 1.0, 5.0, b);
        if (v < lowest) lowest = v, at = mu;
    }
    if (lowest < 0.0)
        throw Error("Fresnel f82-tint:f0=" + format_number(f0) + ",tint=" + format_number(tint) + " goes below 0 (F = " +
                    format_number(lowest) + " at cos " + format_number(at) +
                    "); F82-tint describes metals: raise f0 or tint");
}

/// The wavelength a term that depends on it is evaluated at: --wavelength NM, checked.
double checked_wavelength(double wavelength_nm, const std::string& what, const std::string& range) {
    if (wavelength_nm == 0.0) throw Error("Fresnel '" + what + "' needs --wavelength NM" + range);
    if (!std::isfinite(wavelength_nm) || !(wavelength_nm > 0.0))
        throw Error("--wavelength must be a positive number of nanometres, got " + format_number(wavelength_nm));
    return wavelength_nm;
}

/// " at 550 nm": the wavelength as a canonical spec names it (550, not format_number's 5.5e+02).
std::string at_wavelength(double wavelength_nm) {
    char nm[32];
    std::snprintf(nm, sizeof nm, "%.10g", wavelength_nm);
    return std::string(" at ") + nm + " nm";
}

/// A measured material at one wavelength: the exact conductor with the interpolated n, k.
FresnelConfig measured(const NkTable& table, const std::string& what, double wavelength_nm) {
    checked_wavelength(wavelength_nm, what,
                       " (its tabulated n,k cover " + format_number(table.min_nm()) + " to " +
                           format_number(table.max_nm()) + " nm)");
    const NkValue v = interpolate_nk(table, wavelength_nm);
    FresnelConfig f;
    f.kind = BB_FRESNEL_CONDUCTOR;
    f.params[BB_FRESNEL_ETA] = v.n;
    f.params[BB_FRESNEL_K] = v.k;
    f.canonical = what + at_wavelength(wavelength_nm) + " = conductor:eta=" + format_number(v.n) +
                  ",k=" + format_number(v.k);
    return f;
}

std::string metal_argument() {
    std::string names;
    for (const auto& n : nk_preset_names()) names += (names.empty() ? "" : "|") + n;
    return names;
}

const std::vector<FresnelEntry>& registry() {
    static const std::vector<FresnelEntry> entries = [] {
        const char* f0_hint = "reflectance at normal incidence";
        std::vector<FresnelEntry> e = {
            {{"none", "", "F = 1", false, BB_FRESNEL_NONE}, {}},
            {{"schlick", "", "Schlick 1994: F0 + (1 - F0)(1 - cos theta)^5", false, BB_FRESNEL_SCHLICK},
             {{"f0", "F0", kRequired, kReflectance, f0_hint, BB_SCHLICK_F0}}},
            {{"gen-schlick", "",
              "generalized Schlick (Hoffman 2019): F0 + (F90 - F0)(1 - cos theta)^P; f90 1 and exponent 5 by default",
              false, BB_FRESNEL_GEN_SCHLICK},
             {{"f0", "F0", kRequired, kReflectance, f0_hint, BB_GEN_SCHLICK_F0},
              {"f90", "F90", 1.0, kReflectance, "", BB_GEN_SCHLICK_F90},
              {"exponent", "P", 5.0, kSchlickExponent, "", BB_GEN_SCHLICK_EXPONENT}}},
            {{"gen-schlick-ior", "",
              "Cycles' generalized Schlick driven by the dielectric curve of eta >= 1; f90 1 by default", false, BB_FRESNEL_GEN_SCHLICK_IOR},
             {{"f0", "F0", kRequired, kReflectance, f0_hint, BB_GEN_SCHLICK_F0},
              {"f90", "F90", 1.0, kReflectance, "", BB_GEN_SCHLICK_F90},
              {"eta", "E", kRequired, kEtaAboveOne, "index whose dielectric curve drives F, >= 1",
               BB_GEN_SCHLICK_IOR_ETA}},
             gen_schlick_ior_eta_m1},
            {{"f82-tint", "", "F82-tint (Kutz et al. 2021): Schlick less b cos theta (1 - cos theta)^6, F(82 deg) = "
                              "tint times Schlick's",
              false, BB_FRESNEL_GEN_SCHLICK},
             {{"f0", "F0", kRequired, kReflectance, f0_hint, -1},
              {"tint", "T", kRequired, kReflectance, "F at 82 deg relative to Schlick's", -1}},
             f82_tint},
            {{"dielectric", "", "exact dielectric, relative index eta (1.5: glass seen from air)", false, BB_FRESNEL_DIELECTRIC},
             {{"eta", "E", kRequired, kEta, "relative index of refraction, e.g. 1.5", BB_FRESNEL_ETA}},
             dielectric_eta_m1},
            {{"conductor", "", "exact conductor with complex index eta + ik", false, BB_FRESNEL_CONDUCTOR},
             {{"eta", "E", kRequired, kEta, "real part of the complex index eta + ik", BB_FRESNEL_ETA},
              {"k", "K", kRequired, kExtinction, "extinction coefficient, imaginary part of the index", BB_FRESNEL_K}}},
            {{"conductor-approx", "", "the course notes' closed-form conductor approximation", false, BB_FRESNEL_CONDUCTOR_APPROX},
             {{"eta", "E", kRequired, kEta, "real part of the complex index eta + ik", BB_FRESNEL_ETA},
              {"k", "K", kRequired, kExtinction, "extinction coefficient, imaginary part of the index", BB_FRESNEL_K}}},
            {{"thin-film", "",
              "one film (index eta + ik, thickness in nm) on a substrate (base_eta + i base_k, or base=metal:X for a "
              "measured one) at --wavelength NM: "
              "the Airy sum of wave optics (Born & Wolf 1.6.4; Belcour & Barla 2017)",
              true, BB_FRESNEL_THIN_FILM},
             {{"eta", "E", kRequired, kEta, "the film's index, e.g. 1.33 for a soap film", BB_THIN_FILM_ETA},
              {"k", "K", 0.0, kExtinction, "", BB_THIN_FILM_K},
              {"thickness", "NM", kRequired, kFilmThickness, "the film's thickness in nanometres, e.g. 300",
               BB_THIN_FILM_THICKNESS},
              {"base_eta", "E", kRequired, kEta, "the substrate's index, real part (1.5: glass)", BB_THIN_FILM_BASE_ETA},
              {"base_k", "K", 0.0, kExtinction, "", BB_THIN_FILM_BASE_K}},
             nullptr, nullptr, nullptr, BB_THIN_FILM_WAVELENGTH},
            {{"metal", "metal:" + metal_argument(), "measured n, k of an embedded metal at --wavelength NM", true, BB_FRESNEL_CONDUCTOR},
             {}, nullptr, load_nk_preset,
             "a metal, e.g. metal:Al (known: Al, Au, Ag, Cu)"},
            {{"nk", "nk:FILE.yml", "tabulated n, k of a refractiveindex.info YAML file at --wavelength NM", true, BB_FRESNEL_CONDUCTOR},
             {}, nullptr, load_nk_file,
             "a file, e.g. nk:Al.yml (refractiveindex.info YAML)"},
        };
        for (FresnelEntry& entry : e) {
            if (!entry.term.form.empty()) continue;
            entry.term.form = entry.term.name;
            for (const FresnelKey& k : entry.keys)
                entry.term.form += std::string(&k == &entry.keys.front() ? ":" : ",") + k.key + "=" + k.placeholder;
        }
        return e;
    }();
    return entries;
}

/// The entry a spec names: its name before the colon.
const FresnelEntry* find_entry(const std::string& name) {
    for (const FresnelEntry& e : registry())
        if (e.term.name == name) return &e;
    return nullptr;
}

/// A term with keys: each key in the registry's order into its slot, the canonical spec
/// spelling every key.
FresnelConfig resolve_keys(const FresnelEntry& e, const Spec& spec) {
    KeyReader keys(spec, "Fresnel");
    FresnelConfig f;
    f.kind = e.term.kind;
    f.canonical = e.term.name;
    std::vector<double> values;
    for (const FresnelKey& k : e.keys) {
        const double v = std::isnan(k.fallback) ? keys.required_number(k.key, k.range, k.hint)
                                                : keys.number(k.key, k.fallback, k.range);
        if (k.slot >= 0) f.params[k.slot] = v;
        f.canonical += std::string(values.empty() ? ":" : ",") + k.key + "=" + format_number(v);
        values.push_back(v);
    }
    keys.finish();
    if (e.derive) e.derive(f, values);
    return f;
}

/// thin-film with base=metal:X (or nk:FILE): the substrate's n, k at the wavelength from that
/// measured term instead of base_eta and base_k; otherwise the keys as any term's.
FresnelConfig resolve_thin_film(const FresnelEntry& e, Spec spec, double wavelength_nm) {
    std::string base;
    for (auto it = spec.keys.begin(); it != spec.keys.end(); ++it)
        if (it->first == "base") {
            base = it->second;
            spec.keys.erase(it);
            break;
        }
    if (base.empty()) return resolve_keys(e, spec);
    for (const auto& kv : spec.keys)
        if (kv.first == "base_eta" || kv.first == "base_k")
            throw Error("Fresnel thin-film: base=" + base + " is the substrate; drop " + kv.first);
    const FresnelEntry* sub = find_entry(base.substr(0, base.find(':')));
    if (!sub || !sub->load)
        throw Error("Fresnel thin-film: base=" + base + " is not a measured term; base= takes metal:X (known: " +
                    metal_argument() + ") or nk:FILE, or give base_eta and base_k");
    spec.keys.emplace_back("base_eta", "1");  // replaced below by the measured substrate's
    FresnelConfig f = resolve_keys(e, spec);
    const FresnelConfig n = resolve_fresnel(base, wavelength_nm == 0.0 ? 550.0 : wavelength_nm);
    f.params[BB_THIN_FILM_BASE_ETA] = n.params[BB_FRESNEL_ETA];
    f.params[BB_THIN_FILM_BASE_K] = n.params[BB_FRESNEL_K];
    f.canonical = f.canonical.substr(0, f.canonical.find(",base_eta=")) + ",base=" + base + " (base_eta=" +
                  format_number(n.params[BB_FRESNEL_ETA]) + ",base_k=" + format_number(n.params[BB_FRESNEL_K]) + ")";
    return f;
}

std::vector<FresnelTerm> terms_of(const std::vector<FresnelEntry>& entries) {
    std::vector<FresnelTerm> terms;
    for (const FresnelEntry& e : entries) terms.push_back(e.term);
    return terms;
}

}  // namespace

const std::vector<FresnelTerm>& fresnel_terms() {
    static const std::vector<FresnelTerm> terms(terms_of(registry()));
    return terms;
}

std::string fresnel_spec_forms() {
    std::string forms;
    for (const FresnelTerm& t : fresnel_terms()) forms += (forms.empty() ? "" : ", ") + t.form;
    return forms;
}

std::string fresnel_kind_name(int kind) {
    for (const FresnelTerm& t : fresnel_terms())
        if (t.kind == kind) return t.name;
    return "unknown";
}

bool fresnel_needs_wavelength(const std::string& text) {
    const FresnelEntry* e = find_entry(text.substr(0, text.find(':')));
    return e && e->term.measured;
}

int fresnel_kind_of(const std::string& text) {
    const FresnelEntry* e = find_entry(text.substr(0, text.find(':')));
    return e ? e->term.kind : -1;
}

bool fresnel_reads_file(const std::string& text) {
    const FresnelEntry* e = find_entry(text.substr(0, text.find(':')));
    return e && e->load == load_nk_file;
}

FresnelConfig resolve_fresnel(const std::string& text, double wavelength_nm) {
    const std::string name = text.substr(0, text.find(':'));
    const FresnelEntry* e = find_entry(name);
    if (e && e->load) {
        // Measured data: the part after the colon is a symbol or a path, not key=value pairs.
        const std::string argument = name.size() < text.size() ? text.substr(name.size() + 1) : "";
        if (argument.empty()) throw Error("Fresnel '" + name + "' needs " + e->argument_needed);
        return measured(e->load(argument), text, wavelength_nm);
    }
    const Spec spec = parse_spec(text);
    e = find_entry(spec.name);
    if (!e) {
        std::vector<std::string> names;
        for (const FresnelEntry& entry : registry()) names.push_back(entry.term.name);
        throw Error(unknown_name_message("Fresnel term", spec.name, names, "known", fresnel_spec_forms()));
    }
    FresnelConfig f = e->term.kind == BB_FRESNEL_THIN_FILM ? resolve_thin_film(*e, spec, wavelength_nm)
                                                            : resolve_keys(*e, spec);
    if (e->wavelength_slot >= 0) {
        f.params[e->wavelength_slot] = checked_wavelength(wavelength_nm, e->term.name, "");
        f.canonical += at_wavelength(wavelength_nm);
    }
    return f;
}

double fresnel_value(const FresnelConfig& f, double cos_theta) {
    if (f.kind == BB_FRESNEL_TABLE) return bb_fresnel_table_at(cos_theta, int(f.curve.size()), f.curve.data());
    return bb_fresnel_eval(f.kind, to_bb_params(f.params), cos_theta);
}

std::function<FresnelConfig(double)> fresnel_over_wavelengths(const std::string& text) {
    const std::string name = text.substr(0, text.find(':'));
    const FresnelEntry* e = find_entry(name);
    if (e && e->load && name.size() < text.size()) {
        const NkTable table = e->load(text.substr(name.size() + 1));
        return [table, text](double nm) { return measured(table, text, nm); };
    }
    return [text](double nm) { return resolve_fresnel(text, nm); };
}

}  // namespace brdfbake

// Spec parsing and the host's side of the model registry (brdf/model_registry.h): each model's
// resolver resolve_<name> (its keys, ranges and defaults, and how its parameters map onto the
// slots of its header), and the traits of the registry's table as ModelTraits.
#include "brdfbake/spec.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <utility>
#include <vector>

#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/random_walk.h"
#include "brdfbake/brdf/sheen_volume.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/error.h"
#include "models/key_reader.h"
#include "models/merl_file.h"
#include "models/sheen_ltc_table.h"

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

/// Reads the Smith shadowing choice shared by the microfacet models (brdf/smith.h): correlated
/// (Heitz 2014 eq. 99), separable (eq. 98) or masking (G2 = G1(wo), the masking term of eq. 43
/// alone: the lobe of Cycles' albedo estimator, which ignores shadowing and so reflects more).
double read_shadowing(KeyReader& keys, std::string& canonical) {
    const std::string s = keys.choice("shadowing", "correlated", {"correlated", "separable", "masking"});
    canonical += ",shadowing=" + s;
    return s == "correlated" ? BB_SHADOWING_CORRELATED : s == "masking" ? BB_SHADOWING_MASKING : BB_SHADOWING_SEPARABLE;
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
    const double rho = keys.number("rho", 1.0, {0.0, 1e6});
    m.params[BB_LAMBERT_RHO] = rho;
    m.canonical = "lambert:rho=" + format_number(rho);
    return m;
}

/// Reads scattering=single|multiple, bounces=N and eta=E of the Smith lobes: multiple is the random
/// walk on the Smith microsurface (brdf/random_walk.h), whose first order is the height-correlated
/// lobe, so it takes shadowing=correlated only; bounces (default BB_WALK_DEFAULT_BOUNCES) is its
/// limit; eta makes it the rough dielectric interface of that relative index (reflection and
/// refraction at every bounce, bb_walk_dielectric), a conductor without it.
void read_scattering(KeyReader& keys, ModelConfig& m) {
    constexpr Range kWalkEta{0.01, 100.0};
    const std::string s = keys.choice("scattering", "single", {"single", "multiple"});
    if (s == "single") {
        if (keys.has("bounces")) throw Error("model '" + keys.name() + "': bounces=N needs scattering=multiple");
        if (keys.has("eta"))
            throw Error("model '" + keys.name() + "': eta=E (the rough dielectric's random walk) needs "
                        "scattering=multiple; the single-scattering dielectric is `brdfbake lut dielectric`");
        return;
    }
    if (m.params[m.smith_shadowing_slot] != BB_SHADOWING_CORRELATED)
        throw Error("model '" + keys.name() + "': scattering=multiple is the height-correlated Smith microsurface; "
                    "it takes shadowing=correlated only");
    const double n = keys.number("bounces", BB_WALK_DEFAULT_BOUNCES, {1.0, double(BB_WALK_MAX_BOUNCES)});
    if (n != std::floor(n)) throw Error("model '" + keys.name() + "': bounces=" + format_number(n) + " is not an integer");
    m.params[BB_SMITH_SCATTERING] = BB_SCATTERING_MULTIPLE;
    m.params[BB_SMITH_BOUNCES] = n;
    m.simulated = true;
    m.canonical += ",scattering=multiple,bounces=" + fmt(n);
    if (const auto eta = keys.optional_number("eta", kWalkEta)) {
        m.params[BB_SMITH_WALK_ETA] = *eta;
        m.params[BB_SMITH_WALK_ETA_M1] = *eta - 1.0;
        m.dielectric_walk = true;
        m.canonical += ",eta=" + format_number(*eta);
    }
}

// The microfacet lobes with a Smith shadowing choice: alpha in (slot_x, slot_y), the shadowing
// in shadowing_slot.
ModelConfig resolve_smith_microfacet(KeyReader& keys, const std::string& name, int slot_x, int slot_y,
                                     int shadowing_slot) {
    ModelConfig m;
    m.canonical = name;
    read_alpha(keys, m, slot_x, slot_y);
    m.params[shadowing_slot] = read_shadowing(keys, m.canonical);
    m.smith_shadowing_slot = shadowing_slot;
    read_scattering(keys, m);
    // diffuse=KD: a Lambert base kd/pi beside the lobe (brdf/smith.h, BB_SMITH_DIFFUSE)
    if (const auto kd = keys.optional_number("diffuse", {0.0, 1.0})) {
        if (m.simulated) throw Error("model '" + name + "': diffuse=KD is a sum with the single-scattering lobe; it takes scattering=single only");
        m.params[BB_SMITH_DIFFUSE] = *kd;
        m.canonical += ",diffuse=" + format_number(*kd);
    }
    return m;
}

// ggx also names how the rough dielectric (the dielectric table, brdf/rough_dielectric.h) shadows
// its transmitted lobe under height-correlated shadowing: transmission_shadowing=beta (Heitz 2014
// eq. 100, the default) or cycles (1/(1 + L_o + L_t), Blender Cycles' form), in a slot of its own
// (BB_GGX_TRANSMISSION_SHADOWING) that no reflection reads; the canonical spec names it only when
// it is not the default.
ModelConfig resolve_ggx(KeyReader& keys) {
    ModelConfig m = resolve_smith_microfacet(keys, "ggx", BB_GGX_ALPHA_X, BB_GGX_ALPHA_Y, BB_GGX_SHADOWING);
    const std::string t = keys.choice("transmission_shadowing", "beta", {"beta", "cycles"});
    m.params[BB_GGX_TRANSMISSION_SHADOWING] = BB_TRANSMISSION_SHADOWING_BETA;
    if (t == "cycles") {
        if (m.params[BB_GGX_SHADOWING] != BB_SHADOWING_CORRELATED)
            throw Error("model 'ggx': transmission_shadowing=cycles is a height-correlated form; it needs "
                        "shadowing=correlated, not shadowing=" +
                        std::string(m.params[BB_GGX_SHADOWING] == BB_SHADOWING_MASKING ? "masking" : "separable"));
        m.params[BB_GGX_TRANSMISSION_SHADOWING] = BB_TRANSMISSION_SHADOWING_CYCLES;
        m.canonical += ",transmission_shadowing=cycles";
    }
    return m;
}

ModelConfig resolve_oren_nayar(KeyReader& keys) {
    ModelConfig m;
    const double sigma = keys.required_number("sigma", kSigma, "facet slope deviation in radians");
    const double rho = keys.number("rho", 1.0, {0.0, 1e6});
    m.params[BB_OREN_NAYAR_SIGMA] = sigma;
    m.params[BB_OREN_NAYAR_RHO] = rho;
    m.canonical = "oren-nayar:sigma=" + format_number(sigma) + ",rho=" + format_number(rho);
    return m;
}

// The Phong-family lobes: the exponent n and the specular weight ks in the model's slots, and
// the normalization key where the model has a slot for it (normalized_slot >= 0).
ModelConfig resolve_phong_lobe(KeyReader& keys, const std::string& name, int n_slot, int ks_slot,
                               int normalized_slot) {
    ModelConfig m;
    const double n = keys.required_number("n", kExponent, "the lobe exponent");
    const double ks = keys.number("ks", 1.0, kSpecular);
    m.params[n_slot] = n;
    m.params[ks_slot] = ks;
    m.canonical = name + ":n=" + fmt(n) + ",ks=" + format_number(ks);
    if (normalized_slot >= 0) m.params[normalized_slot] = read_normalized(keys, m.canonical);
    return m;
}

ModelConfig resolve_phong(KeyReader& keys) {
    return resolve_phong_lobe(keys, "phong", BB_PHONG_N, BB_PHONG_KS, BB_PHONG_NORMALIZED);
}

ModelConfig resolve_phong_original(KeyReader& keys) {
    return resolve_phong_lobe(keys, "phong-original", BB_PHONG_N, BB_PHONG_KS, -1);
}

ModelConfig resolve_blinn_phong(KeyReader& keys) {
    return resolve_phong_lobe(keys, "blinn-phong", BB_BLINN_PHONG_N, BB_BLINN_PHONG_KS, BB_BLINN_PHONG_NORMALIZED);
}

ModelConfig resolve_torrance_sparrow(KeyReader& keys) {
    ModelConfig m;
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
    return resolve_smith_microfacet(keys, "beckmann", BB_BECKMANN_ALPHA_X, BB_BECKMANN_ALPHA_Y, BB_BECKMANN_SHADOWING);
}

ModelConfig resolve_mirror(KeyReader&) {
    ModelConfig m;
    m.canonical = "mirror";
    return m;
}

ModelConfig resolve_dielectric_specular(KeyReader& keys) {
    ModelConfig m;
    const double eta = keys.required_number("eta", kEta, "relative index of refraction, e.g. 1.5");
    m.params[BB_DIELECTRIC_SPECULAR_ETA] = eta;
    m.canonical = "dielectric-specular:eta=" + format_number(eta);
    return m;
}

// sheen: roughness=R (glTF's sheenRoughness, alpha = R^2) or alpha=A, and the visibility.
// The roughness is that of [EK17]'s fit, r in (0, 1]; the floor is the microfacet alpha floor,
// BB_ALPHA_MIN = 1e-4 (sheenRoughness 0.01), below which a table's texels are clamped as for
// the other microfacet lobes. The canonical spec spells alpha, as the other lobes' do, so that a
// table's roughness sweep (tables/sweep.h) can set it.
constexpr Range kSheenAlpha{BB_ALPHA_MIN, 1.0};
constexpr Range kSheenRoughness{0.01, 1.0};  // roughness^2 within kSheenAlpha

/// The alpha of a sheen spec (sheen, sheen-ltc): roughness=R (alpha = R^2) or alpha=A.
double read_sheen_alpha(KeyReader& keys, const std::string& model) {
    if (keys.has("alpha") && keys.has("roughness"))
        throw Error("model '" + model + "': give roughness (glTF's sheenRoughness) or alpha = roughness^2, not both");
    if (auto r = keys.optional_number("roughness", kSheenRoughness)) return *r * *r;
    return keys.required_number("alpha", kSheenAlpha, "or roughness=R, glTF's sheenRoughness, with alpha = R^2");
}

ModelConfig resolve_sheen(KeyReader& keys) {
    ModelConfig m;
    const double alpha = read_sheen_alpha(keys, "sheen");
    const std::string v = keys.choice("visibility", "charlie", {"charlie", "ashikhmin"});
    m.params[BB_SHEEN_ALPHA] = alpha;
    m.params[BB_SHEEN_VISIBILITY] = v == "charlie" ? BB_SHEEN_V_CHARLIE : BB_SHEEN_V_ASHIKHMIN;
    m.canonical = "sheen:alpha=" + format_number(alpha) + ",visibility=" + v;
    return m;
}

// merl: a measured file (Matusik et al. 2003, brdf/merl.h), one channel of it (r, g, b or
// Rec. 709 luminance y, the default) and its lookup (nearest, MERL's reader, the default; or
// linear). The file is read and validated here, once per process (models/merl_file.h).
ModelConfig resolve_merl(KeyReader& keys) {
    ModelConfig m;
    const auto file = keys.optional_string("file");
    if (keys.optional_string("channel").value_or("") == "rgb")
        throw Error("model 'merl': channel=rgb makes one table channel per colour (lut albedo, lut eavg); "
                    "elsewhere give one channel: r, g, b or y");
    const std::string channel = keys.choice("channel", "y", {"r", "g", "b", "y"});
    const std::string interp = keys.choice("interp", "linear", {"nearest", "linear"});
    if (!file) keys.finish();  // an unknown key (a misspelt file) is named first
    if (!file) throw Error("model 'merl' needs file=PATH, a MERL binary file (e.g. merl:file=gold-metallic-paint.binary)");
    const MerlChannel c = channel == "r" ? MerlChannel::R : channel == "g" ? MerlChannel::G
                          : channel == "b" ? MerlChannel::B : MerlChannel::Y;
    m.params[BB_MERL_TABLE] = merl_table_index(*file, c);
    m.params[BB_MERL_INTERP] = interp == "linear" ? BB_MERL_LINEAR : BB_MERL_NEAREST;
    m.params[BB_MERL_MIRROR] = interp == "linear" && merl_table_info(int(m.params[BB_MERL_TABLE])).mirror_symmetric;
    m.canonical = "merl:file=" + *file + ",channel=" + channel + ",interp=" + interp;
    return m;
}

// sheen-ltc: the LTC sheen (brdf/sheen_ltc.h), roughness=R or alpha=A (= R^2, the layer's sigma, as
// sheen's; the canonical spec spells alpha for a table's roughness sweep), and the table (a, b, R):
// table=FILE, a CSV of `lut sheen-ltc`, or the embedded default (data/sheen_ltc/).
ModelConfig resolve_sheen_ltc(KeyReader& keys) {
    ModelConfig m;
    const double alpha = read_sheen_alpha(keys, "sheen-ltc");
    const std::string file = keys.optional_string("table").value_or(kSheenLtcBuiltin);
    keys.finish();
    const SheenLtcTablePlace t = sheen_ltc_table(file);
    m.params[BB_SHEEN_LTC_ALPHA] = alpha;
    m.params[BB_SHEEN_LTC_OFFSET] = double(t.offset);
    m.params[BB_SHEEN_LTC_NX] = t.nx;
    m.params[BB_SHEEN_LTC_NY] = t.ny;
    m.canonical = "sheen-ltc:alpha=" + format_number(alpha) + (file == kSheenLtcBuiltin ? "" : ",table=" + file);
    return m;
}

// sheen-volume: the volumetric sheen layer of Zeltner, Burley and Chiang 2022 (brdf/sheen_volume.h)
// simulated, roughness=R or alpha=A (= R^2 = the fibers' sigma, as sheen-ltc's), bounces=N its
// walk's scattering limit. Always simulated: no pointwise f (brdf/sheen_volume_model.h).
ModelConfig resolve_sheen_volume(KeyReader& keys) {
    ModelConfig m;
    const double alpha = read_sheen_alpha(keys, "sheen-volume");
    const double n = keys.number("bounces", BB_SHEEN_VOLUME_DEFAULT_BOUNCES, {1.0, double(BB_SHEEN_VOLUME_MAX_BOUNCES)});
    if (n != std::floor(n)) throw Error("model 'sheen-volume': bounces=" + format_number(n) + " is not an integer");
    m.params[BB_SHEEN_VOLUME_MODEL_ALPHA] = alpha;
    m.params[BB_SHEEN_VOLUME_MODEL_BOUNCES] = n;
    m.simulated = true;
    m.canonical = "sheen-volume:alpha=" + format_number(alpha) + ",bounces=" + fmt(n);
    return m;
}

/// Torrance-Sparrow's roughness axis exists only for the distributions with an alpha.
const char* torrance_sparrow_roughness_refusal(const ParamBlock& params) {
    return params[BB_TORRANCE_SPARROW_DIST] == BB_TS_D_BLINN
               ? "torrance-sparrow with d=blinn has an exponent, not alpha, to sweep; use d=beckmann or d=ggx"
               : nullptr;
}

/// The hooks a few models add to their registry entry: roughness_refusal.
const char* (*roughness_refusal_of(int id))(const ParamBlock&) {
    return id == BB_MODEL_TORRANCE_SPARROW ? torrance_sparrow_roughness_refusal : nullptr;
}

/// The planner's cost per sample of the models whose samples cost more than 1.5x GGX's. Sheen,
/// measured on the development machine (benchmarks/results/plan-estimates-2c-shared.md): its 32x27
/// albedo at 65536 samples ran at 4.7e7 samples/s against GGX's 2.1e9 in idle-core seconds (the
/// Charlie distribution is sampled uniformly and its visibility term is costly).
double sample_cost_of(int id) { return id == BB_MODEL_SHEEN ? 45.0 : 1.0; }
/// The Phong lobes' exponent at a table alpha: n = 2/alpha^2 - 2, the exponent whose Blinn-Phong
/// distribution matches Beckmann's of width alpha (Walter, Marschner, Li and Torrance 2007,
/// "Microfacet Models for Refraction through Rough Surfaces", sec. 5.2: alpha_p = 2 alpha_b^-2 - 2);
/// n = 1e4 (kExponent's top) at alpha = sqrt(2/10002) = 0.01414, n = 0 at alpha = 1.
double phong_exponent_of_alpha(double alpha) { return std::max(0.0, 2.0 / (alpha * alpha) - 2.0); }

/// Oren-Nayar's sigma at a table alpha: sigma = alpha in radians (the slope-angle deviation of
/// [ON94], which Cycles' Oren-Nayar roughness and OpenPBR's base_diffuse_roughness take directly).
double oren_nayar_sigma_of_alpha(double alpha) { return alpha; }

constexpr const char* kPhongAxisText =
    "n = 2/alpha^2 - 2 (the exponent matched to Beckmann's alpha, Walter et al. 2007 sec. 5.2); "
    "alpha from 0.01414 (n = 1e4) to 1 (n = 0)";

/// The roughness axis of a registry row: its alpha slots, or the mapped keys of the models without
/// (a table, not a switch: one row per model that has one).
RoughnessAxis roughness_axis_of(int id, int alpha_slot) {
    if (alpha_slot >= 0) {
        RoughnessAxis a;
        a.key = "alpha";
        a.mapping = "alpha";
        a.alpha_lo = BB_ALPHA_MIN;
        a.alpha_hi = kAlpha.hi;
        a.slot = alpha_slot;
        return a;
    }
    static const double kPhongLo = std::sqrt(2.0 / (kExponent.hi + 2.0));
    static const std::vector<std::pair<int, RoughnessAxis>> mapped = {
        {BB_MODEL_OREN_NAYAR,
         {"sigma", "sigma = alpha (radians, the facet slope-angle deviation of Oren and Nayar 1994); alpha from 0 to pi/2",
          oren_nayar_sigma_of_alpha, kSigma.lo, kSigma.hi, BB_OREN_NAYAR_SIGMA}},
        {BB_MODEL_PHONG, {"n", kPhongAxisText, phong_exponent_of_alpha, kPhongLo, 1.0, BB_PHONG_N}},
        {BB_MODEL_PHONG_ORIGINAL, {"n", kPhongAxisText, phong_exponent_of_alpha, kPhongLo, 1.0, BB_PHONG_N}},
        {BB_MODEL_BLINN_PHONG, {"n", kPhongAxisText, phong_exponent_of_alpha, kPhongLo, 1.0, BB_BLINN_PHONG_N}},
    };
    for (const auto& e : mapped)
        if (e.first == id) return e.second;
    return {};
}

using Resolver = ModelConfig (*)(KeyReader&);

struct ModelEntry {
    ModelTraits traits;
    Resolver resolve;
};

#define BB_HOST_MODEL_ENTRY(NAME, name, SPEC, ARGS, QUAD, TRAITS, AX, AY, EX, EXAMPLE)                          \
    {ModelTraits{BB_MODEL_##NAME, SPEC, EXAMPLE, BB_USES_FRESNEL_##ARGS != 0,                                     \
                 BB_QUAD_SPACE_##QUAD == BB_QUAD_SPACE_HALFVECTOR, ((TRAITS) & BB_TRAIT_COSINE_SAMPLER) != 0,      \
                 ((TRAITS) & BB_TRAIT_DELTA) != 0, ((TRAITS) & BB_TRAIT_SAMPLES_DISK) != 0,                        \
                 ((TRAITS) & BB_TRAIT_SAMPLES_VECTOR) != 0, ((TRAITS) & BB_TRAIT_EVALS_VECTOR) != 0,               \
                 ((TRAITS) & BB_TRAIT_RECIPROCAL) != 0, AX, AY, EX, ((TRAITS) & BB_TRAIT_KINKED) != 0,             \
                 ((TRAITS) & BB_TRAIT_FURNACE) != 0, ((TRAITS) & BB_TRAIT_STOCHASTIC) != 0,                        \
                 ((TRAITS) & BB_TRAIT_MEASURED) != 0, ((TRAITS) & BB_TRAIT_DIFFUSE_KEY) != 0,                         \
                 ((TRAITS) & BB_TRAIT_LAYER_WALK) != 0,                                                            \
                 roughness_refusal_of(BB_MODEL_##NAME), sample_cost_of(BB_MODEL_##NAME),                            \
                 roughness_axis_of(BB_MODEL_##NAME, AX)},                                                           \
     resolve_##name},

const std::vector<ModelEntry>& registry() {
    static const std::vector<ModelEntry> entries = {BB_MODEL_REGISTRY(BB_HOST_MODEL_ENTRY)};
    return entries;
}

}  // namespace

const std::vector<ModelTraits>& model_registry() {
    static const std::vector<ModelTraits> traits = [] {
        std::vector<ModelTraits> t;
        for (const auto& e : registry()) t.push_back(e.traits);
        return t;
    }();
    return traits;
}

const ModelTraits& model_traits(int id) {
    for (const auto& e : registry())
        if (e.traits.id == id) return e.traits;
    throw Error("internal error: no model with id " + std::to_string(id));
}

std::vector<int> roughness_slots(const ModelConfig& model) {
    const ModelTraits& t = model.traits();
    if (!t.roughness_axis.key)
        throw Error("model '" + model.name + "' has no roughness alpha to sweep; tables need a model with a roughness "
                    "axis (alpha, oren-nayar's sigma or the Phong lobes' n)");
    if (t.roughness_refusal)
        if (const char* why = t.roughness_refusal(model.params)) throw Error(why);
    if (t.alpha_x_slot < 0) return {t.roughness_axis.slot};
    return {t.alpha_x_slot, t.alpha_y_slot};
}

ParamBlock with_roughness(const ModelConfig& model, ParamBlock params, double alpha) {
    const RoughnessAxis& axis = model.traits().roughness_axis;
    const double v = axis.value ? axis.value(alpha) : alpha;
    for (int s : roughness_slots(model)) params[size_t(s)] = v;
    return params;
}

RoughnessAxis roughness_axis_of_spec(const std::string& spec_text) {
    const std::string name = parse_spec(spec_text).name;
    for (const auto& e : registry())
        if (name == e.traits.name) return e.traits.roughness_axis;
    return {};
}

std::vector<std::string> model_names() {
    std::vector<std::string> names;
    for (const auto& e : registry()) names.push_back(e.traits.name);
    return names;
}

ModelConfig resolve_model(const std::string& text) {
    ModelConfig m = resolve_model_simulated(text);
    if (m.simulated && m.traits().layer_walk)
        throw Error("model '" + m.name +
                    "' is a random walk through a volumetric layer (Zeltner et al. 2022): f has no pointwise value; "
                    "albedo, check, lobe and lut albedo (Python: lut) take it, this command does not (sheen-ltc is its "
                    "pointwise fit)");
    if (m.simulated)
        throw Error("model '" + m.name +
                    "': scattering=multiple (a random-walk estimate) is supported by albedo, check, lobe (plane and 3d), "
                    "lut albedo and compensation; this command does not support it");
    return m;
}

ModelConfig resolve_model_simulated(const std::string& text) {
    const Spec spec = parse_spec(text);
    for (const auto& e : registry()) {
        if (spec.name != e.traits.name) continue;
        KeyReader keys(spec, "model");
        ModelConfig m = e.resolve(keys);
        keys.finish();
        m.id = e.traits.id;
        m.name = e.traits.name;
        m.uses_fresnel = e.traits.uses_fresnel && !m.dielectric_walk;  // the walk's own exact dielectric F
        return m;
    }
    std::string list;
    for (const auto& n : model_names()) list += (list.empty() ? "" : ", ") + n;
    throw Error(unknown_name_message("model", spec.name, model_names(), "known models", list));
}

}  // namespace brdfbake

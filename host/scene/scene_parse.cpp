// Scene files (JSON): materials, their lobes and the settings. Which tables a lobe needs is
// needs.cpp; the glTF reader is gltf_scene.cpp; the planner is planner.cpp.
#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/version.h"
#include "models/input_file.h"
#include "models/key_reader.h"
#include "models/merl_file.h"
#include "scene/json_read.h"
#include "scene/scene_text.h"
#include "tables/lut_common.h"
#include "tables/sweep.h"

namespace brdfbake {

namespace {

using json = nlohmann::json;
using scene_text::is_conductor_fresnel;

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// --- reading JSON values with messages that name the file, the material and the key ---------------

struct Where {
    std::string file;
    std::string what;  // "material 'gold'" or "settings"
    std::string at(const std::string& key) const { return "scene '" + file + "': " + what + ": '" + key + "'"; }
};

const char* type_name(const json& v) { return v.type_name(); }

double number_at(const json& v, const Where& w, const std::string& key) {
    if (!v.is_number()) throw Error(w.at(key) + " must be a number, not " + type_name(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) throw Error(w.at(key) + " is not a finite number");
    return x;
}

std::string string_at(const json& v, const Where& w, const std::string& key) {
    if (!v.is_string()) throw Error(w.at(key) + " must be a string, not " + type_name(v));
    return v.get<std::string>();
}

/// A number or a [lo, hi] pair.
Interval interval_at(const json& v, const Where& w, const std::string& key) {
    if (v.is_number()) {
        const double x = number_at(v, w, key);
        return {x, x};
    }
    if (v.is_array() && v.size() == 2) {
        const double lo = number_at(v[0], w, key), hi = number_at(v[1], w, key);
        if (lo > hi) throw Error(w.at(key) + " range [" + format_number(lo) + ", " + format_number(hi) + "] has lo > hi");
        return {lo, hi};
    }
    throw Error(w.at(key) + " must be a number or a [lo, hi] pair");
}

// --- lobes --------------------------------------------------------------------------------------

// A model spec split into the part that is the same for every texel of a table (model name and
// keys such as shadowing) and the roughness it was given with.
struct SweepSplit {
    ModelConfig base;               // resolved with a placeholder alpha (or as given, no alpha)
    std::string canonical;          // canonical spec without alpha
    bool sweepable = false;         // the model has an alpha that tables sweep
    std::optional<Interval> alpha;  // alpha given in the spec
    bool anisotropic = false;
};

/// The table alpha at which a mapped roughness axis (oren-nayar's sigma, the Phong lobes' n:
/// RoughnessAxis) gives the key `value`: the mapping is monotonic on [alpha_lo, alpha_hi], bisected.
double alpha_of_axis_value(const RoughnessAxis& axis, double value) {
    double lo = axis.alpha_lo, hi = axis.alpha_hi;
    const bool rising = axis.value(hi) > axis.value(lo);
    for (int i = 0; i < 200 && lo < hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        ((axis.value(mid) < value) == rising ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

SweepSplit split_model(const std::string& text, const std::string& where) {
    SweepSplit s;
    const Spec spec = parse_spec(text);
    const RoughnessAxis axis = roughness_axis_of_spec(text);
    Spec rest;
    rest.name = spec.name;
    std::optional<double> alpha, rough, ax, ay;
    for (const auto& kv : spec.keys) {
        auto num = [&] { return parse_number(kv.second, where + ": model key " + kv.first); };
        if (kv.first == "alpha") alpha = num();
        else if (axis.value && kv.first == axis.key) alpha = alpha_of_axis_value(axis, num());  // range-checked below
        else if (kv.first == "roughness") rough = num();
        else if (kv.first == "alpha_x") ax = num();
        else if (kv.first == "alpha_y") ay = num();
        else rest.keys.push_back(kv);
    }
    std::string rest_text = rest.name;
    for (size_t i = 0; i < rest.keys.size(); ++i)
        rest_text += (i == 0 ? ":" : ",") + rest.keys[i].first + "=" + rest.keys[i].second;
    // Is there an alpha to sweep? The tables' own sweep (host/tables/sweep.h) tells.
    const std::optional<ModelConfig> swept = try_sweep_model(rest_text);
    s.sweepable = swept.has_value();
    if (!s.sweepable) {
        s.base = resolve_model(text);  // the model's own message for a bad spec
        s.canonical = s.base.canonical;
        return s;
    }
    s.base = *swept;
    if (alpha || rough || ax || ay) resolve_model(text);  // the given values, range-checked
    s.canonical = s.base.canonical;
    if (alpha) s.alpha = Interval{*alpha, *alpha};
    if (rough) s.alpha = Interval{*rough * *rough, *rough * *rough};
    if (ax || ay) {
        const double x = ax.value_or(ay.value_or(0)), y = ay.value_or(x);
        s.alpha = Interval{std::min(x, y), std::max(x, y)};
        s.anisotropic = x != y;
    }
    return s;
}

const std::set<std::string> kMaterialKeys = {"name", "model", "fresnel", "wavelength", "alpha", "roughness",
                                             "eta", "transmission", "tables", "thickness", "comment"};
const std::set<std::string> kSettingsKeys = {"samples",   "mu_texels", "alpha_texels", "eta_step", "thickness_step",
                                             "mu_map",    "alpha_map", "precision",    "format",   "half",
                                             "sheen_model"};

/// The material's "tables" (a list of kinds, each checked against the lobe), when it names them.
void read_lobe_tables(const json& m, const Where& w, const std::string& ctx, Lobe& lobe) {
    if (!m.contains("tables")) return;
    const json& t = m["tables"];
    if (!t.is_array() || t.empty()) throw Error(w.at("tables") + " must be a non-empty list of table kinds");
    lobe.kinds.clear();
    for (const auto& k : t) {
        const TableKind* kind = &lobe_table_kind(string_at(k, w, "tables"), lobe, ctx);
        if (std::find(lobe.kinds.begin(), lobe.kinds.end(), kind) == lobe.kinds.end()) lobe.kinds.push_back(kind);
    }
}

/// A material of a measured model (merl): one lobe without a roughness axis, whose tables are
/// E(mu) and Eavg (kind_albedo.cpp), per colour when `per_colour` (channel=rgb); "tables" may name
/// a subset of those two.
SceneMaterial measured_material(SceneMaterial& out, const ModelConfig& base, bool per_colour, const json& m,
                                const Where& w, const std::string& ctx) {
    if (m.contains("eta") || m.contains("transmission"))
        throw Error(ctx + ": model '" + base.name + "' is a measured reflectance; drop '" +
                    (m.contains("eta") ? "eta" : "transmission") + "'");
    Lobe lobe;
    lobe.model = per_colour ? merl_channel_spec(base.canonical, "rgb") : base.canonical;
    lobe.model_name = base.name;
    lobe.role = "measured";
    lobe.kinds = default_lobe_kinds(lobe);
    read_lobe_tables(m, w, ctx, lobe);
    for (const TableKind* kind : lobe.kinds)
        if (kind != &table_kind(TableKindId::Albedo) && kind != &table_kind(TableKindId::Eavg))
            throw Error(ctx + ": a measured model's tables are albedo and eavg (no roughness axis); '" + kind->name +
                        "' is not one");
    out.notes.push_back(lobe.model + ": measured, no roughness axis: E(mu) and Eavg" +
                        std::string(per_colour ? " per colour channel" : ""));
    out.lobes.push_back(lobe);
    return out;
}

/// A material's name, checked, with its unknown keys refused: what every later error names it by.
std::string material_name(const json& m, size_t index, const std::string& file) {
    Where w{file, "material " + std::to_string(index + 1)};
    if (!m.is_object()) throw Error("scene '" + file + "': " + w.what + " must be an object");
    if (!m.contains("name")) throw Error("scene '" + file + "': " + w.what + " has no 'name'");
    const std::string name = string_at(m["name"], w, "name");
    if (name.empty()) throw Error("scene '" + file + "': " + w.what + " has an empty 'name'");
    for (const auto& item : m.items())
        if (!kMaterialKeys.count(item.key()))
            throw Error("scene '" + file + "': material '" + name + "': unknown key '" + item.key() +
                        "' (known: name, model, fresnel, wavelength, alpha, roughness, eta, transmission, tables, comment)");
    return name;
}

/// A material's roughness: in the model spec, or as "alpha" / "roughness" (a value or a range),
/// once; range-checked against the model's roughness axis (alpha, or the key a mapped axis sets).
std::optional<Interval> material_alpha(const json& m, const Where& w, const std::string& ctx, const SweepSplit& split,
                                       SceneMaterial& out) {
    const RoughnessAxis& axis = split.base.traits().roughness_axis;
    std::optional<Interval> alpha = split.alpha;
    for (const char* key : {"alpha", "roughness"}) {
        if (!m.contains(key)) continue;
        if (alpha) throw Error(ctx + ": give the roughness once (model spec, 'alpha' or 'roughness')");
        Interval r = interval_at(m[key], w, key);
        if (!split.sweepable)
            throw Error(ctx + ": model '" + split.base.name + "' has no roughness; drop '" + key + "'");
        if (!(r.lo >= 0.0)) throw Error(w.at(key) + " must not be negative");
        if (std::string(key) == "roughness") r = {r.lo * r.lo, r.hi * r.hi};
        alpha = r;
    }
    if (alpha && split.sweepable) {
        // The same range check as a model spec's alpha (or the key a mapped axis sets), for the
        // largest value; values below the alpha floor are planned at it (alpha 0 is the smooth
        // limit of a microfacet lobe), as in a glTF scene.
        if (axis.value && alpha->hi > axis.alpha_hi)
            throw Error(ctx + ": roughness: alpha " + format_number(alpha->hi) + " is beyond " + split.base.name +
                        "'s roughness axis (" + axis.mapping + ")");
        const double top = std::max(alpha->hi, axis.value ? axis.alpha_lo : double(BB_ALPHA_MIN));
        try {
            resolve_model(split.canonical + (split.canonical.find(':') == std::string::npos ? ":" : ",") + axis.key +
                          "=" + format_number(axis.value ? axis.value(top) : top));
        } catch (const Error& e) {
            throw Error(ctx + ": roughness: " + e.what());
        }
        if (!axis.value && alpha->lo < double(BB_ALPHA_MIN)) out.notes.push_back(alpha_floor_note(alpha->lo));
    }

    return alpha;
}

SceneMaterial parse_material(const json& m, size_t index, const std::string& file, std::vector<std::string>& warnings) {
    SceneMaterial out;
    out.name = material_name(m, index, file);
    Where w{file, "material '" + out.name + "'"};
    if (!m.contains("model")) throw Error("scene '" + file + "': " + w.what + " has no 'model' (e.g. \"ggx\")");
    // merl:file=FILE names a file beside the scene, as nk:FILE does; a file without a channel (or
    // channel=rgb) gets tables per colour, its spec read here in red
    const std::string given = merl_spec_beside(string_at(m["model"], w, "model"), file);
    const bool per_colour = merl_per_colour(given);
    const std::string model_text = per_colour ? merl_channel_spec(given, "r") : given;
    const std::string ctx = "scene '" + file + "': " + w.what;

    SweepSplit split;
    try {
        split = split_model(model_text, ctx);
    } catch (const Error& e) {
        throw Error(ctx + ": " + e.what());
    }
    std::string fresnel = "none";
    double wavelength = 0.0;
    std::optional<Interval> thickness;  // a thin film's (nm)
    if (m.contains("wavelength")) {
        wavelength = number_at(m["wavelength"], w, "wavelength");
        if (!(wavelength > 0)) throw Error(w.at("wavelength") + " must be positive (nm)");
    }
    if (m.contains("fresnel")) {
        try {
            // A measured metal without a wavelength is checked at 550 nm; its conductor tables then
            // hold its colour R, G, B (tables/spectral_fresnel.h), and albedo and eavg tables do not depend on it.
            std::string text = string_at(m["fresnel"], w, "fresnel");
            // nk:FILE names a file beside the scene (a relative path is read from the scene's folder),
            // and so does a film's substrate, thin-film:...,base=nk:FILE.
            const size_t slash = file.find_last_of('/');
            const std::string folder = slash == std::string::npos ? "" : file.substr(0, slash + 1);
            auto beside = [&](const std::string& spec) {
                const size_t colon = spec.find(':');
                if (fresnel_reads_file(spec) && colon != std::string::npos && colon + 1 < spec.size() && spec[colon + 1] != '/')
                    return spec.substr(0, colon + 1) + folder + spec.substr(colon + 1);
                return spec;
            };
            text = beside(text);
            const size_t base = text.find("base=nk:");
            if (text.rfind("thin-film:", 0) == 0 && base != std::string::npos) {
                const size_t end = text.find(',', base);
                const std::string nk = text.substr(base + 5, end == std::string::npos ? std::string::npos : end - base - 5);
                text = text.substr(0, base + 5) + beside(nk) + (end == std::string::npos ? "" : text.substr(end));
            }
            const bool measured = fresnel_needs_wavelength(text);
            // A film's thickness range ("thickness": nm or [lo, hi]) is the thin-film table's axis;
            // the spec is checked at its lower end.
            if (m.contains("thickness")) {
                if (text.rfind("thin-film:", 0) != 0)
                    throw Error("'thickness' is a thin film's (nm); the Fresnel '" + text + "' is not thin-film:");
                const auto keys = parse_spec(text).keys;
                if (std::any_of(keys.begin(), keys.end(), [](const auto& kv) { return kv.first == "thickness"; }))
                    throw Error("give the film's thickness once ('thickness' or thickness= in the spec)");
                thickness = interval_at(m["thickness"], w, "thickness");
                if (!(thickness->lo >= 0.0 && thickness->hi <= 100000.0))
                    throw Error(w.at("thickness") + " must lie in [0, 100000] nm");
                resolve_fresnel(tables::thin_film_at(text, thickness->lo), measured && wavelength == 0.0 ? 550.0 : wavelength);
            } else {
                resolve_fresnel(text, measured && wavelength == 0.0 ? 550.0 : wavelength);
                if (text.rfind("thin-film:", 0) == 0) {  // its one thickness: a thin-film table of one slice
                    const double d = resolve_fresnel(text, 550.0).params[BB_THIN_FILM_THICKNESS];
                    thickness = Interval{d, d};
                }
            }
            fresnel = measured || m.contains("thickness") ? text : resolve_fresnel(text, wavelength).canonical;
        } catch (const Error& e) {
            throw Error(ctx + ": " + e.what());
        }
        if (fresnel != "none" && !split.base.uses_fresnel)
            throw Error(ctx + ": model '" + split.base.name + "' has no Fresnel term; drop 'fresnel'");
    }
    const bool transmission = m.contains("transmission") && [&] {
        if (!m["transmission"].is_boolean()) throw Error(w.at("transmission") + " must be true or false");
        return m["transmission"].get<bool>();
    }();

    const std::optional<Interval> alpha = material_alpha(m, w, ctx, split, out);
    const RoughnessAxis& axis = split.base.traits().roughness_axis;

    // Index of refraction: from a dielectric Fresnel spec, or "eta" (a value or a range).
    std::optional<Interval> eta;
    if (fresnel_kind_of(fresnel) == BB_FRESNEL_DIELECTRIC) {
        const double e = resolve_fresnel(fresnel).params[0];
        eta = Interval{e, e};
    }
    if (m.contains("eta")) {
        if (eta) throw Error(ctx + ": give eta once (in 'fresnel' or as 'eta')");
        if (fresnel != "none")
            throw Error(ctx + ": 'eta' makes a dielectric interface; it cannot go with fresnel '" + fresnel + "'");
        eta = interval_at(m["eta"], w, "eta");
    }
    if (eta && !(eta->lo > 1.0 && eta->hi <= kSceneEtaMax))
        throw Error(ctx + ": eta " + format_number(eta->lo) + (eta->lo == eta->hi ? "" : ".." + format_number(eta->hi)) +
                    " is out of range: tables take the relative index of the denser side, 1 < eta <= " +
                    format_number(kSceneEtaMax) + " (the table "
                    "holds the view from inside, 1/eta, too)");
    if (transmission && !eta)
        throw Error(ctx + ": a transmissive material needs an index of refraction: fresnel \"dielectric:eta=E\" or \"eta\"");

    if (!split.sweepable && split.base.traits().measured)
        return measured_material(out, split.base, per_colour, m, w, ctx);
    if (!split.sweepable) {
        const std::string name = split.base.name;
        if (m.contains("tables"))
            throw Error(ctx + ": model '" + name + "' has no roughness to sweep; tables need a microfacet model");
        if (split.base.id == BB_MODEL_LAMBERT)
            out.notes.push_back(name + ": albedo is rho (closed form), no table");
        else if (split.base.traits().delta)
            out.notes.push_back(name + ": delta lobe, albedo is the Fresnel term (analytic), no table");
        else {
            out.notes.push_back(split.base.canonical + ": no roughness axis, no table");
            warnings.push_back("material '" + out.name + "': model '" + name +
                               "' is not modelled by tables (no roughness to sweep); use `brdfbake albedo` for its "
                               "albedo curve");
        }
        return out;
    }
    if (!alpha)
        throw Error(ctx + ": needs its roughness: 'alpha' or 'roughness' (a value or a [lo, hi] range), or " +
                    std::string(axis.key) + "=" + (axis.value ? std::string(1, char(std::toupper(axis.key[0]))) : "A") +
                    " in the model spec" + (axis.value ? std::string(" (alpha sets ") + axis.key + ": " + axis.mapping + ")" : ""));
    if (split.anisotropic) {
        out.notes.push_back("anisotropic alpha: isotropic tables over [alpha_y, alpha_x]");
        warnings.push_back("material '" + out.name + "': anisotropic roughness (alpha_x != alpha_y) is not "
                           "modelled; its tables are isotropic over [" + format_number(alpha->lo) + ", " +
                           format_number(alpha->hi) + "]");
    }

    Lobe lobe;
    lobe.model = split.canonical;
    lobe.model_name = split.base.name;
    lobe.fresnel = fresnel;
    lobe.wavelength_nm = wavelength;
    lobe.alpha = *alpha;
    lobe.eta = eta;
    lobe.thickness = thickness;
    if (eta) lobe.role = transmission ? "transmission" : "dielectric";
    else lobe.role = is_conductor_fresnel(fresnel) ? "metal" : "specular";
    lobe.kinds = default_lobe_kinds(lobe);
    read_lobe_tables(m, w, ctx, lobe);
    out.lobes.push_back(lobe);
    return out;
}

void parse_settings(const json& s, const std::string& file, SceneSettings& out) {
    const Where w{file, "settings"};
    if (!s.is_object()) throw Error("scene '" + file + "': 'settings' must be an object");
    for (const auto& item : s.items()) {
        const std::string& k = item.key();
        const json& v = item.value();
        if (!kSettingsKeys.count(k))
            throw Error(w.at(k) + " is not a setting (known: samples, mu_texels, alpha_texels, eta_step, thickness_step, "
                                  "mu_map, alpha_map, precision, format, half, sheen_model)");
        auto integer = [&] {
            const double x = number_at(v, w, k);
            if (x != std::floor(x) || x < 1 || x > 1e12) throw Error(w.at(k) + " must be a positive whole number");
            return x;
        };
        if (k == "samples") out.samples = std::uint64_t(integer());
        else if (k == "mu_texels") out.mu_texels = int(std::min(integer(), 1e6));
        else if (k == "alpha_texels") out.alpha_texels = int(std::min(integer(), 1e6));
        else if (k == "eta_step") out.eta_step = number_at(v, w, k);
        else if (k == "thickness_step") out.thickness_step = number_at(v, w, k);
        else if (k == "mu_map") out.mu_map = string_at(v, w, k);
        else if (k == "alpha_map") out.alpha_map = string_at(v, w, k);
        else if (k == "sheen_model") out.sheen_model = string_at(v, w, k);
        else if (k == "precision") {
            const std::string p = string_at(v, w, k);
            if (p != "float" && p != "double") throw Error(w.at(k) + " must be \"float\" or \"double\"");
            out.precision = p == "double" ? Precision::Double : Precision::Float;
        } else if (k == "format") out.table_format = string_at(v, w, k);
        else if (k == "half") {
            if (!v.is_boolean()) throw Error(w.at(k) + " must be true or false");
            out.half = v.get<bool>();
        }
    }
    try {
        check_settings(out);
    } catch (const Error& e) {
        throw Error("scene '" + file + "': settings: " + e.what());
    }
}

}  // namespace

void check_settings(const SceneSettings& s) {
    if (s.samples < 16) throw Error("samples must be at least 16");
    if (s.mu_texels < 1 || s.mu_texels > 4096) throw Error("mu_texels must lie in 1..4096");
    if (s.alpha_texels < 1 || s.alpha_texels > 4096) throw Error("alpha_texels must lie in 1..4096");
    if (!(s.eta_step > 0.0 && s.eta_step <= 10.0)) throw Error("eta_step must lie in (0, 10]");
    if (!(s.thickness_step > 0.0 && s.thickness_step <= 100000.0)) throw Error("thickness_step must lie in (0, 100000] (nm)");
    if (s.mu_map != "linear" && s.mu_map != "sqrt") throw Error("mu_map must be \"linear\" or \"sqrt\"");
    if (s.sheen_model != "charlie" && s.sheen_model != "ltc") throw Error("sheen_model must be \"charlie\" or \"ltc\"");
    if (s.alpha_map != "alpha" && s.alpha_map != "roughness")
        throw Error("alpha_map must be \"alpha\" or \"roughness\"");
    if (s.table_format != "exr" && s.table_format != "csv" && s.table_format != "h")
        throw Error("table format must be exr, csv or h");
    if (s.half && s.table_format != "exr") throw Error("half-float channels are an EXR option");
}

Scene parse_scene_json(const std::string& text, const std::string& path) {
    const json j = scene_json::parse_strict(text, "scene '" + path + "'");
    if (!j.is_object()) throw Error("scene '" + path + "': expected a JSON object with \"materials\"");
    for (const auto& item : j.items())
        if (item.key() != "materials" && item.key() != "settings" && item.key() != "brdfbake_scene" &&
            item.key() != "comment")
            throw Error("scene '" + path + "': unknown top-level key '" + item.key() +
                        "' (known: brdfbake_scene, settings, materials, comment)");
    if (j.contains("brdfbake_scene") && j["brdfbake_scene"] != 1)
        throw Error("scene '" + path + "': unsupported \"brdfbake_scene\" version (this build reads 1)");
    if (!j.contains("materials") || !j["materials"].is_array())
        throw Error("scene '" + path + "': \"materials\" must be a list of materials");
    if (j["materials"].empty()) throw Error("scene '" + path + "': \"materials\" is empty");
    Scene scene;
    scene.path = path;
    scene.source = "brdfbake scene";
    if (j.contains("settings")) parse_settings(j["settings"], path, scene.settings);
    std::set<std::string> names;
    for (size_t i = 0; i < j["materials"].size(); ++i) {
        SceneMaterial m = parse_material(j["materials"][i], i, path, scene.warnings);
        if (!names.insert(m.name).second)
            throw Error("scene '" + path + "': two materials are named '" + m.name + "'");
        scene.materials.push_back(std::move(m));
    }
    return scene;
}

Scene load_scene(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const std::string ext = dot == std::string::npos ? "" : lower(path.substr(dot));
    if (ext == ".gltf" || ext == ".glb") return load_gltf_scene(path);
    if (ext != ".json")
        throw Error("scene '" + path + "': unknown scene format; expected a .json scene file, .gltf or .glb");
    // A regular file of at most 64 MiB (a scene lists materials, not geometry), judged before reading.
    return parse_scene_json(read_input_file(path, "scene", std::uintmax_t(64) << 20), path);
}

std::string model_without_alpha(const std::string& spec) { return split_model(spec, "model").canonical; }

}  // namespace brdfbake

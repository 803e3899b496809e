// Scene files (JSON), the rules that decide which tables a lobe needs, and the planner that
// merges those needs into the fewest tables. The glTF reader is host/gltf_scene.cpp.
#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/version.h"
#include "models/key_reader.h"

namespace brdfbake {

namespace {

using json = nlohmann::json;

/// The table kinds the planner knows how to size. "dielectric" and "conductor" are computed
/// where this build's compute_lut knows them (lut_kind_available).
const std::vector<std::string>& planner_kinds() {
    static const std::vector<std::string> k = {"albedo", "eavg", "dfg", "dfg-ms", "conductor", "dielectric"};
    return k;
}

std::string join(const std::vector<std::string>& v, const std::string& sep = ", ") {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
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

/// The name of a Fresnel spec ("metal:Au" is not key=value, so not parse_spec).
std::string fresnel_name(const std::string& fresnel) { return fresnel.substr(0, fresnel.find(':')); }

bool is_conductor_fresnel(const std::string& fresnel) {
    const std::string name = fresnel_name(fresnel);
    return name == "conductor" || name == "conductor-approx" || name == "metal" || name == "nk";
}

// A model spec split into the part that is the same for every texel of a table (model name and
// keys such as shadowing) and the roughness it was given with.
struct SweepSplit {
    ModelConfig base;               // resolved with a placeholder alpha (or as given, no alpha)
    std::string canonical;          // canonical spec without alpha
    bool sweepable = false;         // the model has an alpha that tables sweep
    std::optional<Interval> alpha;  // alpha given in the spec
    bool anisotropic = false;
};

SweepSplit split_model(const std::string& text, const std::string& where) {
    SweepSplit s;
    const Spec spec = parse_spec(text);
    Spec rest;
    rest.name = spec.name;
    std::optional<double> alpha, rough, ax, ay;
    for (const auto& kv : spec.keys) {
        auto num = [&] { return parse_number(kv.second, where + ": model key " + kv.first); };
        if (kv.first == "alpha") alpha = num();
        else if (kv.first == "roughness") rough = num();
        else if (kv.first == "alpha_x") ax = num();
        else if (kv.first == "alpha_y") ay = num();
        else rest.keys.push_back(kv);
    }
    std::string rest_text = rest.name;
    for (size_t i = 0; i < rest.keys.size(); ++i)
        rest_text += (i == 0 ? ":" : ",") + rest.keys[i].first + "=" + rest.keys[i].second;
    // Is there an alpha to sweep? Resolving with a placeholder alpha tells, without a list of
    // microfacet models here (torrance-sparrow with d=blinn has none).
    try {
        s.base = resolve_model(rest_text + (rest.keys.empty() ? ":" : ",") + "alpha=0.5");
        s.sweepable = true;
    } catch (const Error&) {
        s.sweepable = false;
    }
    if (!s.sweepable) {
        s.base = resolve_model(text);  // the model's own message for a bad spec
        s.canonical = s.base.canonical;
        return s;
    }
    if (alpha || rough || ax || ay) resolve_model(text);  // the given values, range-checked
    std::string c = s.base.canonical;
    const size_t p = c.find("alpha=0.5");
    if (p != std::string::npos) {
        c.erase(p, 9);
        while (c.find(":,") != std::string::npos) c.replace(c.find(":,"), 2, ":");
        while (c.find(",,") != std::string::npos) c.replace(c.find(",,"), 2, ",");
        if (!c.empty() && (c.back() == ',' || c.back() == ':')) c.pop_back();
    }
    s.canonical = c;
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
                                             "eta", "transmission", "tables", "comment"};
const std::set<std::string> kSettingsKeys = {"samples", "mu_texels", "alpha_texels", "eta_step", "mu_map",
                                             "alpha_map", "precision", "format", "half"};

SceneMaterial parse_material(const json& m, size_t index, const std::string& file, std::vector<std::string>& warnings) {
    Where w{file, "material " + std::to_string(index + 1)};
    if (!m.is_object()) throw Error("scene '" + file + "': " + w.what + " must be an object");
    if (!m.contains("name")) throw Error("scene '" + file + "': " + w.what + " has no 'name'");
    SceneMaterial out;
    out.name = string_at(m["name"], w, "name");
    if (out.name.empty()) throw Error("scene '" + file + "': " + w.what + " has an empty 'name'");
    w.what = "material '" + out.name + "'";
    for (const auto& item : m.items())
        if (!kMaterialKeys.count(item.key()))
            throw Error("scene '" + file + "': " + w.what + ": unknown key '" + item.key() +
                        "' (known: name, model, fresnel, wavelength, alpha, roughness, eta, transmission, tables, comment)");
    if (!m.contains("model")) throw Error("scene '" + file + "': " + w.what + " has no 'model' (e.g. \"ggx\")");
    const std::string model_text = string_at(m["model"], w, "model");
    const std::string ctx = "scene '" + file + "': " + w.what;

    SweepSplit split;
    try {
        split = split_model(model_text, ctx);
    } catch (const Error& e) {
        throw Error(ctx + ": " + e.what());
    }
    std::string fresnel = "none";
    double wavelength = 0.0;
    if (m.contains("wavelength")) {
        wavelength = number_at(m["wavelength"], w, "wavelength");
        if (!(wavelength > 0)) throw Error(w.at("wavelength") + " must be positive (nm)");
    }
    if (m.contains("fresnel")) {
        try {
            // A measured metal without a wavelength is checked at 550 nm; its conductor tables then
            // hold R, G and B (650, 550, 450 nm), and albedo and eavg tables do not depend on it.
            const std::string text = string_at(m["fresnel"], w, "fresnel");
            const std::string fname = fresnel_name(text);
            const bool measured = fname == "metal" || fname == "nk";
            resolve_fresnel(text, measured && wavelength == 0.0 ? 550.0 : wavelength);
            fresnel = measured ? text : resolve_fresnel(text, wavelength).canonical;
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

    // Roughness: in the spec, or as "alpha" / "roughness" (a value or a range), once.
    std::optional<Interval> alpha = split.alpha;
    for (const char* key : {"alpha", "roughness"}) {
        if (!m.contains(key)) continue;
        if (alpha) throw Error(ctx + ": give the roughness once (model spec, 'alpha' or 'roughness')");
        Interval r = interval_at(m[key], w, key);
        if (!split.sweepable)
            throw Error(ctx + ": model '" + split.base.name + "' has no roughness; drop '" + key + "'");
        if (!(r.lo > 0.0)) throw Error(w.at(key) + " must be positive");
        if (std::string(key) == "roughness") r = {r.lo * r.lo, r.hi * r.hi};
        alpha = r;
    }
    if (alpha && split.sweepable) {
        // The same range check as a model spec's alpha.
        resolve_model(split.canonical + (split.canonical.find(':') == std::string::npos ? ":" : ",") +
                      "alpha=" + format_number(alpha->lo));
        resolve_model(split.canonical + (split.canonical.find(':') == std::string::npos ? ":" : ",") +
                      "alpha=" + format_number(alpha->hi));
    }

    // Index of refraction: from a dielectric Fresnel spec, or "eta" (a value or a range).
    std::optional<Interval> eta;
    if (fresnel_name(fresnel) == "dielectric") {
        const double e = resolve_fresnel(fresnel).params[0];
        eta = Interval{e, e};
    }
    if (m.contains("eta")) {
        if (eta) throw Error(ctx + ": give eta once (in 'fresnel' or as 'eta')");
        if (fresnel != "none")
            throw Error(ctx + ": 'eta' makes a dielectric interface; it cannot go with fresnel '" + fresnel + "'");
        eta = interval_at(m["eta"], w, "eta");
    }
    if (eta && !(eta->lo > 1.0 && eta->hi <= 10.0))
        throw Error(ctx + ": eta " + format_number(eta->lo) + (eta->lo == eta->hi ? "" : ".." + format_number(eta->hi)) +
                    " is out of range: tables take the relative index of the denser side, 1 < eta <= 10 (the table "
                    "holds the view from inside, 1/eta, too)");
    if (transmission && !eta)
        throw Error(ctx + ": a transmissive material needs an index of refraction: fresnel \"dielectric:eta=E\" or \"eta\"");

    if (!split.sweepable) {
        const std::string name = split.base.name;
        if (m.contains("tables"))
            throw Error(ctx + ": model '" + name + "' has no roughness to sweep; tables need a microfacet model");
        if (name == "lambert")
            out.notes.push_back("lambert: albedo is rho (closed form), no table");
        else if (name == "mirror" || name == "dielectric-specular")
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
        throw Error(ctx + ": needs its roughness: 'alpha' or 'roughness' (a value or a [lo, hi] range), "
                          "or alpha=A in the model spec");
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
    if (eta) {
        lobe.role = transmission ? "transmission" : "dielectric";
        lobe.kinds = {"dielectric"};
    } else {
        lobe.role = is_conductor_fresnel(fresnel) ? "metal" : "specular";
        lobe.kinds = {"albedo", "eavg"};
    }
    if (m.contains("tables")) {
        const json& t = m["tables"];
        if (!t.is_array() || t.empty()) throw Error(w.at("tables") + " must be a non-empty list of table kinds");
        lobe.kinds.clear();
        for (const auto& k : t) {
            const std::string kind = string_at(k, w, "tables");
            if (std::find(planner_kinds().begin(), planner_kinds().end(), kind) == planner_kinds().end())
                throw Error(ctx + ": unknown table kind '" + kind + "' in 'tables' (known: " + join(planner_kinds()) + ")");
            if (kind == "dielectric" && !eta)
                throw Error(ctx + ": a dielectric table needs an index of refraction (fresnel dielectric:eta=E or 'eta')");
            if (kind == "conductor" && !is_conductor_fresnel(fresnel))
                throw Error(ctx + ": a conductor table needs a conductor Fresnel (conductor:, metal:, nk:)");
            if (std::find(lobe.kinds.begin(), lobe.kinds.end(), kind) == lobe.kinds.end()) lobe.kinds.push_back(kind);
        }
    }
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
            throw Error(w.at(k) + " is not a setting (known: samples, mu_texels, alpha_texels, eta_step, mu_map, "
                                  "alpha_map, precision, format, half)");
        auto integer = [&] {
            const double x = number_at(v, w, k);
            if (x != std::floor(x) || x < 1 || x > 1e12) throw Error(w.at(k) + " must be a positive whole number");
            return x;
        };
        if (k == "samples") out.samples = std::uint64_t(integer());
        else if (k == "mu_texels") out.mu_texels = int(std::min(integer(), 1e6));
        else if (k == "alpha_texels") out.alpha_texels = int(std::min(integer(), 1e6));
        else if (k == "eta_step") out.eta_step = number_at(v, w, k);
        else if (k == "mu_map") out.mu_map = string_at(v, w, k);
        else if (k == "alpha_map") out.alpha_map = string_at(v, w, k);
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
    if (s.mu_map != "linear" && s.mu_map != "sqrt") throw Error("mu_map must be \"linear\" or \"sqrt\"");
    if (s.alpha_map != "alpha" && s.alpha_map != "roughness")
        throw Error("alpha_map must be \"alpha\" or \"roughness\"");
    if (s.table_format != "exr" && s.table_format != "csv" && s.table_format != "h")
        throw Error("table format must be exr, csv or h");
    if (s.half && s.table_format != "exr") throw Error("half-float channels are an EXR option");
}

Scene parse_scene_json(const std::string& text, const std::string& path) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        const size_t p = what.find("] ");
        if (what.rfind("[json.exception", 0) == 0 && p != std::string::npos) what = what.substr(p + 2);
        throw Error("scene '" + path + "' is not valid JSON: " + one_line(what));
    }
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
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read scene '" + path + "': " + std::strerror(errno));
    std::stringstream s;
    s << in.rdbuf();
    return parse_scene_json(s.str(), path);
}

// --- planning ----------------------------------------------------------------------------------

std::string model_without_alpha(const std::string& spec) { return split_model(spec, "model").canonical; }

bool lut_kind_available(const std::string& kind) {
    for (const auto& k : lut_kinds())
        if (k.first == kind) return true;
    return false;
}

namespace {

/// Axis of `n` texels whose first and last texel centres fall on c_lo and c_hi (a single value
/// gets one texel centred on it). Returns {lo, hi, n} of the coordinate range.
struct AxisPlan {
    double lo, hi;
    int n;
};

AxisPlan plan_axis(double c_lo, double c_hi, int n_full_range, double full_width, double floor, int max_n) {
    const double w = c_hi - c_lo;
    if (w <= 1e-12 * std::max(1.0, std::fabs(c_hi))) {
        const double h = 0.5 * full_width / n_full_range;
        const double lo = std::max(floor, c_lo - h);
        return {lo, std::max(c_hi + h, lo + 2 * h), 1};
    }
    int n = int(std::ceil(n_full_range * w / full_width - 1e-9)) + 1;
    n = std::max(2, std::min(n, std::max(2, max_n)));
    const double pad = w / (2.0 * (n - 1));
    return {std::max(floor, c_lo - pad), c_hi + pad, n};
}

double alpha_coordinate(double alpha, const std::string& map) { return map == "roughness" ? std::sqrt(alpha) : alpha; }

std::string hex64(std::uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
    return b;
}

std::uint64_t fnv1a(const std::string& s) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

std::string g17(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

/// Value channels of a table (the error channel comes on top): dielectric R, T, R_inside,
/// T_inside; a measured conductor without a wavelength R, G, B.
int channel_count(const std::string& kind, const std::string& fresnel, double wavelength_nm) {
    if (kind == "dielectric") return 4;
    if (kind == "dfg" || kind == "dfg-ms") return 2;
    if (kind == "conductor" && wavelength_nm == 0.0) {
        const std::string name = fresnel_name(fresnel);
        if (name == "metal" || name == "nk") return 3;
    }
    return 1;
}

/// Integrations per cell: the split-sum kinds integrate twice (F = 1 and F = Schlick f0 = 0), a
/// measured conductor once per RGB wavelength.
int integrations(const std::string& kind, const std::string& fresnel, double wavelength_nm) {
    if (kind == "dfg" || kind == "dfg-ms") return 2;
    if (kind == "conductor") return channel_count(kind, fresnel, wavelength_nm);
    return 1;
}

/// Samples per second the estimates assume: PoCL on one core of the development machine (AMD
/// EPYC, float, GGX importance sampling; docs/scenes.md) times the hardware threads.
constexpr double kSamplesPerSecondPerCore = 1.0e7;

/// A cold kernel build and first launch on PoCL (docs/scenes.md: 0.35 to 0.55 s for GGX).
constexpr double kSecondsPerProgram = 0.5;

}  // namespace

void apply_eta_axis(const PlannedTable& t, LutRequest& request) {
    if (t.request.kind != "dielectric") return;
    request.eta_lo = t.eta_lo;
    request.eta_hi = t.eta_hi;
    request.depth = t.depth;
}

Plan make_plan(const Scene& scene) {
    check_settings(scene.settings);
    const SceneSettings& s = scene.settings;
    Plan plan;
    plan.scene = scene.path;
    plan.source = scene.source;
    plan.warnings = scene.warnings;
    plan.settings = s;
    plan.materials = scene.materials;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    plan.samples_per_second = kSamplesPerSecondPerCore * cores;
    plan.throughput_basis = std::to_string(cores) + " hardware threads x 1.0e7 (PoCL, float, measured; docs/scenes.md)";

    // Group the needs: one table per (kind, model, Fresnel in the table).
    struct Group {
        std::string kind, model, model_name, fresnel;
        double wavelength = 0.0;
        Interval alpha;
        std::optional<Interval> eta;
        std::vector<std::string> serves, materials;
    };
    std::vector<Group> groups;
    for (const auto& m : scene.materials) {
        if (m.lobes.empty()) {
            plan.no_table.push_back(m.name + (m.notes.empty() ? "" : " (" + m.notes.front() + ")"));
            continue;
        }
        for (const auto& lobe : m.lobes) {
            for (const auto& kind : lobe.kinds) {
                // Which Fresnel the table itself holds: albedo and eavg are computed with F = 1 (the
                // lobe's Fresnel enters at render time through its hemispherical average), the
                // split-sum kinds factor it out, a dielectric table has eta as an axis; only a
                // conductor table bakes the lobe's own Fresnel in.
                const std::string fresnel = kind == "conductor" ? lobe.fresnel : "none";
                const double wl = kind == "conductor" ? lobe.wavelength_nm : 0.0;
                auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
                    return g.kind == kind && g.model == lobe.model && g.fresnel == fresnel && g.wavelength == wl;
                });
                if (it == groups.end()) {
                    Group g;
                    g.kind = kind;
                    g.model = lobe.model;
                    g.model_name = lobe.model_name;
                    g.fresnel = fresnel;
                    g.wavelength = wl;
                    g.alpha = lobe.alpha;
                    if (kind == "dielectric") g.eta = lobe.eta;
                    groups.push_back(g);
                    it = groups.end() - 1;
                } else {
                    it->alpha.lo = std::min(it->alpha.lo, lobe.alpha.lo);
                    it->alpha.hi = std::max(it->alpha.hi, lobe.alpha.hi);
                    if (kind == "dielectric" && lobe.eta) {
                        it->eta->lo = std::min(it->eta->lo, lobe.eta->lo);
                        it->eta->hi = std::max(it->eta->hi, lobe.eta->hi);
                    }
                }
                const std::string serve = m.name + " (" + lobe.role + ")";
                if (std::find(it->serves.begin(), it->serves.end(), serve) == it->serves.end())
                    it->serves.push_back(serve);
                if (std::find(it->materials.begin(), it->materials.end(), m.name) == it->materials.end())
                    it->materials.push_back(m.name);
            }
        }
    }

    // File names: kind-model, with the model's non-default keys (and a conductor's Fresnel) where
    // they tell two tables apart, and a short hash where even that does not.
    auto sanitize = [](std::string x) {
        for (char& c : x)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '-';
        return x;
    };
    std::vector<std::string> names;
    for (const auto& g : groups) {
        std::string n = g.kind + "-" + g.model_name;
        if (g.model != model_without_alpha(g.model_name) && g.model.find(':') != std::string::npos)
            n += "-" + sanitize(g.model.substr(g.model.find(':') + 1));
        if (g.kind == "conductor") n += "-" + sanitize(g.fresnel) + (g.wavelength > 0 ? "-" + format_number(g.wavelength) + "nm" : "");
        names.push_back(n);
    }
    std::map<std::string, int> name_count;
    for (const auto& n : names) ++name_count[n];
    for (const auto& g : groups) {
        PlannedTable t;
        LutRequest& r = t.request;
        r.kind = g.kind;
        r.model = g.model;
        r.fresnel = g.fresnel;
        r.wavelength_nm = g.wavelength;
        r.mu_map = s.mu_map;
        r.alpha_map = s.alpha_map;
        r.samples = s.samples;
        r.precision = s.precision;
        t.alpha = g.alpha;
        t.eta = g.eta;
        t.serves = g.serves;
        t.materials = g.materials;

        const double c_lo = alpha_coordinate(std::max(g.alpha.lo, 0.0), s.alpha_map);
        const double c_hi = alpha_coordinate(g.alpha.hi, s.alpha_map);
        const AxisPlan a = plan_axis(c_lo, c_hi, s.alpha_texels, 1.0, 0.0, s.alpha_texels);
        if (a.hi > 3.0)
            throw Error("alpha up to " + format_number(g.alpha.hi) + " (" + join(g.materials) +
                        ") is beyond the tables' roughness axis, which stops at coordinate 3");
        r.alpha_lo = a.lo;
        r.alpha_hi = a.hi;
        const int n_alpha = a.n;
        if (g.kind == "eavg") {
            r.width = n_alpha;
            r.height = 1;
            t.cells = std::uint64_t(n_alpha) * 48;  // 32 + 16 Gauss-Legendre nodes in mu
        } else {
            r.width = s.mu_texels;
            r.height = n_alpha;
            t.cells = std::uint64_t(r.width) * r.height;
        }
        if (g.kind == "dielectric") {
            const AxisPlan e = plan_axis(g.eta->lo, g.eta->hi, 1, s.eta_step, 1.0, 64);
            t.eta_lo = e.lo;
            t.eta_hi = e.hi;
            t.depth = e.n;
            apply_eta_axis(t, r);
            t.cells *= std::uint64_t(t.depth) * 2;  // both sides of the interface
        }
        t.samples_total = t.cells * s.samples * integrations(g.kind, g.fresnel, g.wavelength);
        // A dielectric sample (microfacet normal, exact Fresnel, reflect or refract) costs about
        // 3.5 albedo samples (measured: 22 M samples of examples/scene.gltf in 8.8 s against
        // 4.7 M albedo samples in 0.7 s on the same machine).
        t.est_seconds = double(t.samples_total) * (g.kind == "dielectric" ? 3.5 : 1.0) / plan.samples_per_second;
        const std::uint64_t texels = std::uint64_t(r.width) * r.height * t.depth;
        const int channels = channel_count(g.kind, g.fresnel, g.wavelength) + 1;  // values + error
        // Per cell: ~170 B of device buffers (float; 16 replicas) and ~470 B on the host while
        // the kernel runs; the finished table holds doubles.
        t.est_memory = t.cells * 640 + texels * channels * 8;
        if (s.table_format == "exr") t.file_bytes = texels * channels * (s.half ? 2 : 4) + 2048;
        else t.file_bytes = texels * channels * 26 + 1024;

        std::string name = names[size_t(&g - groups.data())];
        if (name_count[name] > 1) name += "-" + hex64(fnv1a(g.model + "|" + g.fresnel)).substr(0, 6);
        t.file = name + "." + s.table_format;

        std::ostringstream k;
        k << "brdfbake " << BRDFBAKE_VERSION << "; kind=" << r.kind << "; model=" << r.model << "; fresnel=" << r.fresnel
          << "; wavelength_nm=" << g17(r.wavelength_nm) << "; size=" << r.width << "x" << r.height;
        if (g.kind == "dielectric") k << "x" << t.depth << "; eta_range=" << g17(t.eta_lo) << "," << g17(t.eta_hi);
        k << "; mu_map=" << r.mu_map << "; alpha_map=" << r.alpha_map << "; alpha_range=" << g17(r.alpha_lo) << ","
          << g17(r.alpha_hi) << "; samples=" << r.samples << "; precision=" << precision_name(r.precision)
          << "; format=" << s.table_format << (s.half ? "-half" : "");
        t.key = k.str();
        t.hash = hex64(fnv1a(t.key));

        if (!lut_kind_available(g.kind)) {
            t.unavailable = "table kind '" + g.kind + "' is not available in this build (known: ";
            std::vector<std::string> known;
            for (const auto& kk : lut_kinds()) known.push_back(kk.first);
            t.unavailable += join(known) + ")";
        } else {
            try {
                LutRequest check = r;
                apply_eta_axis(t, check);
                validate_lut(check);
            } catch (const Error& e) {
                t.unavailable = e.what();
            }
        }
        if (!t.unavailable.empty())
            plan.warnings.push_back("table '" + t.file + "' (for " + join(t.materials) + "): cannot be computed by "
                                    "this build: " + t.unavailable);
        if (std::find(plan.models.begin(), plan.models.end(), g.model_name) == plan.models.end())
            plan.models.push_back(g.model_name);
        plan.tables.push_back(std::move(t));
    }
    // Programs: one albedo kernel per (model, Fresnel kind) and one dielectric kernel per model.
    std::set<std::string> programs;
    for (const auto& t : plan.tables) {
        const std::string& k = t.request.kind;
        const std::string m = t.request.model;
        if (k == "albedo" || k == "eavg") programs.insert("albedo|" + m + "|none");
        else if (k == "dfg" || k == "dfg-ms") {
            programs.insert("albedo|" + m + "|none");
            programs.insert("albedo|" + m + "|schlick");
        } else if (k == "conductor") programs.insert("albedo|" + m + "|" + fresnel_name(t.request.fresnel));
        else programs.insert(k + "|" + m);
    }
    plan.programs = int(programs.size());
    plan.build_seconds = kSecondsPerProgram * plan.programs;
    return plan;
}

// --- plan output -------------------------------------------------------------------------------

namespace {

std::string human_bytes(double b) {
    char s[32];
    if (b < 1024) std::snprintf(s, sizeof s, "%.0f B", b);
    else if (b < 1024 * 1024) std::snprintf(s, sizeof s, "%.1f KiB", b / 1024);
    else if (b < 1024.0 * 1024 * 1024) std::snprintf(s, sizeof s, "%.1f MiB", b / 1024 / 1024);
    else std::snprintf(s, sizeof s, "%.2f GiB", b / 1024 / 1024 / 1024);
    return s;
}

std::string human_count(double n) {
    char s[32];
    if (n < 1e4) std::snprintf(s, sizeof s, "%.0f", n);
    else if (n < 1e9) std::snprintf(s, sizeof s, "%.1f M", n / 1e6);
    else std::snprintf(s, sizeof s, "%.2f G", n / 1e9);
    return s;
}

std::string human_seconds(double t) {
    char s[32];
    if (t < 0.1) std::snprintf(s, sizeof s, "%.2f s", t);
    else if (t < 120) std::snprintf(s, sizeof s, "%.1f s", t);
    else if (t < 7200) std::snprintf(s, sizeof s, "%.1f min", t / 60);
    else std::snprintf(s, sizeof s, "%.1f h", t / 3600);
    return s;
}

std::string short_num(double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%.4g", v);
    return s;
}

std::string alpha_axis_name(const std::string& map) { return map == "roughness" ? "roughness" : "alpha"; }

std::string size_text(const PlannedTable& t) {
    std::string s = std::to_string(t.request.width) + "x" + std::to_string(t.request.height);
    if (t.request.kind == "dielectric") s += "x" + std::to_string(t.depth);
    return s;
}

}  // namespace

std::string plan_text(const Plan& p) {
    std::ostringstream o;
    size_t n_mat = p.no_table.size();
    std::set<std::string> served;
    for (const auto& t : p.tables)
        for (const auto& m : t.materials) served.insert(m);
    n_mat += served.size();
    std::vector<std::string> all_models = model_names();
    o << "plan for " << p.scene << " (" << p.source << "): " << n_mat << " material" << (n_mat == 1 ? "" : "s") << ", "
      << p.tables.size() << " table" << (p.tables.size() == 1 ? "" : "s");
    if (!p.models.empty())
        o << "; kernels built for " << join(p.models) << " only (" << p.models.size() << " of " << all_models.size()
          << " models)";
    o << "\n";
    double total_s = 0, total_samples = 0, peak_mem = 0, disk = 0;
    for (const auto& t : p.tables) {
        const LutRequest& r = t.request;
        o << "\n  " << t.file << "   " << r.kind << ", " << r.model << ", Fresnel ";
        if (r.kind == "dielectric") o << "exact dielectric at each eta";
        else if (r.kind == "dfg" || r.kind == "dfg-ms") o << "factored out (split sum)";
        else if (r.kind == "albedo" || r.kind == "eavg") o << "none (F = 1: each lobe's Fresnel enters at render time)";
        else o << r.fresnel << (r.wavelength_nm > 0 ? " at " + short_num(r.wavelength_nm) + " nm" : "");
        o << "\n";
        o << "      axes      ";
        const std::string an = alpha_axis_name(r.alpha_map);
        const std::string alpha_axis = an + " " + short_num(r.alpha_lo) + ".." + short_num(r.alpha_hi) + " (" +
                                       std::to_string(r.kind == "eavg" ? r.width : r.height) + ")";
        if (r.kind == "eavg") o << alpha_axis;
        else o << "mu 0..1 (" << r.width << ", " << r.mu_map << ") x " << alpha_axis;
        if (r.kind == "dielectric")
            o << " x eta " << short_num(t.eta_lo) << ".." << short_num(t.eta_hi) << " (" << t.depth << ")";
        auto range = [](Interval v) {
            return v.lo == v.hi ? short_num(v.lo) : short_num(v.lo) + ".." + short_num(v.hi);
        };
        o << "\n      scene     alpha " << range(t.alpha);
        if (t.eta) o << ", eta " << range(*t.eta);
        o << (t.alpha.lo == t.alpha.hi && (!t.eta || t.eta->lo == t.eta->hi)
                  ? " (one texel centred on each value)\n"
                  : " (the first and last texel centres sit on the scene's extremes)\n");
        o << "      serves    " << join(t.serves) << "\n";
        o << "      estimate  " << size_text(t) << ", " << human_count(double(t.samples_total)) << " samples ("
          << r.samples << " per cell), " << human_seconds(t.est_seconds) << ", memory "
          << human_bytes(double(t.est_memory)) << ", file " << human_bytes(double(t.file_bytes)) << "\n";
        if (!t.unavailable.empty()) o << "      NOT AVAILABLE " << t.unavailable << "\n";
        total_s += t.est_seconds;
        total_samples += double(t.samples_total);
        peak_mem = std::max(peak_mem, double(t.est_memory));
        disk += double(t.file_bytes);
    }
    o << "\nmaterials:\n";
    for (const auto& m : p.materials) {
        if (m.lobes.empty()) continue;
        o << "  " << m.name << ":";
        for (const auto& l : m.lobes) {
            o << " " << l.role << " (" << l.model_name << ", alpha " << short_num(l.alpha.lo)
              << (l.alpha.lo == l.alpha.hi ? "" : ".." + short_num(l.alpha.hi));
            if (l.eta) o << ", eta " << short_num(l.eta->lo) << (l.eta->lo == l.eta->hi ? "" : ".." + short_num(l.eta->hi));
            o << ", Fresnel " << l.fresnel << ")";
            if (&l != &m.lobes.back()) o << ";";
        }
        o << "\n";
        for (const auto& n : m.notes) o << "      " << n << "\n";
    }
    if (!p.no_table.empty()) {
        o << "\nno table needed:\n";
        for (const auto& m : p.no_table) o << "  " << m << "\n";
    }
    if (!p.warnings.empty()) {
        o << "\nwarnings:\n";
        for (const auto& w : p.warnings) o << "  warning: " << w << "\n";
    }
    o << "\ntotal: " << p.tables.size() << " tables, " << human_count(total_samples) << " samples, about "
      << human_seconds(total_s + p.build_seconds) << " (" << human_seconds(total_s) << " integrating at "
      << human_count(p.samples_per_second) << " samples/s: " << p.throughput_basis << "; "
      << human_seconds(p.build_seconds) << " for " << p.programs << " kernel build" << (p.programs == 1 ? "" : "s")
      << ", cached by PoCL after the first run), peak memory " << human_bytes(peak_mem) << ", " << human_bytes(disk)
      << " on disk\n";
    return o.str();
}

std::string plan_json(const Plan& p) {
    nlohmann::ordered_json j;
    j["command"] = "plan";
    j["scene"] = p.scene;
    j["source"] = p.source;
    j["models"] = p.models;
    j["all_models"] = model_names();
    j["tables"] = nlohmann::ordered_json::array();
    double total_s = 0, total_samples = 0;
    for (const auto& t : p.tables) {
        const LutRequest& r = t.request;
        nlohmann::ordered_json a = nlohmann::ordered_json::array();
        if (r.kind != "eavg") a.push_back({{"name", "mu"}, {"mapping", r.mu_map}, {"lo", 0.0}, {"hi", 1.0}, {"size", r.width}});
        a.push_back({{"name", alpha_axis_name(r.alpha_map)},
                     {"mapping", r.alpha_map == "roughness" ? "alpha = r^2" : "alpha = v"},
                     {"lo", r.alpha_lo},
                     {"hi", r.alpha_hi},
                     {"size", r.kind == "eavg" ? r.width : r.height}});
        if (r.kind == "dielectric")
            a.push_back({{"name", "eta"}, {"mapping", "eta = e"}, {"lo", t.eta_lo}, {"hi", t.eta_hi}, {"size", t.depth}});
        nlohmann::ordered_json e = {{"file", t.file},
                  {"kind", r.kind},
                  {"model", r.model},
                  {"fresnel", r.fresnel},
                  {"axes", a},
                  {"size", size_text(t)},
                  {"alpha_range", {t.alpha.lo, t.alpha.hi}},
                  {"samples_per_cell", r.samples},
                  {"precision", precision_name(r.precision)},
                  {"cells", t.cells},
                  {"samples_total", t.samples_total},
                  {"estimated_seconds", t.est_seconds},
                  {"estimated_memory_bytes", t.est_memory},
                  {"estimated_file_bytes", t.file_bytes},
                  {"serves", t.serves},
                  {"materials", t.materials},
                  {"request_hash", t.hash},
                  {"available", t.unavailable.empty()}};
        if (r.wavelength_nm > 0) e["wavelength_nm"] = r.wavelength_nm;
        if (t.eta) e["eta_range"] = {t.eta->lo, t.eta->hi};
        if (!t.unavailable.empty()) e["unavailable"] = t.unavailable;
        j["tables"].push_back(e);
        total_s += t.est_seconds;
        total_samples += double(t.samples_total);
    }
    j["materials"] = nlohmann::ordered_json::array();
    for (const auto& m : p.materials) {
        nlohmann::ordered_json lobes = nlohmann::ordered_json::array();
        for (const auto& l : m.lobes) {
            nlohmann::ordered_json x = {{"role", l.role}, {"model", l.model}, {"fresnel", l.fresnel},
                                        {"alpha_range", {l.alpha.lo, l.alpha.hi}}, {"kinds", l.kinds}};
            if (l.eta) x["eta_range"] = {l.eta->lo, l.eta->hi};
            lobes.push_back(x);
        }
        j["materials"].push_back({{"name", m.name}, {"lobes", lobes}, {"notes", m.notes}});
    }
    j["no_table"] = p.no_table;
    j["warnings"] = p.warnings;
    j["estimate"] = {{"seconds", total_s + p.build_seconds},
                     {"integration_seconds", total_s},
                     {"kernel_programs", p.programs},
                     {"kernel_build_seconds", p.build_seconds},
                     {"samples", total_samples},
                     {"samples_per_second", p.samples_per_second},
                     {"basis", p.throughput_basis}};
    return j.dump(2) + "\n";
}

}  // namespace brdfbake

// glTF 2.0 scenes (.gltf, .glb) read with tinygltf and mapped to brdfbake lobes.
//
// The core metallic-roughness material is GGX with alpha = roughness^2 (Smith height-correlated
// masking-shadowing, as the glTF specification's appendix B). A metal is a conductor lobe whose
// Fresnel is Schlick with f0 = baseColor: its albedo and average albedo tables are computed with
// F = 1 and the Fresnel enters at render time. A non-metal is a dielectric interface with eta 1.5
// (or KHR_materials_ior): its rough reflection (and, with transmission, transmission) albedo comes
// from the dielectric table. Textures are not read: a textured factor spans [0, factor]. The
// extensions that change which tables are needed are mapped; every other extension is reported
// by name. docs/scenes.md has the table of this mapping.
#include <tiny_gltf.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "brdfbake/error.h"
#include "models/key_reader.h"
#include "scene/scene.h"

namespace brdfbake {
namespace {

/// Images are not needed (textures only widen ranges); skip decoding them.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ';';
    while (!s.empty() && (s.back() == ';' || s.back() == ' ')) s.pop_back();
    return s;
}

/// The material extensions whose effect on tables is modelled.
const std::set<std::string> kModelled = {"KHR_materials_ior",          "KHR_materials_specular",
                                         "KHR_materials_transmission", "KHR_materials_volume",
                                         "KHR_materials_clearcoat",    "KHR_materials_anisotropy",
                                         "KHR_materials_unlit",        "KHR_materials_sheen"};

/// Extensions known not to change any table (geometry, textures, lights): reported, nothing else.
const std::map<std::string, std::string> kNoTableEffect = {
    {"KHR_texture_transform", "texture coordinates"},
    {"KHR_texture_basisu", "texture compression"},
    {"EXT_texture_webp", "texture format"},
    {"EXT_texture_avif", "texture format"},
    {"KHR_mesh_quantization", "geometry encoding"},
    {"KHR_draco_mesh_compression", "geometry compression"},
    {"EXT_meshopt_compression", "geometry compression"},
    {"EXT_mesh_gpu_instancing", "instancing"},
    {"KHR_lights_punctual", "lights"},
    {"KHR_materials_variants", "material variants (every variant's material is planned)"},
    {"KHR_animation_pointer", "animation"},
    {"KHR_xmp_json_ld", "metadata"},
    {"KHR_materials_emissive_strength", "emission"},
};

/// Material extensions that need tables brdfbake does not compute.
const std::map<std::string, std::string> kNotModelled = {
    {"KHR_materials_iridescence", "thin-film interference changes the Fresnel term; tables are computed without it"},
    {"KHR_materials_dispersion", "the index of refraction varies with wavelength; only the base ior is tabulated"},
    {"KHR_materials_diffuse_transmission", "diffuse transmission needs no microfacet table and is not modelled"},
    {"KHR_materials_pbrSpecularGlossiness", "the specular-glossiness workflow is not modelled; the material is "
                                            "planned from its metallic-roughness values"},
};

double number(const tinygltf::Value& v, const std::string& key, double fallback) {
    if (!v.IsObject() || !v.Has(key)) return fallback;
    const tinygltf::Value& x = v.Get(key);
    if (!x.IsNumber()) return fallback;
    return x.GetNumberAsDouble();
}

bool has_texture(const tinygltf::Value& v, const std::string& key) { return v.IsObject() && v.Has(key) && v.Get(key).IsObject(); }

std::vector<double> number_array(const tinygltf::Value& v, const std::string& key, std::vector<double> fallback) {
    if (!v.IsObject() || !v.Has(key) || !v.Get(key).IsArray()) return fallback;
    const tinygltf::Value& a = v.Get(key);
    std::vector<double> out;
    for (size_t i = 0; i < a.ArrayLen(); ++i)
        if (a.Get(int(i)).IsNumber()) out.push_back(a.Get(int(i)).GetNumberAsDouble());
    return out;
}

/// A factor with an optional texture multiplying it: the range the material can take.
Interval factor_range(double factor, bool textured) { return textured ? Interval{0.0, factor} : Interval{factor, factor}; }

Interval square(Interval r) { return {r.lo * r.lo, r.hi * r.hi}; }

std::string fmt(double v) { return format_number(v); }

std::string range_text(Interval r) { return r.lo == r.hi ? fmt(r.lo) : "[" + fmt(r.lo) + ", " + fmt(r.hi) + "]"; }

void check_factor(const std::string& where, const std::string& what, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi)
        throw Error(where + ": " + what + " " + fmt(v) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
}

SceneMaterial map_material(const tinygltf::Material& mat, const std::string& name, const std::string& file,
                           std::vector<std::string>& warnings) {
    const std::string where = "glTF '" + file + "': material '" + name + "'";
    SceneMaterial out;
    out.name = name;
    const std::string ggx = model_without_alpha("ggx");

    for (const auto& e : mat.extensions) {
        if (kModelled.count(e.first)) continue;
        auto nt = kNoTableEffect.find(e.first);
        if (nt != kNoTableEffect.end()) {
            warnings.push_back("material '" + name + "': " + e.first + " is not modelled (" + nt->second +
                               "; does not change the tables)");
            continue;
        }
        auto nm = kNotModelled.find(e.first);
        warnings.push_back("material '" + name + "': " + e.first + " is not modelled" +
                           (nm != kNotModelled.end() ? " (" + nm->second + ")" : "") + "; its other lobes are planned");
    }
    auto ext = [&](const char* key) -> const tinygltf::Value* {
        auto it = mat.extensions.find(key);
        return it == mat.extensions.end() ? nullptr : &it->second;
    };
    if (ext("KHR_materials_unlit")) {
        out.notes.push_back("KHR_materials_unlit: no BRDF, no table");
        return out;
    }

    const auto& pbr = mat.pbrMetallicRoughness;
    const bool mr_tex = pbr.metallicRoughnessTexture.index >= 0;
    check_factor(where, "metallicFactor", pbr.metallicFactor, 0, 1);
    check_factor(where, "roughnessFactor", pbr.roughnessFactor, 0, 1);
    const Interval metallic = factor_range(pbr.metallicFactor, mr_tex);
    const Interval roughness = factor_range(pbr.roughnessFactor, mr_tex);
    Interval alpha = square(roughness);
    if (mr_tex) out.notes.push_back("metallicRoughnessTexture: roughness " + range_text(roughness) + ", metallic " + range_text(metallic));
    if (roughness.lo == 0.0) out.notes.push_back("roughness 0 is computed at the alpha floor");

    // Anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha (KHR_materials_anisotropy).
    if (const tinygltf::Value* a = ext("KHR_materials_anisotropy")) {
        const double strength = number(*a, "anisotropyStrength", 0.0);
        check_factor(where, "anisotropyStrength", strength, 0, 1);
        const Interval s = factor_range(strength, has_texture(*a, "anisotropyTexture"));
        if (s.hi > 0.0) {
            const double at_hi = alpha.hi + (1.0 - alpha.hi) * s.hi * s.hi;
            alpha.hi = std::max(alpha.hi, at_hi);
            out.notes.push_back("KHR_materials_anisotropy: isotropic tables over [alpha_b, alpha_t] = " + range_text(alpha));
            warnings.push_back("material '" + name + "': KHR_materials_anisotropy is approximated: the tables are "
                               "isotropic and cover alpha up to alpha_t = " + fmt(at_hi));
        }
    }

    // Index of refraction.
    double ior = 1.5;
    if (const tinygltf::Value* e = ext("KHR_materials_ior")) {
        ior = number(*e, "ior", 1.5);
        if (!std::isfinite(ior) || ior < 1.0 || ior > 1e3)
            throw Error(where + ": KHR_materials_ior: ior " + fmt(ior) + " is out of range [1, 1000]");
    }

    // Metal lobe.
    if (metallic.hi > 0.0) {
        Lobe l;
        l.role = "metal";
        l.model = ggx;
        l.model_name = "ggx";
        l.fresnel = "schlick:f0=baseColor";
        l.alpha = alpha;
        l.kinds = default_lobe_kinds(l);
        out.lobes.push_back(l);
    }

    // Dielectric lobe (the non-metal part).
    if (metallic.lo < 1.0) {
        double transmission = 0.0;
        bool transmission_tex = false;
        if (const tinygltf::Value* t = ext("KHR_materials_transmission")) {
            transmission = number(*t, "transmissionFactor", 0.0);
            check_factor(where, "transmissionFactor", transmission, 0, 1);
            transmission_tex = has_texture(*t, "transmissionTexture");
        }
        const bool transmissive = transmission > 0.0 || transmission_tex;
        double specular = 1.0;
        bool specular_tex = false, tinted = false;
        if (const tinygltf::Value* s = ext("KHR_materials_specular")) {
            specular = number(*s, "specularFactor", 1.0);
            check_factor(where, "specularFactor", specular, 0, 1);
            specular_tex = has_texture(*s, "specularTexture");
            const std::vector<double> color = number_array(*s, "specularColorFactor", {1, 1, 1});
            for (double c : color) check_factor(where, "specularColorFactor", c, 0, 1e3);
            tinted = has_texture(*s, "specularColorTexture") ||
                     std::any_of(color.begin(), color.end(), [](double c) { return c != 1.0; });
        }
        const bool reflects = (specular > 0.0 || specular_tex) && ior > 1.0;
        if (!reflects && !transmissive) {
            out.notes.push_back(ior == 1.0 ? "ior 1: the dielectric interface does not reflect, no table"
                                           : "KHR_materials_specular: specularFactor 0, no specular reflection");
        } else if (ior == 1.0) {
            out.notes.push_back("ior 1: index-matched interface, transmission albedo 1, no table");
        } else {
            Lobe l;
            l.role = transmissive ? "transmission" : "dielectric";
            l.model = ggx;
            l.model_name = "ggx";
            l.fresnel = "dielectric:eta=" + fmt(ior);
            l.alpha = alpha;
            l.eta = Interval{ior, ior};
            l.kinds = default_lobe_kinds(l);
            if (specular != 1.0 || specular_tex)
                out.notes.push_back("KHR_materials_specular: specularFactor " + range_text(factor_range(specular, specular_tex)) +
                                    " scales the reflection albedo (linear in F), same table");
            if (tinted) {
                // A tinted F0 makes F Schlick with a per-channel f0: E = f0 A + B (split-sum terms).
                l.kinds.push_back(&table_kind(TableKindId::Dfg));
                out.notes.push_back("KHR_materials_specular: specularColor tints F0 (Schlick), E = f0 A + B from dfg");
            }
            if (transmissive) {
                // Rough glass's multiple-scattering compensation (Kulla and Conty 2017) needs the
                // average of R + T over mu from both sides, as Cycles' ggx_glass_Eavg.
                l.kinds.push_back(&table_kind(TableKindId::DielectricEavg));
                out.notes.push_back("KHR_materials_transmission: transmission " +
                                    range_text(factor_range(transmission, transmission_tex)) +
                                    ", rough transmission from the dielectric table");
                bool volume = false;
                if (const tinygltf::Value* v = ext("KHR_materials_volume")) {
                    const double thickness = number(*v, "thicknessFactor", 0.0);
                    if (!std::isfinite(thickness) || thickness < 0)
                        throw Error(where + ": KHR_materials_volume: thicknessFactor " + fmt(thickness) + " is negative");
                    volume = thickness > 0.0 || has_texture(*v, "thicknessTexture");
                }
                out.notes.push_back(volume ? "KHR_materials_volume: refracting volume, both sides of the interface (eta and 1/eta)"
                                           : "thin-walled (no volume): the outside of the interface only");
            } else if (ext("KHR_materials_volume")) {
                out.notes.push_back("KHR_materials_volume without transmission has no effect");
            }
            out.lobes.push_back(l);
        }
    }

    // Clear coat: a GGX dielectric layer with ior 1.5 (fixed by KHR_materials_clearcoat) and its own
    // roughness; its reflection albedo weights the base by 1 - E_coat.
    if (const tinygltf::Value* c = ext("KHR_materials_clearcoat")) {
        const double factor = number(*c, "clearcoatFactor", 0.0);
        check_factor(where, "clearcoatFactor", factor, 0, 1);
        if (factor > 0.0 || has_texture(*c, "clearcoatTexture")) {
            const double cr = number(*c, "clearcoatRoughnessFactor", 0.0);
            check_factor(where, "clearcoatRoughnessFactor", cr, 0, 1);
            Lobe l;
            l.role = "clearcoat";
            l.model = ggx;
            l.model_name = "ggx";
            l.fresnel = "dielectric:eta=1.5";
            const Interval r = factor_range(cr, has_texture(*c, "clearcoatRoughnessTexture"));
            l.alpha = square(r);
            l.eta = Interval{1.5, 1.5};
            l.kinds = default_lobe_kinds(l);
            out.notes.push_back("KHR_materials_clearcoat: GGX coat, eta 1.5, roughness " + range_text(r));
            out.lobes.push_back(l);
        }
    }
    // Sheen: the Charlie lobe of Estevez and Kulla 2017 with alpha = sheenRoughness^2 and the
    // specification's visibility (charlie), layered over the rest; its directional albedo scales
    // the layer beneath (KHR_materials_sheen, "Sheen layering"). A black sheen adds nothing.
    if (const tinygltf::Value* s = ext("KHR_materials_sheen")) {
        const std::vector<double> color = number_array(*s, "sheenColorFactor", {0, 0, 0});
        for (double c : color) check_factor(where, "KHR_materials_sheen: sheenColorFactor", c, 0, 1);
        const double sr = number(*s, "sheenRoughnessFactor", 0.0);
        check_factor(where, "KHR_materials_sheen: sheenRoughnessFactor", sr, 0, 1);
        const bool colored = has_texture(*s, "sheenColorTexture") ||
                             std::any_of(color.begin(), color.end(), [](double c) { return c > 0.0; });
        if (!colored) {
            out.notes.push_back("KHR_materials_sheen: sheenColorFactor 0, no sheen, no table");
        } else {
            const Interval r = factor_range(sr, has_texture(*s, "sheenRoughnessTexture"));
            Lobe l;
            l.role = "sheen";
            l.model = model_without_alpha("sheen");
            l.model_name = "sheen";
            l.alpha = square(r);
            l.kinds = default_lobe_kinds(l);
            out.notes.push_back("KHR_materials_sheen: Charlie sheen, sheenRoughness " + range_text(r) +
                                ", charlie visibility; its albedo scales the base (1 - max(sheenColor) E)");
            if (r.lo == 0.0) out.notes.push_back("sheenRoughness 0 is computed at the alpha floor");
            out.lobes.push_back(l);
        }
    }
    if (out.lobes.empty() && out.notes.empty()) out.notes.push_back("no lobe needs a table");
    return out;
}

}  // namespace

Scene load_gltf_scene(const std::string& path) {
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe) throw Error("cannot read scene '" + path + "': " + std::strerror(errno));
    }
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 ||
                                             path.compare(path.size() - 4, 4, ".GLB") == 0);
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                    : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    } catch (const std::exception& e) {
        err = e.what();
        ok = false;
    }
    if (!ok) throw Error("glTF '" + path + "' cannot be read: " + (err.empty() ? std::string("invalid file") : one_line(err)));

    Scene scene;
    scene.path = path;
    scene.source = "glTF 2.0";
    if (!warn.empty()) scene.warnings.push_back("glTF reader: " + one_line(warn));

    // Only the materials that a mesh primitive uses (all of them in a file without meshes: a
    // material library); a primitive without a material uses the glTF default material.
    std::set<int> used;
    bool default_used = false;
    for (const auto& mesh : model.meshes)
        for (const auto& prim : mesh.primitives) {
            if (prim.material < 0) default_used = true;
            else if (prim.material >= int(model.materials.size()))
                throw Error("glTF '" + path + "': mesh '" + mesh.name + "' refers to material " +
                            std::to_string(prim.material) + ", which does not exist");
            else used.insert(prim.material);
        }
    const bool library = model.meshes.empty();

    std::set<std::string> material_exts;
    std::map<std::string, int> seen_names;
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const auto& mat = model.materials[i];
        std::string name = mat.name.empty() ? "material " + std::to_string(i) : mat.name;
        if (seen_names[name]++) name += " #" + std::to_string(i);
        if (!library && !used.count(int(i))) {
            SceneMaterial m;
            m.name = name;
            m.notes.push_back("not used by any mesh primitive, not planned");
            scene.materials.push_back(m);
            continue;
        }
        for (const auto& e : mat.extensions) material_exts.insert(e.first);
        scene.materials.push_back(map_material(mat, name, path, scene.warnings));
    }
    if (default_used) {
        tinygltf::Material def;  // glTF defaults: metallic 1, roughness 1
        scene.materials.push_back(map_material(def, "(glTF default material)", path, scene.warnings));
    }
    if (scene.materials.empty()) throw Error("glTF '" + path + "' has no materials and no meshes: nothing to plan");

    for (const auto& e : model.extensionsUsed) {
        if (material_exts.count(e) || kModelled.count(e)) continue;  // reported per material, or modelled
        auto nt = kNoTableEffect.find(e);
        if (nt != kNoTableEffect.end())
            scene.warnings.push_back("extension " + e + " is not modelled (" + nt->second + "; does not change the tables)");
        else
            scene.warnings.push_back("extension " + e + " is not modelled" +
                                     (kNotModelled.count(e) ? " (" + kNotModelled.at(e) + ")" : ""));
    }
    return scene;
}

}  // namespace brdfbake

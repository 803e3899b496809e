#include "scene/gltf_extensions.h"

#include <map>
#include <set>

namespace brdfbake {
namespace gltf_extensions {
namespace {

/// The material extensions whose effect on tables is modelled.
const std::set<std::string> kModelled = {"KHR_materials_ior",          "KHR_materials_specular",
                                         "KHR_materials_transmission", "KHR_materials_volume",
                                         "KHR_materials_clearcoat",    "KHR_materials_anisotropy",
                                         "KHR_materials_unlit",        "KHR_materials_sheen",
                                         "KHR_materials_variants",
                                         "KHR_materials_iridescence"};

/// Extensions known not to change any table (geometry, textures, lights): reported once, nothing else.
const std::map<std::string, std::string> kNoTableEffect = {
    {"KHR_texture_transform", "texture coordinates"},
    {"KHR_texture_basisu", "texture compression"},
    {"EXT_texture_webp", "texture format"},
    {"EXT_texture_avif", "texture format"},
    {"KHR_mesh_quantization", "geometry encoding"},
    {"KHR_draco_mesh_compression", "geometry compression; geometry is not read"},
    {"EXT_meshopt_compression", "geometry compression; geometry is not read"},
    {"EXT_mesh_gpu_instancing", "instancing"},
    {"KHR_lights_punctual", "lights"},
    {"KHR_animation_pointer", "animation"},
    {"KHR_xmp_json_ld", "metadata"},
    {"KHR_materials_emissive_strength", "emission"},
};

/// Material extensions that need tables brdfbake does not compute.
const std::map<std::string, std::string> kNotModelled = {
    {"KHR_materials_dispersion", "the index of refraction varies with wavelength; only the base ior is tabulated"},
    {"KHR_materials_diffuse_transmission", "diffuse transmission needs no microfacet table and is not modelled"},
    {"KHR_materials_pbrSpecularGlossiness", "the specular-glossiness workflow is not modelled; the material is "
                                            "planned from its metallic-roughness values"},
};

}  // namespace

bool modelled(const std::string& name) { return kModelled.count(name) > 0; }

std::string unmodelled_text(const std::string& name, bool in_material) {
    auto nt = kNoTableEffect.find(name);
    if (nt != kNoTableEffect.end()) return " (" + nt->second + "; does not change the tables)";
    auto nm = kNotModelled.find(name);
    return (nm != kNotModelled.end() ? " (" + nm->second + ")" : "") +
           std::string(in_material ? "; its other lobes are planned" : "");
}

}  // namespace gltf_extensions
}  // namespace brdfbake

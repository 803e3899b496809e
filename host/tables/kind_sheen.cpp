// The directional albedo of the Charlie sheen lobe, E(mu_o, sheenRoughness), with either
// visibility of the sheen model (include/brdfbake/brdf/sheen.h): the table that scales the layer
// beneath a sheen (glTF's albedo scaling, KHR_materials_sheen "Sheen layering") and the sheen
// term of image-based lighting (Filament's cloth DFG channel). The glTF Sample Viewer's
// lut_charlie and lut_sheen_E clamp the visibility: kind_sheen_viewer.cpp. docs/models.md says
// which visibility each engine's table uses.
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

std::vector<std::string> sheen_program(const LutRequest& r) { return {"albedo|" + r.model + "|none"}; }

void validate_sheen(const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    if (m.id != BB_MODEL_SHEEN)
        throw Error("the sheen-albedo table is of the sheen model: --model sheen or sheen:visibility=charlie|ashikhmin, "
                    "not '" + m.name + "'");
    // [EK17]'s fitted Lambda is defined for alpha = sheenRoughness^2 in (0, 1].
    if (r.alpha_hi > 1.0)
        throw Error("--alpha-range of a sheen-albedo table must lie within [0, 1] (sheenRoughness and alpha = "
                    "sheenRoughness^2 are at most 1)");
}

Table compute_sheen(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    const bool charlie = m.params[BB_SHEEN_VISIBILITY] == BB_SHEEN_V_CHARLIE;
    Table t = directional_albedo_table(
        engine, r, m, f,
        std::string("sheen directional albedo E(mu_o, ") + (r.alpha_map == "roughness" ? "sheenRoughness" : "alpha") +
            ") of the Charlie distribution with the " + (charlie ? "charlie (Estevez-Kulla fitted Lambda)" : "ashikhmin (Neubelt-Pettineo)") +
            " visibility, alpha = sheenRoughness^2");
    t.attributes["visibility"] = charlie ? "charlie" : "ashikhmin";
    return t;
}

}  // namespace

TableKind sheen_albedo_kind() {
    TableKind k(TableKindId::SheenAlbedo, "sheen-albedo",
                "sheen directional albedo E(mu_o, sheenRoughness) of the Charlie lobe, either visibility (2D)",
                sheen_program, compute_sheen);
    k.plan_fresnel = "none (the sheen lobe has no Fresnel term)";
    k.required_model = "sheen";
    k.lobe_requirement = "the sheen-albedo table needs a sheen lobe (model sheen, KHR_materials_sheen)";
    k.tileable = true;
    k.validate = validate_sheen;
    return k;
}

}  // namespace tables
}  // namespace brdfbake

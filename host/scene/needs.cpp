// Which tables a lobe needs: its default kinds, and the kinds a scene names in "tables", checked
// against what the lobe has (the registry entry's requirement).
#include <algorithm>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "models/key_reader.h"
#include "scene/scene.h"
#include "scene/scene_text.h"

namespace brdfbake {

std::vector<const TableKind*> default_lobe_kinds(const Lobe& lobe) {
    // A dielectric interface: its reflection and transmission over (mu, alpha, eta). Any other
    // lobe: the albedo with F = 1 and its average, which serve every Fresnel at render time.
    if (lobe.eta) return {&table_kind(TableKindId::Dielectric)};
    // A film over a range of thicknesses (a scene's "thickness": [lo, hi]): its table over them.
    if (lobe.thickness && lobe.thickness->lo < lobe.thickness->hi) return {&table_kind(TableKindId::ThinFilm)};
    // A lobe of a model that has its own kind (sheen: its directional albedo, which scales the
    // layer beneath): that kind.
    for (const TableKind* kind : table_kinds())
        if (!kind->required_model.empty() && kind->required_model == lobe.model_name) return {kind};
    return {&table_kind(TableKindId::Albedo), &table_kind(TableKindId::Eavg)};
}

const TableKind& lobe_table_kind(const std::string& name, const Lobe& lobe, const std::string& ctx) {
    const TableKind* kind = find_table_kind(name);
    if (!kind) throw Error(ctx + ": unknown table kind '" + name + "' in 'tables' (known: " + table_kind_names() + ")");
    // The thin-film kind's z axis is the film's thickness, every other z axis the lobe's eta.
    const bool film = kind->id == TableKindId::ThinFilm;
    if (film && !lobe.thickness) throw Error(ctx + ": " + kind->lobe_requirement);
    if (kind->eta_axis && !film && !lobe.eta) throw Error(ctx + ": " + kind->lobe_requirement);
    if (!film && kind->bakes_lobe_fresnel && lobe.thickness && lobe.thickness->lo < lobe.thickness->hi)
        throw Error(ctx + ": a " + kind->name + " table holds one film thickness; give thickness=NM in the Fresnel spec, "
                    "or name the 'thin-film' table for the range");
    if (kind->needs_conductor_fresnel && !scene_text::is_conductor_fresnel(lobe.fresnel))
        throw Error(ctx + ": " + kind->lobe_requirement);
    if (!kind->required_model.empty() && lobe.model_name != kind->required_model)
        throw Error(ctx + ": " + kind->lobe_requirement);
    return *kind;
}

std::string alpha_floor_note(double alpha_lo) {
    return "alpha " + format_number(alpha_lo) + " is planned at the alpha floor " + format_number(double(BB_ALPHA_MIN)) +
           (alpha_lo == 0.0 ? " (alpha 0 is the smooth limit; a texel centre is never at 0, and the floor is the "
                              "nearest the tables come to it)"
                            : "");
}

std::vector<std::string> kind_names(const std::vector<const TableKind*>& kinds) {
    std::vector<std::string> names;
    for (const TableKind* k : kinds) names.push_back(k->name);
    return names;
}

}  // namespace brdfbake

#include "scene/bake_index.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/version.h"
#include "engine/distributed.h"
#include "models/input_file.h"
#include "scene/bake_folder.h"

namespace brdfbake {

namespace {

using json = BakeIndexJson;

json axis_json(const Axis& a) {
    return {{"name", a.name}, {"mapping", a.mapping}, {"lo", a.lo}, {"hi", a.hi}, {"size", a.size}};
}

json lobe_json(const Lobe& l) {
    json j = {{"role", l.role}, {"model", l.model}, {"fresnel", l.fresnel}, {"alpha_range", {l.alpha.lo, l.alpha.hi}},
              {"kinds", kind_names(l.kinds)}};
    if (l.eta) j["eta_range"] = {l.eta->lo, l.eta->hi};
    if (l.wavelength_nm > 0) j["wavelength_nm"] = l.wavelength_nm;
    return j;
}

json materials_json(const Plan& plan) {
    // The plan's materials: the scene's, with the tables --tables gave them. Each table's
    // materials are looked up once (a scene may hold many materials).
    std::map<std::string, json> files_of;
    for (const auto& t : plan.tables)
        for (const auto& m : t.materials) {
            json& files = files_of[m];
            if (files.is_null()) files = json::array();
            if (files.empty() || files.back() != t.file) files.push_back(t.file);
        }
    json out = json::array();
    for (const auto& m : plan.materials) {
        auto it = files_of.find(m.name);
        json lobes = json::array();
        for (const auto& l : m.lobes) lobes.push_back(lobe_json(l));
        out.push_back({{"name", m.name},
                       {"tables", it == files_of.end() ? json::array() : it->second},
                       {"lobes", lobes},
                       {"notes", m.notes}});
    }
    return out;
}

json settings_json(const SceneSettings& s) {
    return {{"samples", s.samples},       {"mu_texels", s.mu_texels}, {"alpha_texels", s.alpha_texels},
            {"eta_step", s.eta_step},     {"mu_map", s.mu_map},       {"alpha_map", s.alpha_map},
            {"precision", precision_name(s.precision)}, {"format", s.table_format}, {"half", s.half},
            {"tables", s.tables}, {"preset", s.preset}, {"target", s.target}};
}

}  // namespace

std::string bake_index_path(const std::string& folder) {
    return folder.empty() || folder.back() == '/' ? folder + "index.json" : folder + "/index.json";
}

bool bake_index_exists(const std::string& folder) {
    struct stat st;
    return ::stat(bake_index_path(folder).c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

BakeIndexJson read_bake_index(const std::string& folder) {
    const std::string path = bake_index_path(folder);
    json index;
    try {
        index = json::parse(read_input_file(path, "bake index", std::uintmax_t(64) << 20));
    } catch (const json::exception& e) {
        throw Error("'" + path + "' is not a bake index: " + e.what());
    }
    const bool tables_ok = index.is_object() && index.contains("tables") && index["tables"].is_array() &&
                           std::all_of(index["tables"].begin(), index["tables"].end(),
                                       [](const json& e) { return e.is_object() && e.contains("file") && e["file"].is_string(); });
    if (!index.is_object() || !index.contains("brdfbake_index") || !tables_ok)
        throw Error("'" + path + "' is not an index.json that brdfbake bake wrote");
    return index;
}

const BakeIndexJson* bake_index_entry(const BakeIndexJson& index, const std::string& file) {
    if (!index.is_object() || !index.contains("tables") || !index["tables"].is_array()) return nullptr;
    for (const auto& e : index["tables"])
        if (e.is_object() && e.value("file", "") == file) return &e;
    return nullptr;
}

BakeIndexJson new_bake_index(const Plan& plan) {
    return {{"brdfbake_index", 1},
            {"tool", std::string("brdfbake ") + BRDFBAKE_VERSION},
            {"scene", plan.scene},
            {"source", plan.source},
            {"settings", settings_json(plan.settings)},
            {"content_hash_algorithm", kContentHashAlgorithm},
            {"tables", json::array()},
            {"materials", materials_json(plan)},
            {"warnings", plan.warnings}};
}

BakeIndexJson bake_index_table_entry(const PlannedTable& t, const LutRequest& r, const Table& table,
                                     const std::string& content_hash, const std::string& preview,
                                     const std::string& preview_full, double seconds) {
    const TableKind& kind = *t.kind;
    json axes = json::array({axis_json(table.x)});
    if (table.height() > 1 || !kind.one_dimensional) axes.push_back(axis_json(table.y));
    if (table.depth() > 1 || kind.eta_axis) axes.push_back(axis_json(table.z));
    json e = {{"file", t.file},
              {"kind", r.kind},
              {"quantity", table.quantity},
              {"model", r.model},
              {"fresnel", r.fresnel},
              {"size", std::to_string(table.width()) + "x" + std::to_string(table.height()) +
                           (kind.eta_axis ? "x" + std::to_string(table.depth()) : "")},
              {"layout", table.depth() > 1 ? "z-slices stacked along y" : "2D"},
              {"axes", axes},
              {"channels", table.channels},
              {"error_channel", "estimated absolute error per texel"},
              {"max_error", table.max_error()},
              {"samples_per_cell", r.samples},
              {"precision", precision_name(r.precision)},
              {"attributes", table.attributes},
              {"alpha_range", {t.alpha.lo, t.alpha.hi}},
              {"materials", t.materials},
              {"serves", t.serves},
              {"request_hash", t.hash},
              {"content_hash", content_hash},
              {"request", t.key},
              {"seconds", std::round(seconds * 1000) / 1000}};
    if (t.eta) e["eta_range"] = {t.eta->lo, t.eta->hi};
    if (r.wavelength_nm > 0) e["wavelength_nm"] = r.wavelength_nm;
    if (!t.layout.empty()) e["layout"] = t.layout;
    if (!preview.empty()) e["preview"] = preview;
    if (!preview_full.empty()) e["preview_full"] = preview_full;
    return e;
}

void bake_index_set_table(BakeIndexJson& index, const Plan& plan, const BakeIndexJson& entry) {
    // In the plan's order: the tables the index lists, with this one in its place.
    const std::string file = entry.at("file").get<std::string>();
    std::map<std::string, const json*> listed;
    for (const auto& x : index["tables"]) listed[x.value("file", "")] = &x;
    json tables = json::array();
    for (const auto& t : plan.tables) {
        if (t.file == file) tables.push_back(entry);
        else if (auto it = listed.find(t.file); it != listed.end()) tables.push_back(*it->second);
    }
    index["tables"] = std::move(tables);
}

std::string bake_index_text(const BakeIndexJson& index) { return index.dump(2) + "\n"; }

bool write_bake_index(const std::string& folder, const BakeIndexJson& index) {
    const std::string path = bake_index_path(folder), text = bake_index_text(index);
    // The writer rank compares with the file; every rank takes its answer (writing is a
    // collective step in an MPI job).
    std::string same = "0";
    if (dist::is_writer()) {
        std::ifstream in(path, std::ios::binary);
        std::stringstream s;
        if (in) s << in.rdbuf();
        if (in && s.str() == text) same = "1";
    }
    if (dist::exchange(same)[0] == "1") return false;
    write_file_atomically(path, text);
    return true;
}

}  // namespace brdfbake

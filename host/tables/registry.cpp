// The table-kind registry: the list of kinds and the look-ups by name and id.
#include "brdfbake/table_kinds.h"

#include "brdfbake/error.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"

namespace brdfbake {

const std::vector<const TableKind*>& table_kinds() {
    static const std::vector<TableKind> entries = {tables::albedo_kind(),     tables::eavg_kind(),
                                                   tables::dfg_kind(),        tables::dielectric_kind(),
                                                   tables::conductor_kind(),  tables::dfg_ms_kind(),
                                                   tables::sheen_albedo_kind(),
                                                   tables::dielectric_eavg_kind(), tables::gen_schlick_kind(), tables::gen_schlick_ior_kind(),
                                                   tables::dfg_f82_kind(),        tables::sheen_viewer_kind(),
                                                   tables::ltc_kind(),
                                                   tables::sheen_ltc_kind(),
                                                   tables::thin_film_kind()};
    static const std::vector<const TableKind*> kinds = [] {
        std::vector<const TableKind*> list;
        for (const TableKind& k : entries) list.push_back(&k);
        return list;
    }();
    return kinds;
}

const TableKind* find_table_kind(const std::string& name) {
    for (const TableKind* k : table_kinds())
        if (k->name == name) return k;
    return nullptr;
}

std::string table_kind_names() {
    std::string list;
    for (const TableKind* k : table_kinds()) list += (list.empty() ? "" : ", ") + k->name;
    return list;
}

const TableKind& table_kind(const std::string& name) {
    if (const TableKind* k = find_table_kind(name)) return *k;
    std::vector<std::string> names;
    for (const TableKind* k : table_kinds()) names.push_back(k->name);
    throw Error(unknown_name_message("table kind", name, names, "known", table_kind_names()));
}

Table read_table(const std::string& path) {
    Table t = read_table_file(path);
    if (find_table_kind(t.kind) == nullptr && t.kind != "reciprocity")
        throw Error("'" + path + "': its kind '" + t.kind + "' is not a table brdfbake writes (known: " +
                    table_kind_names() + ", reciprocity)");
    return t;
}

const TableKind& table_kind(TableKindId id) {
    for (const TableKind* k : table_kinds())
        if (k->id == id) return *k;
    throw Error("internal error: a table kind without a registry entry");
}

}  // namespace brdfbake

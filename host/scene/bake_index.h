// A bake folder's index.json: its format, written and read here only. `bake` writes it (the
// scene, the settings, one entry per table with its request and content hash, the materials and
// the tables they use); `bake` reads it back to skip what is up to date, and the bake report
// (host/plot/bake_report.cpp) reads it to draw DIR/index.html. docs/scenes.md documents the fields.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "brdfbake/table.h"
#include "scene/scene.h"

namespace brdfbake {

/// The index as JSON, its keys in the order written (a readable file).
using BakeIndexJson = nlohmann::ordered_json;

/// FOLDER/index.json.
std::string bake_index_path(const std::string& folder);

/// Whether FOLDER holds an index.json (a regular file).
bool bake_index_exists(const std::string& folder);

/// Reads FOLDER/index.json: a JSON object with "brdfbake_index" and a "tables" array of objects.
/// Throws Error naming the file when it is missing, too large (64 MiB), not JSON or not an index.
BakeIndexJson read_bake_index(const std::string& folder);

/// The index's entry for `file`, or nullptr.
const BakeIndexJson* bake_index_entry(const BakeIndexJson& index, const std::string& file);

/// The index of `plan` with no tables yet (bake_index_set_table adds them).
BakeIndexJson new_bake_index(const Plan& plan);

/// The entry of a table just computed: what it holds (kind, model, axes, error), what asked for
/// it (the request and its hash), the hash of `content_hash` of its file, its preview and the
/// full-size picture beside it of a deep 3D table (relative to the folder; empty: none).
BakeIndexJson bake_index_table_entry(const PlannedTable& planned, const LutRequest& request, const Table& table,
                                     const std::string& content_hash, const std::string& preview,
                                     const std::string& preview_full, double seconds);

/// Puts `entry` into the index's tables, in the plan's order (replacing an entry of its file).
void bake_index_set_table(BakeIndexJson& index, const Plan& plan, const BakeIndexJson& entry);

/// The index as the file holds it.
std::string bake_index_text(const BakeIndexJson& index);

/// Writes FOLDER/index.json atomically when its text differs from the file's; returns whether it
/// wrote.
bool write_bake_index(const std::string& folder, const BakeIndexJson& index);

}  // namespace brdfbake

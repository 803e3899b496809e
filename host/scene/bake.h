// Baking a plan into a folder (`brdfbake bake`): which tables are up to date, computing the
// others (in tiles along the roughness axis, so that progress moves within a table), and
// committing each table with its entry in index.json (host/scene/bake_index.h) so that the index
// and the folder agree after every step, a killed bake included. docs/scenes.md ("Bake folders")
// documents the behaviour; the command line (host/cli/cmd_scene.cpp) parses, calls and prints.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/table.h"
#include "scene/calibration.h"
#include "scene/scene.h"

namespace brdfbake {

struct BakeOptions {
    std::string output;           // the bake folder
    bool force = false;           // recompute tables that are up to date
    double lock_timeout = 600.0;  // seconds to wait for another bake into the same folder
    /// Draws a table's preview picture (PNG) at a path, and returns the path of the full-size
    /// picture it wrote beside it ("" when none: tables shallow enough for one picture); empty: no
    /// previews (--no-previews).
    std::function<std::string(const Table&, const std::string&)> write_preview;
    /// Called at the end, while the folder is still locked, with the engine if one was started
    /// (nullptr when every table was up to date): the bake report. Also when a table's computation
    /// or commit fails, with the error's text as `failure` (empty otherwise), before it is rethrown.
    std::function<void(Engine*, const std::string& failure)> finish;
};

struct BakeResult {
    std::size_t tables = 0;       // tables in the plan
    int computed = 0;             // tables computed by this bake (the others were up to date)
    double max_error = 0.0;       // the largest estimated error of the computed tables
    double build_seconds = 0.0;   // kernel builds
    double seconds = 0.0;         // the whole bake until `finish` was called
    std::string index_path;       // FOLDER/index.json
    /// What the stages took (tables, previews, kernel builds, `finish` as the report with
    /// report_checks 0): for the calibration of estimates (scene/calibration.h).
    BakeTimings timings;
};

/// Bakes `plan` into options.output: locks the folder, skips what is up to date (the same
/// request hash in the index, and the file present with the content hash the index records),
/// computes the rest with an engine made by `make_engine` (called once, only when something is
/// computed) under one ProgressStage, and writes the index after each table. Lines of the log
/// (each table begun and written, warnings) go through progress_message. Throws Error for a plan
/// with a table this build cannot compute, before anything is written.
BakeResult bake_plan(const Plan& plan, const BakeOptions& options,
                     const std::function<std::unique_ptr<Engine>()>& make_engine);

/// The tiles of a table along its roughness axis (rows of a 2D table, texels of a 1D one): each
/// tile is the same request over a sub-range whose texel centres are the full table's.
std::vector<LutRequest> bake_tiles(const TableKind& kind, const LutRequest& request, int max_tiles);

/// Joins tiles computed from bake_tiles back into the table of the full request.
Table stitch_tiles(const TableKind& kind, const LutRequest& request, std::vector<Table>& parts);

}  // namespace brdfbake

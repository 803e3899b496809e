// The bake report: DIR/index.html beside the index.json that `bake` writes, readable offline in any
// browser. It shows the scene and settings, and for each table its preview, axes, size, max error,
// the materials it serves, and the `check` verdict (white furnace, reciprocity, values) of each
// lobe it tabulates, at the ends of the lobe's roughness range. Self-contained: the previews are
// PNG files in DIR/report/, no script, no network.
#pragma once

#include <string>
#include <vector>

#include "brdfbake/check.h"
#include "brdfbake/engine.h"

namespace brdfbake {

struct BakeReportOptions {
    bool checks = true;  // run `check` on each lobe (a fraction of a second per lobe)
    /// Draw a preview into DIR/report/ for a table whose index entry names none (the bake's own
    /// previews, DIR/previews/, are shown where they exist).
    bool draw_missing_previews = true;
    CheckOptions check;  // lighter than `check`'s defaults: see bake_report.cpp
    /// A bake that stopped: why (empty: it did not fail), and the files its plan has, so that the
    /// page names those it did not write.
    std::string failure;
    std::vector<std::string> planned_tables;
    BakeReportOptions();
};

struct BakeReportSummary {
    int tables = 0;
    int previews = 0;  // tables whose preview could be drawn
    int lobes_checked = 0;
    int lobes_failed = 0;  // lobes whose verdict is VIOLATION
};

/// Writes `folder`/index.html and `folder`/report/*.png from `folder`/index.json and the tables it
/// lists. Throws Error if the folder holds no index.json a bake wrote; a table that cannot be read
/// or drawn is reported in the page rather than failing it. Written atomically.
BakeReportSummary write_bake_report(Engine& engine, const std::string& folder, const BakeReportOptions& options);

}  // namespace brdfbake

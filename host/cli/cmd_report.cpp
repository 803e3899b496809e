// `brdfbake report DIR`: the bake report (DIR/index.html) of a folder that `bake` wrote; `bake`
// writes it itself after its tables, and this command redraws it (after a bake with --no-report,
// or to add the lobe checks).
#include <cstdio>

#include "brdfbake/error.h"
#include "cli/cli.h"
#include "plot/bake_report.h"

namespace brdfbake {
namespace {

struct ReportOptions {
    std::string folder;
    bool no_checks = false;
};

int run_report(const ReportOptions& o, const GlobalOptions& g) {
    Engine engine(g.device, g.verbose);
    BakeReportOptions options;
    options.checks = !o.no_checks;
    const BakeReportSummary s = write_bake_report(engine, o.folder, options);
    std::fprintf(stderr, "brdfbake: wrote %s/index.html: %d tables (%d previews), %d lobe checks, %d violations\n",
                 o.folder.c_str(), s.tables, s.previews, s.lobes_checked, s.lobes_failed);
    return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<ReportOptions>(
        app, "report", "the bake report of a bake folder: DIR/index.html with previews, errors and lobe checks",
        global, action, run_report);
    cmd->add_option("folder", o->folder, "a folder that brdfbake bake wrote (with its index.json)")->required();
    cmd->add_flag("--no-checks", o->no_checks, "leave out the check of each lobe");
}

}  // namespace brdfbake

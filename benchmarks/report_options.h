// What the benchmark programs (brdfbake-bench, brdfbake-tradeoff) share on their command line:
// a quick mode, where the report goes, which device runs, and how an error ends the program.
#pragma once

#include <CLI/CLI.hpp>

#include <exception>
#include <functional>
#include <iostream>
#include <string>

#include "brdfbake/error.h"

namespace brdfbake {

struct ReportOptions {
    bool quick = false;  // a small, fast run
    std::string out_dir = BRDFBAKE_BENCH_RESULTS_DIR;  // benchmarks/results (benchmarks/CMakeLists.txt)
    std::string name;    // file name stem of NAME.json and NAME.md
    std::string plot;    // a figure too (.png or .svg), when given
    std::string device;  // OpenCL device selector
};

inline void add_report_options(CLI::App& app, ReportOptions& o, const std::string& quick_help,
                               const std::string& name_help, const std::string& plot_help) {
    app.add_flag("--quick", o.quick, quick_help);
    app.add_option("--out-dir", o.out_dir, "directory for NAME.json and NAME.md")->capture_default_str();
    app.add_option("--name", o.name, name_help);
    app.add_option("--plot", o.plot, plot_help);
    app.add_option("--device", o.device, "OpenCL device selector (see `brdfbake devices`)");
}

/// Runs a program's body; an error is printed as "PROGRAM: error: ..." and gives its exit status
/// (brdfbake::Error's own, else 2).
inline int run_reporting_errors(const char* program, const std::function<int()>& body) {
    try {
        return body();
    } catch (const Error& e) {
        std::cerr << program << ": error: " << e.what() << "\n";
        return e.exit_code();
    } catch (const std::exception& e) {
        std::cerr << program << ": error: " << e.what() << "\n";
        return 2;
    }
}

/// Parses the command line (CLI11 answers --help and usage errors itself), then runs the body
/// as run_reporting_errors does.
inline int parse_and_run(CLI::App& app, int argc, char** argv, const char* program,
                         const std::function<int()>& body) {
    CLI11_PARSE(app, argc, argv);
    return run_reporting_errors(program, body);
}

}  // namespace brdfbake

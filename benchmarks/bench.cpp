// brdfbake-bench: the GGX albedo kernel through PoCL against the OpenMP baseline and the FMA
// peak, kernel build times and scaling (issue 9). Writes NAME.json and NAME.md (and a plot).
//   brdfbake-bench                      full run, results into benchmarks/results/<machine>.*
//   brdfbake-bench --quick --out-dir D  a few seconds on tiny tables (what CI runs)
#include <iostream>

#include "harness/bench.h"
#include "report_options.h"

int main(int argc, char** argv) {
    using namespace brdfbake;
    CLI::App app{"brdfbake-bench: GGX albedo kernel vs the OpenMP baseline and the FMA peak"};
    bool no_build = false;
    ReportOptions report;
    int table = 0;
    std::int64_t samples = 0;
    add_report_options(app, report, "tiny sizes, one run each (a few seconds)",
                       "file name stem (default: the machine, e.g. amd-epyc-2c-avx512)",
                       "also plot time against cells x samples (.png or .svg)");
    app.add_option("--table", table, "throughput table side N (N x N cells; default 64, quick 8)");
    app.add_option("--samples", samples, "samples per cell of the throughput table (default 65536)");
    app.add_flag("--no-build-times", no_build, "skip the cold/warm kernel build figures");
    return parse_and_run(app, argc, argv, "brdfbake-bench", [&] {
        const bool quick = report.quick;
        BenchOptions o = quick ? BenchOptions::quick_options() : BenchOptions();
        o.device = report.device;
        o.build_times = !no_build;
        if (table > 0) o.table = table;
        if (samples > 0) o.samples = std::uint64_t(samples);
        const BenchReport r = run_bench(o, std::cerr);
        std::string name = report.name.empty() ? bench_machine_name() + (quick ? "-quick" : "") : report.name;
        write_bench_report(r, report.out_dir, name);
        if (!report.plot.empty() && r.agreed) write_bench_plot(r, report.plot);
        std::cout << r.markdown;
        std::cerr << "brdfbake-bench: wrote " << report.out_dir << "/" << name << ".json and .md\n";
        return r.agreed ? 0 : 1;
    });
}

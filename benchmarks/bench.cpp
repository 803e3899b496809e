// brdfbake-bench: the GGX albedo kernel through PoCL against the OpenMP baseline and the FMA
// peak, kernel build times and scaling (issue 9). Writes NAME.json and NAME.md (and a plot).
//   brdfbake-bench                      full run, results into benchmarks/results/<machine>.*
//   brdfbake-bench --quick --out-dir D  a few seconds on tiny tables (what CI runs)
#include <CLI/CLI.hpp>

#include <iostream>

#include "harness/bench.h"
#include "brdfbake/error.h"

int main(int argc, char** argv) {
    using namespace brdfbake;
    CLI::App app{"brdfbake-bench: GGX albedo kernel vs the OpenMP baseline and the FMA peak"};
    bool quick = false, no_build = false;
    std::string out_dir = BRDFBAKE_BENCH_RESULTS_DIR, name, plot, device;
    int table = 0;
    std::int64_t samples = 0;
    app.add_flag("--quick", quick, "tiny sizes, one run each (a few seconds)");
    app.add_option("--table", table, "throughput table side N (N x N cells; default 64, quick 8)");
    app.add_option("--samples", samples, "samples per cell of the throughput table (default 65536)");
    app.add_option("--out-dir", out_dir, "directory for NAME.json and NAME.md")->capture_default_str();
    app.add_option("--name", name, "file name stem (default: the machine, e.g. amd-epyc-2c-avx512)");
    app.add_option("--plot", plot, "also plot time against cells x samples (.png or .svg)");
    app.add_option("--device", device, "OpenCL device selector (see `brdfbake devices`)");
    app.add_flag("--no-build-times", no_build, "skip the cold/warm kernel build figures");
    CLI11_PARSE(app, argc, argv);
    try {
        BenchOptions o = quick ? BenchOptions::quick_options() : BenchOptions();
        o.device = device;
        o.build_times = !no_build;
        if (table > 0) o.table = table;
        if (samples > 0) o.samples = std::uint64_t(samples);
        const BenchReport r = run_bench(o, std::cerr);
        if (name.empty()) name = bench_machine_name() + (quick ? "-quick" : "");
        write_bench_report(r, out_dir, name);
        if (!plot.empty() && r.agreed) write_bench_plot(r, plot);
        std::cout << r.markdown;
        std::cerr << "brdfbake-bench: wrote " << out_dir << "/" << name << ".json and .md\n";
        return r.agreed ? 0 : 1;
    } catch (const Error& e) {
        std::cerr << "brdfbake-bench: error: " << e.what() << "\n";
        return e.exit_code();
    } catch (const std::exception& e) {
        std::cerr << "brdfbake-bench: error: " << e.what() << "\n";
        return 2;
    }
}

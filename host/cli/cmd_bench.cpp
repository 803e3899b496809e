// `brdfbake bench`: the short benchmark (the quick mode of brdfbake-bench, same harness):
// the GGX albedo kernel against the OpenMP baseline of benchmarks/, the FMA peak, and a row per
// table kind of the registry; it prints its estimated length first. --full runs the whole suite
// (with kernel build times); --json / --markdown keep the report.
#include <iostream>
#include <memory>
#include <streambuf>

#include "harness/bench.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "cli/cli.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

/// The benchmark's log, line by line through progress_message (so that it and the progress bar
/// do not overwrite each other on a terminal).
class ProgressLog : public std::streambuf {
protected:
    int overflow(int c) override {
        if (c == traits_type::eof()) return 0;
        if (c == '\n') {
            progress_message(line_);
            line_.clear();
        } else {
            line_ += char(c);
        }
        return c;
    }

private:
    std::string line_;
};

struct BenchCmdOptions {
    bool full = false;
    int table = 0;
    std::int64_t samples = 0;
    std::string json, markdown, plot;
};

int run_bench_command(const BenchCmdOptions& o, const GlobalOptions& g) {
    check_plot_output(o.plot, "--plot");
    BenchOptions b = o.full ? BenchOptions() : BenchOptions::quick_options();
    if (!o.full) {  // short, but large enough for figures that mean something: runs of tens of
                    // milliseconds, a warm-up and the median of up to 5 (single runs of a 16x16
                    // table lasted 2-16 ms and their ratios varied 2x)
        b.quick = false;
        b.min_seconds = 0.1;
        b.max_runs = 5;
        b.table = 32;
        b.samples = 1u << 14;  // the plain strict baseline runs 1-2 s a precision at this size
        b.scaling_sizes = {8, 16, 32};
        b.scaling_size_samples = 1u << 12;
        b.scaling_samples = {1u << 10, 1u << 12, 1u << 14};
        b.scaling_samples_table = 16;
        // Every table kind, float and double, at tables that take about 30 ms a run.
        b.kind_texels = 16384;
        b.kind_seconds = 0.03;
        b.kind_precisions = {"float", "double"};
        // PoCL's own kernel cache, not a fresh one: a cold build of every kind's kernels would
        // take longer than the rest together. Build times (cold and warm) are in --full.
        b.build_times = false;
    }
    if (o.table > 0) b.table = o.table;
    if (o.samples > 0) b.samples = std::uint64_t(o.samples);
    b.device = g.device;
    b.verbose = g.verbose;
    ProgressLog log_buffer;
    std::ostream log(&log_buffer);
    const BenchReport r = run_bench(b, log);
    std::cout << r.markdown;
    if (!o.json.empty()) write_file_atomically(o.json, r.json.dump(2) + "\n");
    if (!o.markdown.empty()) write_file_atomically(o.markdown, r.markdown);
    if (!o.plot.empty() && r.agreed) write_bench_plot(r, o.plot);
    if (!r.agreed) throw Error("the kernel and a baseline flavour disagree:\n" + r.disagreement);
    return kExitOk;
}

constexpr const char* kBenchSummary =
    "benchmark the GGX albedo kernel against a plain C++ OpenMP loop and the FMA peak, and every table kind";

}  // namespace

void add_bench_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<BenchCmdOptions>(app, "bench", kBenchSummary, global, action, run_bench_command);
    cmd->add_flag("--full", o->full, "the whole suite (as brdfbake-bench): larger tables, repeated runs, sweeps");
    // 0 is these options' "not given"; given, they must be positive.
    cmd->add_option("--table", o->table, "throughput table side N (N x N cells)")->check(kPositive);
    cmd->add_option("--samples", o->samples, "samples per cell of the throughput table")->check(kPositive);
    cmd->add_option("--json", o->json, "write the report as JSON");
    cmd->add_option("--markdown", o->markdown, "write the tables as Markdown");
    cmd->add_option("--plot", o->plot, "plot time against cells x samples (.png or .svg)");
}

}  // namespace brdfbake

// Benchmarks of the kernels against the plain C++ OpenMP baseline (benchmarks/) and the
// machine's FMA peak (issue 9). One harness serves the `brdfbake-bench` program and the
// `brdfbake bench` command. Benchmarks are not timed tests: nothing here passes or fails on a
// time; it fails only when the kernel and the baseline disagree (then no time is reported).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace brdfbake {

struct BenchOptions {
    std::string device;                 // device selector (see choose_device)
    bool quick = false;                 // a few seconds: small tables, one run each
    int table = 64;                     // throughput table: table x table cells (mu x alpha)
    std::uint64_t samples = 1u << 16;   // samples per cell for the throughput figures
    std::vector<int> scaling_sizes = {16, 32, 64, 128, 256};
    std::uint64_t scaling_size_samples = 1u << 10;  // samples per cell of the size sweep
    std::vector<std::uint64_t> scaling_samples = {1u << 8, 1u << 10, 1u << 12, 1u << 14, 1u << 16};
    int scaling_samples_table = 32;     // table of the samples sweep
    double min_seconds = 0.5;           // repeat a measurement until it has taken this long
    int max_runs = 11;
    bool build_times = true;            // cold and warm kernel build (fresh POCL_CACHE_DIR)
    /// Table kinds (every kind of the registry, brdfbake/table_kinds.h): each kind's table at
    /// kind_tolerance with about kind_texels texels (a 2D kind N x N, a 3D kind W x W x W/2; a
    /// 1D kind sqrt(kind_texels) texels), float and double; 0 texels: no kind rows. With
    /// kind_seconds > 0, a smaller table where a run would last longer than that.
    int kind_texels = 16384;
    double kind_seconds = 0.0;
    double kind_tolerance = 1e-4;
    std::vector<std::string> kind_precisions = {"float", "double"};
    bool verbose = false;
    /// The best of the quick options (`--quick`): tiny tables, one run each.
    static BenchOptions quick_options();
};

struct BenchReport {
    nlohmann::json json;   // everything measured, with the machine
    std::string markdown;  // the tables of docs/performance.md
    bool agreed = false;   // kernel and baseline agreed within their error estimates
    std::string disagreement;  // what differed, when they did not
};

/// Runs the benchmarks; progress goes to `log`. Call it before anything in the process has
/// touched OpenCL: the cold-build figure points PoCL's cache at a fresh directory (PoCL reads
/// POCL_CACHE_DIR once per process). The variable is set only until the build times are
/// measured, then given back its previous value (or unset). Throws Error for a device fault.
BenchReport run_bench(const BenchOptions& options, std::ostream& log);

/// Writes the report as NAME.json and NAME.md into `dir` (created if needed), atomically.
void write_bench_report(const BenchReport& report, const std::string& dir, const std::string& name);

/// Plots time against cells x samples from the report's scaling sweeps (PNG or SVG).
void write_bench_plot(const BenchReport& report, const std::string& path);

/// A short file-name-safe name for this machine, e.g. "amd-epyc-2c-avx512".
std::string bench_machine_name();

/// The CPU's model name (/proc/cpuinfo) and the load average (/proc/loadavg), as the benchmark
/// reports state them.
std::string bench_cpu_model();
std::string bench_loadavg();

}  // namespace brdfbake

// The benchmark harness's parts, shared by its files (bench.cpp runs the measurements,
// bench_support.cpp holds the machine's description, the timing rules, the cells and the plan,
// bench_report.cpp writes the Markdown and the plot). Not installed; the tests include it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "baseline.h"
#include "brdfbake/albedo.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"
#include "harness/bench.h"

namespace brdfbake::bench_detail {

/* Flops of one sample of the estimator, counted by hand from the arithmetic the albedo kernel's
 * vector path performs per (cell, sample) for isotropic GGX with F = 1 (kernels/albedo.cl,
 * albedo_replicas_disk built with -D BB_ISOTROPIC=1, and bb_ggx_disk_weight in brdf/ggx.h),
 * counting +, -, *, /, sqrt, min/max and compare-select as 1 flop and fma as 2, and leaving out
 * what does not depend on the cell (the Hammersley point, its rotation, the disk point
 * sqrt(u1) cos/sin(2 pi u2) and sqrt(1 - x^2), which the host tabulates) and what is the same
 * for every sample of a cell (the stretched view, its basis, 1/G1(wo)):
 *   hemisphere point: p2 = (1-s) h + s y (3), p3 = sqrt(max(0, 1 - p1^2 - p2^2)) (6)       9
 *   unnormalised normal n (8), L = |n|^2 (5), wo.n (3), W.z = 2 (wo.n) n.z - L wo.z (4)  20
 *   q = sqrt(a^2 L^2 + (1 - a^2) W.z^2) (6), weight 2 c0 W.z / ((2 c0 - 1) W.z + q) (4),
 *     the horizon and G1(wo) guards (3)                                                  13
 *   finiteness test, non-finite count and the block sum (6)                               6
 * The anisotropic form adds W.x, W.y and their terms in q (about 14 more); the scalar kernel
 * does more work per sample than this (the textbook form, recomputing the hoisted parts),
 * which the count does not credit. The baselines' loops are counted the same way from their
 * source (baseline::flops_per_sample); the fraction of peak of each row uses its own count. */
constexpr double kFlopsPerSample = 48.0;

/// The engine and its warm albedo program, in the estimate of a run's length (seconds).
constexpr double kEngineSeconds = 0.3;

std::string read_cpu_model();
std::string read_loadavg();
std::string cpu_simd();  // "AVX-512", "AVX2", "SSE"
double now();            // seconds on the steady clock
double median(std::vector<double> v);

/// Repeats `run` (returning seconds): one warm-up, then until min_seconds have passed (at
/// least once, at most max_runs). Returns the median; a first run longer than min_seconds
/// is taken as it is.
template <typename Run>
double time_median(Run run, const BenchOptions& o) {
    const double first = run();
    if (o.quick || first >= o.min_seconds) return first;  // a long run is its own warm-up
    std::vector<double> t;
    double total = 0.0;
    while (t.empty() || (total < o.min_seconds && int(t.size()) < o.max_runs)) {
        t.push_back(run());
        total += t.back();
    }
    (void)first;
    return median(t);
}

/// time_median for a run whose first result was needed anyway (a baseline's checked table):
/// `first` is that run's time, taken as the figure when it lasted min_seconds or more.
template <typename Run>
double time_median_from(double first, Run run, const BenchOptions& o) {
    if (o.quick || first >= o.min_seconds) return first;
    std::vector<double> t;
    double total = 0.0;
    while (t.empty() || (total < o.min_seconds && int(t.size()) < o.max_runs)) {
        t.push_back(run());
        total += t.back();
    }
    return median(t);
}

/// What time_median spends on a run of `run` seconds (its first run and the timed ones).
double median_cost(double run, const BenchOptions& o);

struct TableCells {
    std::vector<double> mu, alpha;
};

/// The texel centres of `brdfbake lut albedo --size NxN` (linear mu, alpha in (0, 1)).
TableCells table_cells(int n);
AlbedoRequest kernel_request(const TableCells& t, std::uint64_t samples, Precision p);

/// The flavours of the baselines (benchmarks/baseline.h): the tuned loop (strict, -ffast-math,
/// the kernel's arithmetic) and the plain textbook loop (strict, -ffast-math).
enum class Flavour { Strict, FastMath, KernelArithmetic, PlainStrict, PlainFastMath };

/// The baseline's table at precision p in the given flavour.
baseline::Result run_baseline(const TableCells& t, std::uint64_t samples, Precision p, Flavour f);

std::string fixed(double v, int digits);  // fixed-point with `digits` decimals
std::string sci(double v);                // three significant digits

/// The timing options of the kind rows: with sized tables (kind_seconds), repeats until twice
/// a run's length rather than min_seconds, so that a row costs a few runs.
BenchOptions kind_timing(const BenchOptions& o);

/// The phases of a run and their estimated seconds, in the order run_bench runs them.
struct BenchPhase {
    std::string name;
    double estimate = 0.0;
};
std::vector<BenchPhase> plan_bench(const BenchOptions& o, const baseline::Peak& peak,
                                   const std::vector<Precision>& precisions);

/// The --size of a kind's table with about `texels` texels: N x N for a 2D kind, N texels for
/// a 1D kind, W x W x W/2 for a kind with an eta axis (W x 1 x W/2 for a 1D one).
std::vector<int> kind_size(const TableKind& k, double texels);
double texel_count(const LutRequest& r, const TableKind& k);

/// A request of kind `k` that the registry's own checks accept: the first model of
/// model_names() and Fresnel term (none, then a conductor's) that validate_lut takes, so that
/// every kind, a new one too, gets a row without a list here. Empty kind when none fits.
LutRequest kind_request(const TableKind& k, double texels, double tolerance, Precision p);
std::string size_text(const LutRequest& r, const TableKind& k);

/// Sets an environment variable for a scope: the destructor (or restore()) puts back the value
/// it had, or unsets it when it had none. An empty optional value leaves the variable alone.
class ScopedEnvironment {
public:
    ScopedEnvironment(std::string name, const std::optional<std::string>& value);
    ~ScopedEnvironment();
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;
    void restore();

private:
    std::string name_;
    std::optional<std::string> previous_;
    bool active_ = false;
};

/// The Markdown tables of a run's report (times only where the results agreed).
std::string bench_markdown(const BenchReport& report, const BenchOptions& o, const baseline::Peak& peak);

}  // namespace brdfbake::bench_detail

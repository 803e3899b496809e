// `plan`'s and `bake`'s time estimates from what bakes on this machine measured (issue 32: within
// 1.5x of the bake). Each `brdfbake bake` records its stages' times into a calibration file: per
// (table kind, model, precision) the samples per second its tables integrated at, the seconds a
// preview took, a kernel build, a lobe check of the report. `plan` and `bake` estimate from the
// file when it has figures for this machine, from the built-in figures (measured on the
// development machine: benchmarks/results/plan-estimates-2c-shared.md) otherwise.
//
// The file: $BRDFBAKE_CALIBRATION (a path; "off": none is read or written), else
// $XDG_CACHE_HOME/brdfbake/calibration.json, else ~/.cache/brdfbake/calibration.json. It is
// replaced atomically (write_file_atomically). A file that cannot be used is ignored
// with one warning: one of this format (another version, a value out of range) is replaced by the
// next bake; any other (not JSON, no "format": "brdfbake-calibration") is never written to (it
// may be someone's file the variable names by mistake); docs/scenes.md, "Estimates".
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace brdfbake {

/// The built-in figures of the cost model: seconds on idle cores of the development machine (AMD
/// EPYC, 2 hardware threads, PoCL, float), from bakes' stage times divided by their measured
/// slowdown (SlowdownClock; benchmarks/results/plan-estimates-2c-shared.md, 2026-12-03, load 15).
/// A calibration replaces those it has; the estimates are these times the slowdown now.
namespace builtin_figures {
/// GGX albedo samples per second per hardware thread on PoCL's vector path, float (1024x1024
/// texels x 4096 samples, 1.3e9 samples in 0.61-0.63 idle-core seconds on 2 threads: 2.1e9/s).
constexpr double kSamplesPerSecondPerCore = 1.05e9;
/// A kernel build from PoCL's cache (0.023 s measured; plan's slowdown probe has built the GGX
/// albedo kernel; a cold build is several times more).
constexpr double kSecondsPerProgram = 0.05;
/// Per table: launches, assembling and writing the file (measured: 0.0002 to 0.002 s).
constexpr double kSecondsPerTable = 0.005;
/// The preview picture bake writes beside a table (MathGL, single-threaded: 0.02 s for 32 texels,
/// 0.15-0.16 s for 316 K texels), and per texel drawn.
constexpr double kSecondsPerPreview = 0.02;
constexpr double kSecondsPerPreviewTexel = 4.3e-7;
/// Starting the process and the device (0.06 to 0.09 CPU seconds), the bake folder, its index and
/// report page: about 0.2 s (tests/data/small_glass.json's bake took 0.37 CPU seconds against
/// 0.26 s for its other stages).
constexpr double kStartupSeconds = 0.2;
/// With PoCL's kernel cache cold (a first bake, a new brdfbake, a cleared cache), each program's
/// build and the code generation at its first launch, and once per process the compiler's start:
/// CPU seconds of cold bakes less warm ones, 1.65 s for 3 programs (small_glass.json), 2.6-2.8 s
/// for 6 (examples/scene.json, metals_glass.json), 3.6 s for 8 (materials.gltf): 0.5 s + 0.4 s a
/// program (benchmarks/results/plan-estimates-2c-shared.md, 2026-12-03 session 4).
constexpr double kColdStartSeconds = 0.5;
constexpr double kColdSecondsPerProgram = 0.4;
/// A build of the slowdown probe's kernel longer than this (idle-core seconds) found the cache
/// cold: cached it takes 0.02 s, cold 1.2 s (the compiler starts).
constexpr double kColdBuildSeconds = 0.25;
/// One lobe check of the bake report (24 directions x 2^14 samples and 16^3 reciprocity pairs:
/// 0.019 s a check, the mean of 20 bakes).
constexpr double kSecondsPerReportCheck = 0.02;
}  // namespace builtin_figures

/// A measured figure: its running mean over the last few measurements.
struct CalibratedFigure {
    double value = 0.0;
    int measurements = 0;  // 0: none (the built-in figure holds)
    bool known() const { return measurements > 0; }
    /// Adds a measurement: the mean of up to the last 8 (older ones fade out).
    void add(double x);
};

/// A cost that grows with a size (a table's samples, a preview's texels): seconds = a + b size,
/// fitted to recent measurements (up to 8, 2 of a size, the largest size kept).
struct CalibratedLine {
    std::vector<std::pair<double, double>> runs;  // (size, seconds), oldest first
    void add(double size, double seconds);
    /// The seconds at `size`: by least squares (a, b >= 0) over runs of at least two sizes whose
    /// slope lies within 20x of b0's; from one size (or a slope beyond that), the default line
    /// a0 + b0 size scaled through the runs' mean; the default itself without runs.
    double seconds(double size, double a0, double b0) const;
    /// The fitted slope where the runs determine one (two sizes at least, the larger's samples
    /// costing at least as much as its fixed part), else -1.
    double slope(double b0) const;
};

struct Calibration {
    std::string path;     // the file (empty: calibration off)
    std::string warning;  // why the file was ignored (empty: it was read, or there is none)
    bool writable = true; // false: the file is not a calibration (never overwritten)
    std::string host;     // the machine it was measured on
    unsigned hardware_threads = 0;
    int bakes = 0;        // bakes that recorded into it
    /// Integration seconds over samples, by calibration_rate_key(kind, model, precision).
    std::map<std::string, CalibratedLine> tables;
    CalibratedLine previews;  // seconds over texels
    CalibratedFigure build_seconds_per_program, report_check_seconds;

    /// How much slower than on idle cores this machine runs now (measure_slowdown; 1: idle, or not
    /// measured). The figures are idle-core seconds (the built-in ones measured so, a bake's
    /// divided by its own slowdown); the estimates are those times this.
    double slowdown = 1.0;
    /// PoCL's kernel cache was found cold (the probe's build took longer than kColdBuildSeconds):
    /// the bake's programs are estimated as cold builds.
    bool cold_cache = false;

    /// The file has figures for this machine (same host and hardware threads, a bake recorded).
    bool applies() const;
};

/// A shared machine's cores are not all this process's: the wall time of parallel work over its
/// CPU time per hardware thread (process-wide, every thread) says how much of them it gets. On
/// the 2-core development machine, shared with other jobs, bakes took 1x to 9x their idle-core
/// time within the same hour (benchmarks/results/plan-estimates-2c-shared.md).
class SlowdownClock {
public:
    SlowdownClock();  // starts
    /// wall seconds x hardware threads / CPU seconds since the start, at least 1 (1 also when
    /// too little ran to say: under 0.02 CPU seconds).
    double slowdown() const;
    double wall_seconds() const;
    double cpu_seconds() const;  // the process's, every thread

private:
    double wall0_, cpu0_;
};

/// The built-in samples per second of a table of `kind` and `model_name`: GGX albedo's over the
/// kind's cost per sample (TableKind::sample_cost) and the model's (ModelTraits::sample_cost).
double builtin_rate(const std::string& kind, const std::string& model_name);

/// The seconds a table of `samples` of `kind`, `model_name` and `precision` ("float", "double")
/// integrates for: the calibration's line for it where it has runs; else the built-in rate, scaled
/// by this machine's speed (the geometric mean, over the kinds with a fitted slope, of how much
/// faster than their built-in rate they ran), plus the built-in fixed seconds. `calibration` may
/// be nullptr (built-in figures).
double table_seconds(const Calibration* calibration, const std::string& kind, const std::string& model_name,
                     const std::string& precision, double samples);

/// The seconds a preview of `texels` takes (the built-in line without runs).
double preview_seconds(const Calibration* calibration, double texels);

/// "albedo ggx float": the key of a table's measured rate.
std::string calibration_rate_key(const std::string& kind, const std::string& model_name, const std::string& precision);

/// The file's path from the environment (see the top of this file); empty: calibration off.
std::string calibration_path();

/// Reads the calibration at `path` (empty: off; a missing file: an empty calibration). Never
/// throws: a file that cannot be used comes back empty, with `warning` saying why.
Calibration read_calibration(const std::string& path);

/// The stages one bake measured.
struct BakeTimings {
    struct TableRun {
        std::string kind, model_name, precision;
        std::uint64_t samples = 0;   // samples integrated (the plan's samples_total)
        double compute_seconds = 0;  // integrating, kernel builds excluded
    };
    std::vector<TableRun> tables;
    std::vector<std::pair<double, double>> previews;  // (texels, seconds) per preview
    int programs = 0;                // kernel programs built
    double build_seconds = 0;        // their total
    int report_checks = 0;           // lobe checks of the report (0: no report)
    double report_seconds = 0;
    /// The machine's slowdown while the tables integrated (SlowdownClock over their
    /// integration): the times above are divided by it when recorded.
    double slowdown = 1.0;
};

/// The slowdown of a single-threaded stage (start-up, a kernel build, a preview) when parallel
/// work runs `slowdown` times slower than on idle cores: the probe's wall over CPU time,
/// max(1, slowdown / hardware threads). Measured on the development machine (2 threads, load 15):
/// small bakes, mostly single-threaded, took 3.4x their CPU time while the probe measured 6.3.
double serial_slowdown(double slowdown);

/// BRDFBAKE_SLOWDOWN=X (a number of at least 1): the slowdown `plan` assumes instead of measuring
/// it; -1 when unset. Throws Error naming the variable for any other value.
double slowdown_from_environment();

/// Adds a bake's measurements to `c`.
void add_bake_timings(Calibration& c, const BakeTimings& t);

/// Writes `c` to c.path atomically (a temporary file in the same folder, renamed over it);
/// creates the folder. Returns an empty string, or why it could not (the bake goes on).
std::string write_calibration(const Calibration& c);

}  // namespace brdfbake

// The benchmark harness (benchmarks/harness/bench.h): GGX albedo tables through the kernel
// (compute_albedo, the code path of `brdfbake lut albedo`) against the OpenMP baselines of
// benchmarks/ (the tuned loop and the plain textbook loop), the FMA peak, kernel build times and
// scaling sweeps.
#include "harness/bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <thread>

#include <sys/utsname.h>

#include "baseline.h"
#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/memory_limit.h"
#include "brdfbake/output.h"
#include "brdfbake/progress.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "brdfbake/version.h"
#include "plot/plot.h"

namespace brdfbake {

namespace {

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

std::string read_cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            std::string v = line.substr(line.find(':') + 1);
            v.erase(0, v.find_first_not_of(" \t"));
            return v;
        }
    return "unknown CPU";
}

std::string read_loadavg() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
}

std::string cpu_simd() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("flags", 0) == 0) {
            if (line.find(" avx512f") != std::string::npos) return "AVX-512";
            if (line.find(" avx2") != std::string::npos) return "AVX2";
            return "SSE";
        }
    return "unknown";
}

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

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
double median_cost(double run, const BenchOptions& o) {
    if (o.quick || run >= o.min_seconds) return run;
    const double runs = std::min<double>(o.max_runs, std::max(1.0, std::ceil(o.min_seconds / std::max(run, 1e-6))));
    return run + runs * run;
}

struct TableCells {
    std::vector<double> mu, alpha;
};

/// The texel centres of `brdfbake lut albedo --size NxN` (linear mu, alpha in (0, 1)).
TableCells table_cells(int n) {
    TableCells t;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            t.mu.push_back((i + 0.5) / n);
            t.alpha.push_back(std::max((j + 0.5) / n, 1e-4));
        }
    return t;
}

AlbedoRequest kernel_request(const TableCells& t, std::uint64_t samples, Precision p) {
    AlbedoRequest r;
    r.model = BB_MODEL_GGX;
    r.fresnel.kind = BB_FRESNEL_NONE;
    r.samples = samples;
    r.precision = p;
    for (size_t k = 0; k < t.mu.size(); ++k) {
        AlbedoCell c;
        c.mu = t.mu[k];
        c.params[BB_GGX_ALPHA_X] = c.params[BB_GGX_ALPHA_Y] = t.alpha[k];
        c.params[BB_GGX_SHADOWING] = 1.0;
        r.cells.push_back(c);
    }
    return r;
}

/// The flavours of the baselines (benchmarks/baseline.h): the tuned loop (strict, -ffast-math,
/// the kernel's arithmetic) and the plain textbook loop (strict, -ffast-math).
enum class Flavour { Strict, FastMath, KernelArithmetic, PlainStrict, PlainFastMath };

/// The baseline's table at precision p in the given flavour.
baseline::Result run_baseline(const TableCells& t, std::uint64_t samples, Precision p, Flavour f) {
    baseline::Request r;
    r.mu = t.mu;
    r.alpha = t.alpha;
    r.samples = samples;
    r.single = p == Precision::Float;
    r.fast_math = f == Flavour::FastMath || f == Flavour::PlainFastMath;
    r.kernel_arithmetic = f == Flavour::KernelArithmetic;
    r.plain = f == Flavour::PlainStrict || f == Flavour::PlainFastMath;
    return baseline::albedo_table(r);
}

std::string fixed(double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

std::string sci(double v) {
    std::ostringstream s;
    s << std::setprecision(3) << v;
    return s.str();
}

/* The estimate of a run's length, printed before it starts: the work of each measurement at the
 * rates measured on the development machine (the 2-core AVX-512 EPYC of
 * benchmarks/results/amd-epyc-2c-avx512.md; FMA peak 118 GFLOP/s float, 65 double), scaled by
 * this machine's FMA peak against that one's. Samples per second, float and double, in the
 * order of the throughput rows: the kernel, the tuned baseline (strict, -ffast-math, the
 * kernel's arithmetic), the plain baseline (strict, -ffast-math). */
constexpr double kReferencePeak[2] = {118.0, 65.0};
constexpr double kReferenceRate[6][2] = {{1.16e9, 4.66e8}, {6.18e8, 4.04e8}, {8.61e8, 4.66e8},
                                         {3.50e8, 1.39e8}, {1.71e7, 1.07e7}, {1.66e8, 9.76e7}};
constexpr double kKernelCallSeconds = 5e-4;     // a compute_albedo call's own cost (scaling sweep, 8x8 table)
constexpr double kBaselineCallSeconds = 0.01;  // a baseline call's (thread start-up: 0.2 to 24 ms there)
constexpr double kEngineSeconds = 0.3;          // the engine and its warm albedo program
constexpr double kColdBuildSeconds[2] = {2.3, 0.7};  // the first cold build of a process, and a later one
constexpr double kKindCellSeconds = 2.5e-5;     // an integration cell of a table at 1e-4 (the albedo's: 16 us)

/// The timing options of the kind rows: with sized tables (kind_seconds), repeats until twice
/// a run's length rather than min_seconds, so that a row costs a few runs.
BenchOptions kind_timing(const BenchOptions& o) {
    BenchOptions k = o;
    if (o.kind_seconds > 0) k.min_seconds = std::min(o.min_seconds, 2.0 * o.kind_seconds);
    return k;
}

/// The phases of a run and their estimated seconds, in the order run_bench runs them.
struct BenchPhase {
    std::string name;
    double estimate = 0.0;
};

std::vector<BenchPhase> plan_bench(const BenchOptions& o, const baseline::Peak& peak, const std::vector<Precision>& precisions) {
    std::vector<BenchPhase> plan;
    auto speed = [&](Precision p) {
        const int i = p == Precision::Double ? 1 : 0;
        const double here = p == Precision::Double ? peak.gflops_double : peak.gflops_float;
        return here > 0 ? here / kReferencePeak[i] : 1.0;
    };
    auto run_seconds = [&](int impl, Precision p, double work) {
        const int i = p == Precision::Double ? 1 : 0;
        return (impl == 0 ? kKernelCallSeconds : kBaselineCallSeconds) + work / (kReferenceRate[impl][i] * speed(p));
    };
    if (o.build_times)
        plan.push_back({"kernel builds", kColdBuildSeconds[0] + kColdBuildSeconds[1] * double(precisions.size() - 1) +
                                             0.1 * double(precisions.size())});
    const double work = double(o.table) * o.table * double(o.samples);
    for (Precision p : precisions) {
        double t = run_seconds(0, p, work) + median_cost(run_seconds(0, p, work), o);
        for (int impl = 1; impl < 6; ++impl) t += median_cost(run_seconds(impl, p, work), o);
        plan.push_back({std::string("throughput, ") + precision_name(p), t});
    }
    double sweep = 0.0;
    auto point = [&](int n, std::uint64_t samples) {
        const double w = double(n) * n * double(samples);
        sweep += median_cost(run_seconds(0, Precision::Float, w), o) + median_cost(run_seconds(1, Precision::Float, w), o);
    };
    for (int n : o.scaling_sizes) point(n, o.scaling_size_samples);
    for (std::uint64_t s : o.scaling_samples) point(o.scaling_samples_table, s);
    plan.push_back({"scaling sweeps", sweep});
    if (o.kind_texels > 0)
        for (const std::string& pname : o.kind_precisions) {
            const Precision p = pname == "double" ? Precision::Double : Precision::Float;
            if (std::find(precisions.begin(), precisions.end(), p) == precisions.end()) continue;
            double t = 0.0;
            for (const TableKind* k : table_kinds()) {
                // Adaptive sizes: two tiny runs, then runs of about kind_seconds. Fixed sizes:
                // the table's integration cells at the albedo table's cost per cell (a rough
                // figure: kinds differ several-fold).
                const double texels = k->one_dimensional ? std::sqrt(double(o.kind_texels)) : double(o.kind_texels);
                const double cells = texels * k->cells_per_texel * k->sample_cost;
                // Sized: a tiny warm-up, the sizing runs, the timed ones; double's kernels about
                // 1.5x float's (the slowest kinds' smallest tables outlast kind_seconds).
                t += o.kind_seconds > 0
                         ? (0.03 + 2.0 * o.kind_seconds + median_cost(o.kind_seconds, kind_timing(o))) *
                               (p == Precision::Double ? 1.5 : 1.0)
                         : 2.0 * cells * kKindCellSeconds / speed(p) + 0.05;
            }
            plan.push_back({"table kinds, " + pname, t});
        }
    return plan;
}

/// The --size of a kind's table with about `texels` texels: N x N for a 2D kind, N texels for
/// a 1D kind, W x W x W/2 for a kind with an eta axis (W x 1 x W/2 for a 1D one).
std::vector<int> kind_size(const TableKind& k, double texels) {
    texels = std::max(texels, 1.0);
    if (k.eta_axis && k.one_dimensional) {
        const int w = std::max(2, int(std::lround(std::sqrt(2.0 * texels))));
        return {w, 1, std::max(1, w / 2)};
    }
    if (k.eta_axis) {
        const int w = std::max(2, int(std::lround(std::cbrt(2.0 * texels))));
        return {w, w, std::max(1, w / 2)};
    }
    if (k.one_dimensional) return {std::max(2, int(std::lround(texels)))};
    const int side = std::max(2, int(std::lround(std::sqrt(texels))));
    return {side, side};
}

double texel_count(const LutRequest& r, const TableKind& k) {
    return double(r.width) * (k.one_dimensional ? 1 : r.height) * (k.eta_axis ? r.depth : 1);
}

/// A request of kind `k` that the registry's own checks accept: the first model of
/// model_names() and Fresnel term (none, then a conductor's) that validate_lut takes, so that
/// every kind, a new one too, gets a row without a list here. Empty kind when none fits.
LutRequest kind_request(const TableKind& k, double texels, double tolerance, Precision p) {
    for (const char* fresnel : {"none", "conductor:eta=0.2,k=3"})
        for (const std::string& model : model_names()) {
            LutRequest r;
            r.kind = k.name;
            r.model = model;
            r.fresnel = fresnel;
            set_lut_size(r, kind_size(k, texels));
            r.tolerance.tolerance = tolerance;
            r.precision = p;
            try {
                validate_lut(r);
                return r;
            } catch (const Error&) {
            }
        }
    return LutRequest{};
}

std::string size_text(const LutRequest& r, const TableKind& k) {
    std::string s = std::to_string(r.width);
    if (!k.one_dimensional) s += "x" + std::to_string(r.height);
    if (k.eta_axis) s += "x" + std::to_string(r.depth);
    return s;
}

}  // namespace

BenchOptions BenchOptions::quick_options() {
    BenchOptions o;
    o.quick = true;
    o.table = 8;
    o.samples = 1u << 12;
    o.scaling_sizes = {4, 8, 16};
    o.scaling_size_samples = 1u << 8;
    o.scaling_samples = {1u << 8, 1u << 10};
    o.scaling_samples_table = 8;
    o.min_seconds = 0.0;
    o.max_runs = 1;
    o.kind_texels = 16;
    o.kind_precisions = {"float"};
    return o;
}

std::string bench_machine_name() {
    std::string model = read_cpu_model(), out;
    for (char c : model) {
        const char l = char(std::tolower(static_cast<unsigned char>(c)));
        if (std::isalnum(static_cast<unsigned char>(l)))
            out += l;
        else if (!out.empty() && out.back() != '-')
            out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    // The vector extension too: machines sold under one name differ in it (an AVX2 and an
    // AVX-512 EPYC have both been development machines), and the kernels' speed follows it.
    std::string simd = cpu_simd(), tag;
    for (char c : simd)
        if (std::isalnum(static_cast<unsigned char>(c))) tag += char(std::tolower(static_cast<unsigned char>(c)));
    return out + "-" + std::to_string(std::thread::hardware_concurrency()) + "c-" + tag;
}

BenchReport run_bench(const BenchOptions& o, std::ostream& log) {
    using nlohmann::json;
    namespace fs = std::filesystem;
    BenchReport rep;
    json& j = rep.json;
    if (o.table < 1 || o.samples < 1) throw Error("bench: the table side and the samples must be positive");
    // Judged before anything is allocated: per cell, the table's coordinates, the kernel's request
    // and upload, its per-replica outputs and each baseline flavour's result (about 1 kB).
    int largest = o.table;
    for (int n : o.scaling_sizes) largest = std::max(largest, n);
    check_memory(double(largest) * largest * 1024.0, "bench with a " + std::to_string(largest) + "x" +
                                                          std::to_string(largest) + " table");

    // A fresh PoCL cache for the whole run: the first build of each program is cold.
    std::string cache_dir;
    if (o.build_times) {
        std::string templ = (fs::temp_directory_path() / "brdfbake-bench-cache-XXXXXX").string();
        if (!::mkdtemp(templ.data())) throw Error("cannot create a temporary PoCL cache directory");
        cache_dir = templ;
        ::setenv("POCL_CACHE_DIR", cache_dir.c_str(), 1);
    }
    struct CacheCleanup {
        std::string dir;
        ~CacheCleanup() {
            std::error_code ec;
            if (!dir.empty()) std::filesystem::remove_all(dir, ec);
        }
    } cleanup{cache_dir};

    const double t_start = now();
    Engine engine(o.device, o.verbose);
    const DeviceInfo& dev = engine.device();
    struct utsname u {};
    ::uname(&u);
    j["machine"] = {{"cpu", read_cpu_model()},
                    {"cores", std::thread::hardware_concurrency()},
                    {"simd", cpu_simd()},
                    {"os", std::string(u.sysname) + " " + u.release},
                    {"opencl_platform", dev.platform},
                    {"opencl_device", dev.name},
                    {"opencl_version", dev.version},
                    {"pocl_version", dev.driver},
                    {"compute_units", dev.compute_units},
                    {"loadavg_start", read_loadavg()}};
    j["brdfbake_version"] = BRDFBAKE_VERSION;
    j["baseline_flags"] = baseline::compile_flags();
    j["mode"] = o.quick ? "quick" : "full";
    j["kernel_flops_per_sample"] = kFlopsPerSample;
    log << "machine: " << j["machine"]["cpu"].get<std::string>() << ", " << std::thread::hardware_concurrency()
        << " cores, " << dev.platform << " " << dev.driver << "\n";

    // (c) the FMA probe.
    const baseline::Peak peak = baseline::fma_peak(o.quick ? 0.05 : 0.3);
    std::vector<Precision> precisions = {Precision::Float};
    if (dev.fp64) precisions.push_back(Precision::Double);

    // The estimate, then the run as one progress stage in estimated milliseconds, a phase a
    // step; what runs inside (a table's refinement) shows as part of the step.
    const std::vector<BenchPhase> plan = plan_bench(o, peak, precisions);
    double estimate = kEngineSeconds + (o.quick ? 0.05 : 0.3);  // the engine, the FMA probe
    for (const BenchPhase& ph : plan) estimate += ph.estimate;
    log << "bench: about " << progress_duration(estimate) << " (" << (o.quick ? "quick" : o.kind_seconds > 0 ? "short" : "full")
        << " run; estimated from this machine's FMA peak and the development machine's timings; longer while "
           "PoCL's kernel cache is cold)\n";
    std::uint64_t total_ms = 0;
    for (const BenchPhase& ph : plan) total_ms += std::uint64_t(ph.estimate * 1e3 + 0.5);
    ProgressStage stage("bench", total_ms);
    std::uint64_t done_ms = 0;
    size_t next_phase = 0;
    json phases = json::array();
    double phase_start = now();
    // Starts the named phase: the previous one ends (its time recorded beside its estimate).
    auto phase = [&](const std::string& name) {
        const double t = now();
        if (next_phase > 0) {
            phases.back()["seconds"] = t - phase_start;
            done_ms += std::uint64_t(plan[next_phase - 1].estimate * 1e3 + 0.5);
        }
        while (next_phase < plan.size() && plan[next_phase].name != name) ++next_phase;  // a skipped phase
        if (next_phase >= plan.size()) return;
        const BenchPhase& ph = plan[next_phase++];
        phases.push_back({{"phase", ph.name}, {"estimated_seconds", ph.estimate}});
        stage.update(done_ms, ph.name, std::uint64_t(ph.estimate * 1e3 + 0.5));
        phase_start = t;
    };
    // Part `index` of `count` of the current phase (a table kind): its share of the estimate,
    // so that what runs inside it (a refinement) moves the bar within that share only.
    auto sub_step = [&](const std::string& name, size_t index, size_t count) {
        if (next_phase == 0 || count == 0) return;
        const BenchPhase& ph = plan[next_phase - 1];
        const double share = ph.estimate * 1e3 / double(count);
        stage.update(done_ms + std::uint64_t(share * double(index)), ph.name + ": " + name, std::uint64_t(share));
    };
    j["peak"] = {{"gflops_float", peak.gflops_float},
                 {"gflops_double", peak.gflops_double},
                 {"threads", peak.threads},
                 {"vector_bits", peak.vector_bits}};

    // Kernel build times: a fresh engine (new context) builds the albedo program and runs it on
    // one cell with 32 samples. PoCL compiles the work-group function at the first launch, so
    // the figure is clBuildProgram plus that first launch: what a command waits before work.
    json builds = json::array();
    if (o.build_times) {
        phase("kernel builds");
        const TableCells one = table_cells(1);
        for (Precision p : precisions) {
            double t[2], b[2];
            for (int k = 0; k < 2; ++k) {
                Engine e(o.device, false);
                const double t0 = now();
                compute_albedo(e, kernel_request(one, 32, p));
                t[k] = now() - t0;
                b[k] = e.build_seconds();
            }
            builds.push_back({{"precision", precision_name(p)},
                              {"cold_seconds", t[0]},
                              {"cold_build_program_seconds", b[0]},
                              {"warm_seconds", t[1]},
                              {"warm_build_program_seconds", b[1]}});
            log << "build (" << precision_name(p) << "): cold " << fixed(t[0], 3) << " s, warm " << fixed(t[1], 3)
                << " s\n";
        }
    }
    j["build"] = builds;

    // (a), (b): the throughput table, checked before any time is reported.
    const TableCells cells = table_cells(o.table);
    const double n_samples = double(cells.mu.size()) * double(o.samples);
    json thr = json::array();
    rep.agreed = true;
    for (Precision p : precisions) {
        phase(std::string("throughput, ") + precision_name(p));
        const AlbedoRequest kreq = kernel_request(cells, o.samples, p);
        const AlbedoResult kres = compute_albedo(engine, kreq);  // warm-up and the checked result
        // Every flavour of the baseline must agree with the kernel within the two estimates.
        const Flavour flavours[] = {Flavour::Strict, Flavour::FastMath, Flavour::KernelArithmetic,
                                    Flavour::PlainStrict, Flavour::PlainFastMath};
        const char* flavour_names[] = {"tuned strict", "tuned -ffast-math", "tuned, kernel arithmetic",
                                       "plain strict", "plain -ffast-math"};
        double worst = 0.0;
        bool agreed = true;
        double checked_seconds[5];  // each flavour's checked run is its first timed one
        for (int f = 0; f < 5; ++f) {
            const baseline::Result bres = run_baseline(cells, o.samples, p, flavours[f]);
            checked_seconds[f] = bres.seconds;
            double worst_f = 0.0;
            size_t worst_cell = 0;
            for (size_t c = 0; c < cells.mu.size(); ++c) {
                const double d = std::fabs(kres.values[c].value - bres.value[c]);
                const double tol = kres.values[c].error + bres.error[c];
                if (d / tol > worst_f) {
                    worst_f = d / tol;
                    worst_cell = c;
                }
            }
            worst = std::max(worst, worst_f);
            if (worst_f > 1.0 || bres.non_finite > 0) {
                agreed = false;
                std::ostringstream m;
                m << precision_name(p) << ", baseline " << flavour_names[f] << ": kernel "
                  << kres.values[worst_cell].value << " +- " << kres.values[worst_cell].error << " vs baseline "
                  << bres.value[worst_cell] << " +- " << bres.error[worst_cell] << " at mu = " << cells.mu[worst_cell]
                  << ", alpha = " << cells.alpha[worst_cell] << "; baseline non-finite samples: " << bres.non_finite;
                rep.disagreement += m.str() + "\n";
                log << "DISAGREEMENT " << m.str() << "\n";
            }
        }
        if (!agreed) {
            rep.agreed = false;
            continue;
        }
        double max_err = 0.0;
        for (const auto& v : kres.values) max_err = std::max(max_err, v.error);
        log << precision_name(p)
            << ": kernel and every baseline flavour agree (largest |difference| / (error_k + error_b) = "
            << fixed(worst, 3) << ", max error " << sci(max_err) << ")\n";

        double kernel_device = 0.0;
        const double t_kernel = time_median(
            [&] {
                const double t0 = now();
                kernel_device = compute_albedo(engine, kreq).kernel_seconds;
                return now() - t0;
            },
            o);
        auto time_baseline = [&](Flavour f) {
            return time_median_from(checked_seconds[int(f)], [&] { return run_baseline(cells, o.samples, p, f).seconds; }, o);
        };
        const double t_base = time_baseline(Flavour::Strict);
        const double t_fast = time_baseline(Flavour::FastMath);
        const double t_karith = time_baseline(Flavour::KernelArithmetic);
        const double t_plain = time_baseline(Flavour::PlainStrict);
        const double t_plain_fast = time_baseline(Flavour::PlainFastMath);
        const double pk = p == Precision::Float ? peak.gflops_float : peak.gflops_double;
        auto entry = [&](const std::string& impl, double t, double flops) {
            const double sps = n_samples / t;
            return json{{"precision", precision_name(p)},
                        {"implementation", impl},
                        {"cells", cells.mu.size()},
                        {"samples_per_cell", o.samples},
                        {"seconds", t},
                        {"samples_per_second", sps},
                        {"ratio_to_tuned_baseline", t_base / t},
                        {"ratio_to_plain_fastmath_baseline", t_plain_fast / t},
                        {"flops_per_sample", flops},
                        {"gflops", sps * flops * 1e-9},
                        {"fraction_of_peak", sps * flops * 1e-9 / pk}};
        };
        json ke = entry("kernel (PoCL)", t_kernel, kFlopsPerSample);
        ke["device_seconds"] = kernel_device;
        ke["max_error"] = max_err;
        ke["agreement"] = worst;
        thr.push_back(ke);
        thr.push_back(entry("tuned baseline (OpenMP, strict)", t_base, baseline::flops_per_sample(false)));
        thr.push_back(entry("tuned baseline (OpenMP, -ffast-math)", t_fast, baseline::flops_per_sample(false)));
        thr.push_back(entry("tuned C++ with the kernel's arithmetic (OpenMP, strict)", t_karith,
                            baseline::flops_per_sample(true)));
        thr.push_back(entry("plain baseline (OpenMP, strict)", t_plain, baseline::flops_per_sample(false, true)));
        thr.push_back(
            entry("plain baseline (OpenMP, -ffast-math)", t_plain_fast, baseline::flops_per_sample(false, true)));
        auto msps = [&](double t) { return fixed(n_samples / t * 1e-6, 1); };
        log << precision_name(p) << ": kernel " << msps(t_kernel) << " M samples/s; tuned baseline " << msps(t_base)
            << " (kernel x" << fixed(t_base / t_kernel, 2) << "), -ffast-math " << msps(t_fast)
            << ", kernel's arithmetic " << msps(t_karith) << "; plain baseline " << msps(t_plain) << ", -ffast-math "
            << msps(t_plain_fast) << " (kernel x" << fixed(t_plain_fast / t_kernel, 2) << ")\n";
    }
    j["throughput"] = thr;

    // Scaling: time against cells x samples (float; the kernel and the strict tuned baseline).
    json scaling = json::array();
    if (rep.agreed) {
        phase("scaling sweeps");
        auto point = [&](int n, std::uint64_t s, const char* sweep) {
            const TableCells t = table_cells(n);
            const AlbedoRequest kreq = kernel_request(t, s, Precision::Float);
            const double tk = time_median(
                [&] {
                    const double t0 = now();
                    compute_albedo(engine, kreq);
                    return now() - t0;
                },
                o);
            const double tb =
                time_median([&] { return run_baseline(t, s, Precision::Float, Flavour::Strict).seconds; }, o);
            const double work = double(t.mu.size()) * double(s);
            scaling.push_back({{"sweep", sweep},
                               {"cells", t.mu.size()},
                               {"samples_per_cell", s},
                               {"work", work},
                               {"kernel_seconds", tk},
                               {"kernel_ns_per_sample", tk / work * 1e9},
                               {"tuned_baseline_seconds", tb}});
            log << "scaling " << sweep << ": " << n << "x" << n << " x " << s << " samples: kernel " << fixed(tk, 4)
                << " s, tuned baseline " << fixed(tb, 4) << " s\n";
        };
        for (int n : o.scaling_sizes) point(n, o.scaling_size_samples, "size");
        for (std::uint64_t s : o.scaling_samples) point(o.scaling_samples_table, s, "samples");
    }
    j["scaling"] = scaling;

    // Table kinds: every kind of the registry at a fixed tolerance, through compute_lut (the
    // code path of `brdfbake lut KIND --tolerance T`). Fixed sizes (kind_texels), or, with
    // kind_seconds, a size that makes a run last about that long: a tiny table first (which
    // builds the kernels), timed again, then scaled, up to kind_texels. A first run gives the
    // checked table; then the median of timed runs. A kind that misses the tolerance gets a row
    // saying so, not a time.
    json kinds = json::array();
    if (o.kind_texels > 0)
        for (const std::string& pname : o.kind_precisions) {
            const Precision p = pname == "double" ? Precision::Double : Precision::Float;
            if (std::find(precisions.begin(), precisions.end(), p) == precisions.end()) continue;
            phase("table kinds, " + pname);
            const BenchOptions timing = kind_timing(o);
            for (size_t ki = 0; ki < table_kinds().size(); ++ki) {
                const TableKind* k = table_kinds()[ki];
                sub_step(k->name, ki, table_kinds().size());
                json row = {{"kind", k->name}, {"precision", precision_name(p)}, {"tolerance", o.kind_tolerance}};
                try {
                    // A 1D kind (its texels hold an integral over mu each) as long as a side of the 2D tables.
                    const double cap = k->one_dimensional ? std::sqrt(double(o.kind_texels)) : double(o.kind_texels);
                    double texels = cap;
                    const LutRequest small = kind_request(*k, 4, o.kind_tolerance, p);
                    // The last sized run: a first run of the final size that need not be repeated.
                    std::optional<Table> sized_table;
                    double sized_seconds = 0.0;
                    std::vector<int> sized_size;
                    if (!small.kind.empty()) {
                        compute_lut(engine, small);  // builds the kernels
                        // Grow the table until a run lasts at least half of kind_seconds (a tiny
                        // table's time is mostly the call's own cost, so one step is not enough).
                        LutRequest sized = small;
                        for (int step = 0; o.kind_seconds > 0 && step < 4; ++step) {
                            const double t0 = now();
                            sized_table = compute_lut(engine, sized);
                            sized_seconds = now() - t0;
                            sized_size = {sized.width, sized.height, sized.depth};
                            const double have = texel_count(sized, *k);
                            texels = std::clamp(have * o.kind_seconds / std::max(sized_seconds, 1e-4), have,
                                                std::max(cap, have));
                            if (sized_seconds >= 0.5 * o.kind_seconds || texels >= cap) {
                                texels = have;
                                break;
                            }
                            sized = kind_request(*k, texels, o.kind_tolerance, p);
                        }
                    }
                    const LutRequest r = kind_request(*k, texels, o.kind_tolerance, p);
                    if (r.kind.empty()) {
                        row["note"] = "no model and Fresnel term of the registry fits this kind";
                        kinds.push_back(row);
                        continue;
                    }
                    const double n_texels = texel_count(r, *k);
                    const double cells = n_texels * k->cells_per_texel * k->integrations(r);
                    row["model"] = r.model;
                    row["fresnel"] = r.fresnel;
                    row["size"] = size_text(r, *k);
                    row["texels"] = n_texels;
                    row["cells"] = cells;
                    const bool reuse = sized_table && sized_size == std::vector<int>{r.width, r.height, r.depth};
                    const double t0 = now();
                    const Table table = reuse ? *sized_table : compute_lut(engine, r);
                    const double first = reuse ? sized_seconds : now() - t0;
                    double max_err = 0.0;
                    for (double e : table.error) max_err = std::max(max_err, e);
                    const double t = time_median_from(
                        first,
                        [&] {
                            const double t1 = now();
                            compute_lut(engine, r);
                            return now() - t1;
                        },
                        timing);
                    row["first_run_seconds"] = first;
                    row["seconds"] = t;
                    row["texels_per_second"] = n_texels / t;
                    row["cells_per_second"] = cells / t;
                    row["max_error"] = max_err;
                    row["method"] = table.attributes.count("method") ? table.attributes.at("method") : "";
                    log << "kind " << k->name << " (" << precision_name(p) << ", " << row["size"].get<std::string>()
                        << "): " << fixed(n_texels / t, 0) << " texels/s, " << fixed(cells / t, 0)
                        << " cells/s, max error " << sci(max_err) << "\n";
                } catch (const Error& e) {
                    row["note"] = e.what();
                    log << "kind " << k->name << " (" << precision_name(p) << "): " << e.what() << "\n";
                }
                kinds.push_back(row);
            }
        }
    j["kinds"] = kinds;
    phase("");  // the last phase ends
    j["estimated_seconds"] = estimate;
    j["phases"] = phases;
    j["machine"]["loadavg_end"] = read_loadavg();
    j["total_seconds"] = now() - t_start;
    j["agreed"] = rep.agreed;

    // The Markdown tables: times only where the results agreed.
    std::ostringstream md;
    const json& m = j["machine"];
    md << "Machine: " << m["cpu"].get<std::string>() << ", " << m["cores"].get<unsigned>() << " cores ("
       << m["simd"].get<std::string>() << "), " << m["opencl_platform"].get<std::string>() << " "
       << m["pocl_version"].get<std::string>() << " (" << m["opencl_device"].get<std::string>()
       << "); load average " << m["loadavg_start"].get<std::string>() << " at the start, "
       << m["loadavg_end"].get<std::string>() << " at the end. FMA peak: " << fixed(peak.gflops_float, 1)
       << " GFLOP/s float, " << fixed(peak.gflops_double, 1) << " GFLOP/s double (" << peak.threads << " threads, "
       << peak.vector_bits << "-bit vectors). Baseline flags (tuned and plain loops): `"
       << baseline::compile_flags() << "`.\n\n";
    if (!rep.agreed) {
        md << "**The kernel and a baseline flavour disagreed; no times are reported.**\n\n```\n" << rep.disagreement
           << "```\n";
        rep.markdown = md.str();
        return rep;
    }
    md << "GGX albedo table (height-correlated, F = 1, VNDF importance sampling, randomised Hammersley, 16 "
          "replicas), "
       << o.table << "x" << o.table << " cells x " << o.samples
       << " samples; median of timed runs after a warm-up. Ratios: time of the strict tuned baseline "
          "(benchmarks/baseline_impl.h) and of the -ffast-math plain baseline (benchmarks/baseline_plain_impl.h, "
          "the issue's yardstick) over the row's time. Flops per sample counted from each implementation's source "
          "(benchmarks/harness/bench.cpp, benchmarks/baseline.cpp; the plain loop's sin and cos not counted).\n\n";
    md << "| precision | implementation | time (s) | M samples/s | vs tuned baseline (strict) | "
          "vs plain baseline (-ffast-math) | "
          "flops/sample | GFLOP/s | of peak |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& e : thr)
        md << "| " << e["precision"].get<std::string>() << " | " << e["implementation"].get<std::string>() << " | "
           << fixed(e["seconds"].get<double>(), 3) << " | " << fixed(e["samples_per_second"].get<double>() * 1e-6, 1)
           << " | " << fixed(e["ratio_to_tuned_baseline"].get<double>(), 2) << "x | "
           << fixed(e["ratio_to_plain_fastmath_baseline"].get<double>(), 2) << "x | "
           << fixed(e["flops_per_sample"].get<double>(), 0) << " | " << fixed(e["gflops"].get<double>(), 1) << " | "
           << fixed(100.0 * e["fraction_of_peak"].get<double>(), 1) << "% |\n";
    if (!builds.empty()) {
        md << "\nKernel build (albedo.cl for GGX: clBuildProgram and the first launch, which compiles the "
              "work-group function):\n\n| precision | cold cache (s) | warm cache (s) |\n| --- | ---: | ---: |\n";
        for (const auto& b : builds)
            md << "| " << b["precision"].get<std::string>() << " | " << fixed(b["cold_seconds"].get<double>(), 3)
               << " | " << fixed(b["warm_seconds"].get<double>(), 3) << " |\n";
        if (builds.size() > 1)
            md << "\nThe first cold build of a process also loads and parses PoCL's builtin library (about 0.7 s "
                  "with PoCL 3.1, whatever the kernel); the later rows share that load, so a cold build of "
                  "those programs in a new process takes that much longer.\n";
    }
    md << "\nScaling (float): time against cells x samples.\n\n| sweep | cells | samples/cell | cells x samples | "
          "kernel (s) | kernel ns/sample | tuned baseline (s) |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& s : scaling)
        md << "| " << s["sweep"].get<std::string>() << " | " << s["cells"].get<size_t>() << " | "
           << s["samples_per_cell"].get<std::uint64_t>() << " | " << sci(s["work"].get<double>()) << " | "
           << fixed(s["kernel_seconds"].get<double>(), 4) << " | " << fixed(s["kernel_ns_per_sample"].get<double>(), 2)
           << " | " << fixed(s["tuned_baseline_seconds"].get<double>(), 4) << " |\n";
    if (!kinds.empty()) {
        md << "\nTable kinds at tolerance " << sci(o.kind_tolerance)
           << " (`brdfbake lut KIND --tolerance T`, every kind of the registry with the first model and Fresnel "
              "term it accepts; median of timed runs after a first run that builds the kernels). Cells: the "
              "integrations of a table (texels x integrations per texel).\n\n| kind | model | size | precision | "
              "time (s) | texels/s | cells/s | max error | method |\n| --- | --- | --- | --- | ---: | ---: | ---: | "
              "---: | --- |\n";
        for (const auto& k : kinds) {
            md << "| " << k["kind"].get<std::string>() << " | " << k.value("model", std::string("-")) << " | "
               << k.value("size", std::string("-")) << " | " << k["precision"].get<std::string>() << " | ";
            if (k.contains("seconds"))
                md << fixed(k["seconds"].get<double>(), 3) << " | " << fixed(k["texels_per_second"].get<double>(), 0)
                   << " | " << fixed(k["cells_per_second"].get<double>(), 0) << " | "
                   << sci(k["max_error"].get<double>()) << " | " << k["method"].get<std::string>() << " |\n";
            else
                md << "- | - | - | - | " << k["note"].get<std::string>() << " |\n";
        }
    }
    rep.markdown = md.str();
    return rep;
}

void write_bench_report(const BenchReport& report, const std::string& dir, const std::string& name) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("cannot create directory '" + dir + "': " + ec.message());
    const std::string base = (std::filesystem::path(dir) / name).string();
    write_file_atomically(base + ".json", report.json.dump(2) + "\n");
    write_file_atomically(base + ".md", "# brdfbake benchmark: " + name + "\n\n" + report.markdown);
}

void write_bench_plot(const BenchReport& report, const std::string& path) {
    PlotSpec p;
    p.title = "GGX albedo table: time against cells x samples (float)";
    p.x.label = "cells x samples";
    p.y.label = "seconds";
    Curve ks{"kernel, table size sweep", {}, {}, "b-2o"}, kn{"kernel, samples sweep", {}, {}, "r-2s"};
    Curve bs{"tuned baseline, table size sweep", {}, {}, "b;2"};
    Curve bn{"tuned baseline, samples sweep", {}, {}, "r;2"};
    for (const auto& s : report.json.at("scaling")) {
        const bool size = s["sweep"] == "size";
        const double w = std::log10(s["work"].get<double>());
        (size ? ks : kn).x.push_back(w);
        (size ? ks : kn).y.push_back(std::log10(s["kernel_seconds"].get<double>()));
        (size ? bs : bn).x.push_back(w);
        (size ? bs : bn).y.push_back(std::log10(s["tuned_baseline_seconds"].get<double>()));
    }
    if (ks.x.empty()) throw Error("the report has no scaling data to plot");
    p.x.label = "log_{10}(cells x samples)";
    p.y.label = "log_{10}(seconds)";
    p.curves = {ks, kn, bs, bn};
    p.legend = LegendPlace::Outside;  // never over the baseline curves
    p.x.tick = 1.0;                   // one labelled tick per decade: the labels cannot overlap
    p.y.tick = 1.0;
    write_plot(path, p, 1300, 640);
}

std::string bench_cpu_model() { return read_cpu_model(); }
std::string bench_loadavg() { return read_loadavg(); }

}  // namespace brdfbake

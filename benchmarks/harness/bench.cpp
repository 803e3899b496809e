// The benchmark harness (benchmarks/harness/bench.h): GGX albedo tables through the kernel
// (compute_albedo, the code path of `brdfbake lut albedo`) against the OpenMP baselines of
// benchmarks/ (the tuned loop and the plain textbook loop), the FMA peak, kernel build times and
// scaling sweeps. The parts live beside it: bench_support.cpp (machine, timing, cells, plan)
// and bench_report.cpp (Markdown, files, plot).
#include "harness/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <thread>

#include <sys/utsname.h>

#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "brdfbake/progress.h"
#include "brdfbake/version.h"
#include "harness/bench_internal.h"

namespace brdfbake {

namespace {

using nlohmann::json;
using namespace bench_detail;

/// The run as one progress stage in estimated milliseconds, a phase a step; what runs inside
/// (a table's refinement) shows as part of the step. Records each phase's time beside its
/// estimate.
class PhaseTracker {
public:
    explicit PhaseTracker(const std::vector<BenchPhase>& plan)
        : plan_(plan), stage_("bench", total_ms(plan)), phase_start_(now()) {}

    /// Starts the named phase: the previous one ends (its time recorded beside its estimate).
    void phase(const std::string& name) {
        const double t = now();
        if (next_phase_ > 0) {
            phases_.back()["seconds"] = t - phase_start_;
            done_ms_ += ms(plan_[next_phase_ - 1].estimate);
        }
        while (next_phase_ < plan_.size() && plan_[next_phase_].name != name) ++next_phase_;  // a skipped phase
        if (next_phase_ >= plan_.size()) return;
        const BenchPhase& ph = plan_[next_phase_++];
        phases_.push_back({{"phase", ph.name}, {"estimated_seconds", ph.estimate}});
        stage_.update(done_ms_, ph.name, ms(ph.estimate));
        phase_start_ = t;
    }

    /// Part `index` of `count` of the current phase (a table kind): its share of the estimate,
    /// so that what runs inside it (a refinement) moves the bar within that share only.
    void sub_step(const std::string& name, size_t index, size_t count) {
        if (next_phase_ == 0 || count == 0) return;
        const BenchPhase& ph = plan_[next_phase_ - 1];
        const double share = ph.estimate * 1e3 / double(count);
        stage_.update(done_ms_ + std::uint64_t(share * double(index)), ph.name + ": " + name, std::uint64_t(share));
    }

    const json& phases() const { return phases_; }

private:
    static std::uint64_t ms(double seconds) { return std::uint64_t(seconds * 1e3 + 0.5); }
    static std::uint64_t total_ms(const std::vector<BenchPhase>& plan) {
        std::uint64_t total = 0;
        for (const BenchPhase& ph : plan) total += ms(ph.estimate);
        return total;
    }

    const std::vector<BenchPhase>& plan_;
    ProgressStage stage_;
    std::uint64_t done_ms_ = 0;
    size_t next_phase_ = 0;
    json phases_ = json::array();
    double phase_start_;
};

/// The machine's description in the report, and its line in the log.
json describe_machine(const DeviceInfo& dev) {
    struct utsname u {};
    ::uname(&u);
    return {{"cpu", read_cpu_model()},
            {"cores", std::thread::hardware_concurrency()},
            {"simd", cpu_simd()},
            {"os", std::string(u.sysname) + " " + u.release},
            {"opencl_platform", dev.platform},
            {"opencl_device", dev.name},
            {"opencl_version", dev.version},
            {"pocl_version", dev.driver},
            {"compute_units", dev.compute_units},
            {"loadavg_start", read_loadavg()}};
}

/// A fresh PoCL cache directory for the cold-build figure, removed with this object; `dir` is
/// empty when build times are not measured.
struct FreshPoclCache {
    std::string dir;
    explicit FreshPoclCache(bool wanted) {
        if (!wanted) return;
        std::string templ = (std::filesystem::temp_directory_path() / "brdfbake-bench-cache-XXXXXX").string();
        if (!::mkdtemp(templ.data())) throw Error("cannot create a temporary PoCL cache directory");
        dir = templ;
    }
    ~FreshPoclCache() {
        std::error_code ec;
        if (!dir.empty()) std::filesystem::remove_all(dir, ec);
    }
    FreshPoclCache(const FreshPoclCache&) = delete;
    FreshPoclCache& operator=(const FreshPoclCache&) = delete;
    std::optional<std::string> value() const { return dir.empty() ? std::nullopt : std::optional<std::string>(dir); }
};

/// Kernel build times: a fresh engine (new context) builds the albedo program and runs it on
/// one cell with 32 samples. PoCL compiles the work-group function at the first launch, so
/// the figure is clBuildProgram plus that first launch: what a command waits before work.
json measure_builds(const BenchOptions& o, const std::vector<Precision>& precisions, PhaseTracker& progress,
                    std::ostream& log) {
    json builds = json::array();
    if (!o.build_times) return builds;
    progress.phase("kernel builds");
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
    return builds;
}

/// How the kernel's checked table compared with every baseline flavour's.
struct Agreement {
    bool agreed = true;
    double worst = 0.0;            // the largest |difference| / (error_k + error_b)
    double checked_seconds[5]{};   // each flavour's checked run is its first timed one
};

/// Every flavour of the baseline must agree with the kernel within the two estimates; each
/// disagreement is added to the report and the log.
Agreement check_baselines(const TableCells& cells, const AlbedoResult& kres, const BenchOptions& o, Precision p,
                          BenchReport& rep, std::ostream& log) {
    const Flavour flavours[] = {Flavour::Strict, Flavour::FastMath, Flavour::KernelArithmetic, Flavour::PlainStrict,
                                Flavour::PlainFastMath};
    const char* flavour_names[] = {"tuned strict", "tuned -ffast-math", "tuned, kernel arithmetic", "plain strict",
                                   "plain -ffast-math"};
    Agreement a;
    for (int f = 0; f < 5; ++f) {
        const baseline::Result bres = run_baseline(cells, o.samples, p, flavours[f]);
        a.checked_seconds[f] = bres.seconds;
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
        a.worst = std::max(a.worst, worst_f);
        if (worst_f > 1.0 || bres.non_finite > 0) {
            a.agreed = false;
            std::ostringstream m;
            m << precision_name(p) << ", baseline " << flavour_names[f] << ": kernel " << kres.values[worst_cell].value
              << " +- " << kres.values[worst_cell].error << " vs baseline " << bres.value[worst_cell] << " +- "
              << bres.error[worst_cell] << " at mu = " << cells.mu[worst_cell] << ", alpha = " << cells.alpha[worst_cell]
              << "; baseline non-finite samples: " << bres.non_finite;
            rep.disagreement += m.str() + "\n";
            log << "DISAGREEMENT " << m.str() << "\n";
        }
    }
    return a;
}

/// The throughput rows of one precision, after its tables agreed: the kernel and each
/// baseline flavour, timed.
void time_throughput(Engine& engine, const TableCells& cells, const AlbedoRequest& kreq, const AlbedoResult& kres,
                     const Agreement& a, const BenchOptions& o, Precision p, const baseline::Peak& peak, json& thr,
                     std::ostream& log) {
    const double n_samples = double(cells.mu.size()) * double(o.samples);
    double max_err = 0.0;
    for (const auto& v : kres.values) max_err = std::max(max_err, v.error);
    log << precision_name(p) << ": kernel and every baseline flavour agree (largest |difference| / (error_k + error_b) = "
        << fixed(a.worst, 3) << ", max error " << sci(max_err) << ")\n";

    double kernel_device = 0.0;
    const double t_kernel = time_median(
        [&] {
            const double t0 = now();
            kernel_device = compute_albedo(engine, kreq).kernel_seconds;
            return now() - t0;
        },
        o);
    auto time_baseline = [&](Flavour f) {
        return time_median_from(a.checked_seconds[int(f)], [&] { return run_baseline(cells, o.samples, p, f).seconds; }, o);
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
    ke["agreement"] = a.worst;
    thr.push_back(ke);
    thr.push_back(entry("tuned baseline (OpenMP, strict)", t_base, baseline::flops_per_sample(false)));
    thr.push_back(entry("tuned baseline (OpenMP, -ffast-math)", t_fast, baseline::flops_per_sample(false)));
    thr.push_back(entry("tuned C++ with the kernel's arithmetic (OpenMP, strict)", t_karith,
                        baseline::flops_per_sample(true)));
    thr.push_back(entry("plain baseline (OpenMP, strict)", t_plain, baseline::flops_per_sample(false, true)));
    thr.push_back(entry("plain baseline (OpenMP, -ffast-math)", t_plain_fast, baseline::flops_per_sample(false, true)));
    auto msps = [&](double t) { return fixed(n_samples / t * 1e-6, 1); };
    log << precision_name(p) << ": kernel " << msps(t_kernel) << " M samples/s; tuned baseline " << msps(t_base)
        << " (kernel x" << fixed(t_base / t_kernel, 2) << "), -ffast-math " << msps(t_fast) << ", kernel's arithmetic "
        << msps(t_karith) << "; plain baseline " << msps(t_plain) << ", -ffast-math " << msps(t_plain_fast)
        << " (kernel x" << fixed(t_plain_fast / t_kernel, 2) << ")\n";
}

/// (a), (b): the throughput table, checked before any time is reported.
json measure_throughput(Engine& engine, const BenchOptions& o, const std::vector<Precision>& precisions,
                        const baseline::Peak& peak, PhaseTracker& progress, BenchReport& rep, std::ostream& log) {
    const TableCells cells = table_cells(o.table);
    json thr = json::array();
    rep.agreed = true;
    for (Precision p : precisions) {
        progress.phase(std::string("throughput, ") + precision_name(p));
        const AlbedoRequest kreq = kernel_request(cells, o.samples, p);
        const AlbedoResult kres = compute_albedo(engine, kreq);  // warm-up and the checked result
        const Agreement a = check_baselines(cells, kres, o, p, rep, log);
        if (!a.agreed) {
            rep.agreed = false;
            continue;
        }
        time_throughput(engine, cells, kreq, kres, a, o, p, peak, thr, log);
    }
    return thr;
}

/// Scaling: time against cells x samples (float; the kernel and the strict tuned baseline).
json measure_scaling(Engine& engine, const BenchOptions& o, PhaseTracker& progress, std::ostream& log) {
    json scaling = json::array();
    progress.phase("scaling sweeps");
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
        const double tb = time_median([&] { return run_baseline(t, s, Precision::Float, Flavour::Strict).seconds; }, o);
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
    return scaling;
}

/// The number of texels of kind k's timed table: kind_texels, or with kind_seconds, the size
/// of a run of about that long, found from a tiny table (which builds the kernels), timed
/// again, then scaled, up to kind_texels. The last sized run is kept in `sized` (a first run of
/// the final size that need not be repeated).
struct SizedRun {
    std::optional<Table> table;
    double seconds = 0.0;
    std::vector<int> size;
};
double kind_texels_to_time(Engine& engine, const TableKind& k, const BenchOptions& o, Precision p, SizedRun& sized_run) {
    // A 1D kind (its texels hold an integral over mu each) as long as a side of the 2D tables.
    const double cap = k.one_dimensional ? std::sqrt(double(o.kind_texels)) : double(o.kind_texels);
    double texels = cap;
    const LutRequest small = kind_request(k, 4, o.kind_tolerance, p);
    if (small.kind.empty()) return texels;
    compute_lut(engine, small);  // builds the kernels
    // Grow the table until a run lasts at least half of kind_seconds (a tiny table's time is
    // mostly the call's own cost, so one step is not enough).
    LutRequest sized = small;
    for (int step = 0; o.kind_seconds > 0 && step < 4; ++step) {
        const double t0 = now();
        sized_run.table = compute_lut(engine, sized);
        sized_run.seconds = now() - t0;
        sized_run.size = {sized.width, sized.height, sized.depth};
        const double have = texel_count(sized, k);
        texels = std::clamp(have * o.kind_seconds / std::max(sized_run.seconds, 1e-4), have, std::max(cap, have));
        if (sized_run.seconds >= 0.5 * o.kind_seconds || texels >= cap) {
            texels = have;
            break;
        }
        sized = kind_request(k, texels, o.kind_tolerance, p);
    }
    return texels;
}

/// One table kind's row: a first run gives the checked table, then the median of timed runs.
json measure_kind(Engine& engine, const TableKind& k, const BenchOptions& o, Precision p, std::ostream& log) {
    json row = {{"kind", k.name}, {"precision", precision_name(p)}, {"tolerance", o.kind_tolerance}};
    try {
        SizedRun sized;
        const double texels = kind_texels_to_time(engine, k, o, p, sized);
        const LutRequest r = kind_request(k, texels, o.kind_tolerance, p);
        if (r.kind.empty()) {
            row["note"] = "no model and Fresnel term of the registry fits this kind";
            return row;
        }
        const double n_texels = texel_count(r, k);
        const double cells = n_texels * k.cells_per_texel * k.integrations(r);
        row["model"] = r.model;
        row["fresnel"] = r.fresnel;
        row["size"] = size_text(r, k);
        row["texels"] = n_texels;
        row["cells"] = cells;
        const bool reuse = sized.table && sized.size == std::vector<int>{r.width, r.height, r.depth};
        const double t0 = now();
        const Table table = reuse ? *sized.table : compute_lut(engine, r);
        const double first = reuse ? sized.seconds : now() - t0;
        double max_err = 0.0;
        for (double e : table.error) max_err = std::max(max_err, e);
        const double t = time_median_from(
            first,
            [&] {
                const double t1 = now();
                compute_lut(engine, r);
                return now() - t1;
            },
            kind_timing(o));
        row["first_run_seconds"] = first;
        row["seconds"] = t;
        row["texels_per_second"] = n_texels / t;
        row["cells_per_second"] = cells / t;
        row["max_error"] = max_err;
        row["method"] = table.attributes.count("method") ? table.attributes.at("method") : "";
        log << "kind " << k.name << " (" << precision_name(p) << ", " << row["size"].get<std::string>()
            << "): " << fixed(n_texels / t, 0) << " texels/s, " << fixed(cells / t, 0) << " cells/s, max error "
            << sci(max_err) << "\n";
    } catch (const Error& e) {
        row["note"] = e.what();
        log << "kind " << k.name << " (" << precision_name(p) << "): " << e.what() << "\n";
    }
    return row;
}

/// Table kinds: every kind of the registry at a fixed tolerance, through compute_lut (the
/// code path of `brdfbake lut KIND --tolerance T`). A kind that misses the tolerance gets a
/// row saying so, not a time.
json measure_kinds(Engine& engine, const BenchOptions& o, const std::vector<Precision>& precisions,
                   PhaseTracker& progress, std::ostream& log) {
    json kinds = json::array();
    if (o.kind_texels <= 0) return kinds;
    for (const std::string& pname : o.kind_precisions) {
        const Precision p = pname == "double" ? Precision::Double : Precision::Float;
        if (std::find(precisions.begin(), precisions.end(), p) == precisions.end()) continue;
        progress.phase("table kinds, " + pname);
        for (size_t ki = 0; ki < table_kinds().size(); ++ki) {
            const TableKind* k = table_kinds()[ki];
            progress.sub_step(k->name, ki, table_kinds().size());
            kinds.push_back(measure_kind(engine, *k, o, p, log));
        }
    }
    return kinds;
}

}  // namespace

BenchReport run_bench(const BenchOptions& o, std::ostream& log) {
    BenchReport rep;
    json& j = rep.json;
    if (o.table < 1 || o.samples < 1) throw Error("bench: the table side and the samples must be positive");
    // Judged before anything is allocated: per cell, the table's coordinates, the kernel's request
    // and upload, its per-replica outputs and each baseline flavour's result (about 1 kB).
    int largest = o.table;
    for (int n : o.scaling_sizes) largest = std::max(largest, n);
    check_memory(double(largest) * largest * 1024.0, "bench with a " + std::to_string(largest) + "x" +
                                                          std::to_string(largest) + " table");

    // A fresh PoCL cache, so that the first build of each program is cold. PoCL reads
    // POCL_CACHE_DIR when OpenCL is first used in the process (the engine below), so the
    // variable is set only until the build times are measured, then restored; the directory
    // stays until the run ends (PoCL keeps writing to it).
    const FreshPoclCache cache(o.build_times);
    ScopedEnvironment cache_env("POCL_CACHE_DIR", cache.value());

    const double t_start = now();
    Engine engine(o.device, o.verbose);
    const DeviceInfo& dev = engine.device();
    j["machine"] = describe_machine(dev);
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

    // The estimate, then the run as one progress stage.
    const std::vector<BenchPhase> plan = plan_bench(o, peak, precisions);
    double estimate = kEngineSeconds + (o.quick ? 0.05 : 0.3);  // the engine, the FMA probe
    for (const BenchPhase& ph : plan) estimate += ph.estimate;
    log << "bench: about " << progress_duration(estimate) << " (" << (o.quick ? "quick" : o.kind_seconds > 0 ? "short" : "full")
        << " run; estimated from this machine's FMA peak and the development machine's timings; longer while "
           "PoCL's kernel cache is cold)\n";
    PhaseTracker progress(plan);
    j["peak"] = {{"gflops_float", peak.gflops_float},
                 {"gflops_double", peak.gflops_double},
                 {"threads", peak.threads},
                 {"vector_bits", peak.vector_bits}};

    j["build"] = measure_builds(o, precisions, progress, log);
    cache_env.restore();
    j["throughput"] = measure_throughput(engine, o, precisions, peak, progress, rep, log);
    j["scaling"] = rep.agreed ? measure_scaling(engine, o, progress, log) : json::array();
    j["kinds"] = measure_kinds(engine, o, precisions, progress, log);
    progress.phase("");  // the last phase ends
    j["estimated_seconds"] = estimate;
    j["phases"] = progress.phases();
    j["machine"]["loadavg_end"] = read_loadavg();
    j["total_seconds"] = now() - t_start;
    j["agreed"] = rep.agreed;
    rep.markdown = bench_markdown(rep, o, peak);
    return rep;
}

}  // namespace brdfbake

// The benchmark harness's parts (harness/bench_internal.h): the machine's description, the
// timing rules, the GGX albedo table's cells as the kernel and the baselines take them, the
// run's plan with its estimated seconds, and the table kinds' requests.
#include "harness/bench_internal.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"

namespace brdfbake {
namespace bench_detail {

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

/// What time_median spends on a run of `run` seconds (its first run and the timed ones).
double median_cost(double run, const BenchOptions& o) {
    if (o.quick || run >= o.min_seconds) return run;
    const double runs = std::min<double>(o.max_runs, std::max(1.0, std::ceil(o.min_seconds / std::max(run, 1e-6))));
    return run + runs * run;
}

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
constexpr double kColdBuildSeconds[2] = {2.3, 0.7};  // the first cold build of a process, and a later one
constexpr double kKindCellSeconds = 2.5e-5;     // an integration cell of a table at 1e-4 (the albedo's: 16 us)

BenchOptions kind_timing(const BenchOptions& o) {
    BenchOptions k = o;
    if (o.kind_seconds > 0) k.min_seconds = std::min(o.min_seconds, 2.0 * o.kind_seconds);
    return k;
}

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
/// model_names() and Fresnel term (none, a conductor's, the kind's example_fresnel) that validate_lut takes, so that
/// every kind, a new one too, gets a row without a list here. Empty kind when none fits.
LutRequest kind_request(const TableKind& k, double texels, double tolerance, Precision p) {
    std::vector<std::string> fresnels = {"none", "conductor:eta=0.2,k=3"};
    if (!k.example_fresnel.empty()) fresnels.push_back(k.example_fresnel);
    for (const std::string& fresnel : fresnels)
        for (const std::string& model : model_names()) {
            LutRequest r;
            r.kind = k.name;
            r.model = model;
            r.fresnel = fresnel;
            set_lut_size(r, kind_size(k, texels));
            r.tolerance.tolerance = k.simulated ? 0.0 : tolerance;  // a walk count, never a tolerance
            if (k.simulated) r.samples = std::uint64_t(1) << 16;
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

ScopedEnvironment::ScopedEnvironment(std::string name, const std::optional<std::string>& value)
    : name_(std::move(name)) {
    if (!value) return;
    if (const char* old = std::getenv(name_.c_str())) previous_ = old;
    ::setenv(name_.c_str(), value->c_str(), 1);
    active_ = true;
}

ScopedEnvironment::~ScopedEnvironment() { restore(); }

void ScopedEnvironment::restore() {
    if (!active_) return;
    if (previous_)
        ::setenv(name_.c_str(), previous_->c_str(), 1);
    else
        ::unsetenv(name_.c_str());
    active_ = false;
}

}  // namespace bench_detail

using bench_detail::cpu_simd;
using bench_detail::read_cpu_model;

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

std::string bench_cpu_model() { return read_cpu_model(); }
std::string bench_loadavg() { return bench_detail::read_loadavg(); }

}  // namespace brdfbake

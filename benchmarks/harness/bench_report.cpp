// The benchmark's report (benchmarks/harness/bench.h): the Markdown tables of
// docs/performance.md, the JSON and Markdown files, and the scaling plot.
#include <cmath>
#include <filesystem>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "harness/bench_internal.h"
#include "plot/plot.h"

namespace brdfbake {
namespace bench_detail {

std::string bench_markdown(const BenchReport& rep, const BenchOptions& o, const baseline::Peak& peak) {
    using nlohmann::json;
    const json& j = rep.json;
    const json& thr = j["throughput"];
    const json& builds = j["build"];
    const json& scaling = j["scaling"];
    const json& kinds = j["kinds"];
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
        return md.str();
    }
    md << "GGX albedo table (height-correlated, F = 1, VNDF importance sampling, randomised Hammersley, 16 "
          "replicas), "
       << o.table << "x" << o.table << " cells x " << o.samples
       << " samples; median of timed runs after a warm-up. Ratios: time of the strict tuned baseline "
          "(benchmarks/baseline_impl.h) and of the -ffast-math plain baseline (benchmarks/baseline_plain_impl.h, "
          "the issue's yardstick) over the row's time. Flops per sample counted from each implementation's source "
          "(benchmarks/harness/bench_internal.h, benchmarks/baseline.cpp; the plain loop's sin and cos not counted).\n\n";
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
    return md.str();
}

}  // namespace bench_detail

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

}  // namespace brdfbake

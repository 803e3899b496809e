// brdfbake-baseline: the baseline program for whole-command comparisons. It computes the table
// that `brdfbake lut albedo --model ggx:shadowing=correlated --size WxH --samples N
// --precision P` computes (same texel centres, estimator, replicas and shifts) with an OpenMP
// loop of benchmarks/ (by default the tuned one), and writes it as CSV (mu, alpha, E, error).
//   brdfbake-baseline --size 64x64 --samples 262144 --precision float [--plain] [--fast-math] -o E.csv
// --plain runs the plain textbook loop (baseline_plain_impl.h); --kernel-arithmetic the tuned loop
// with the shared headers' arithmetic (benchmarks/baseline.h).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "baseline.h"

int main(int argc, char** argv) {
    CLI::App app{"brdfbake-baseline: the GGX albedo table with a C++ OpenMP loop (tuned, or --plain)"};
    std::string size = "64x64", precision = "float", output;
    std::uint64_t samples = 1u << 18;
    bool fast = false, separable = false, karith = false, plain = false;
    app.add_option("--size", size, "WIDTHxHEIGHT (mu x alpha)")->capture_default_str();
    app.add_option("--samples", samples, "samples per texel")->capture_default_str();
    app.add_option("--precision", precision, "float or double")->check(CLI::IsMember({"float", "double"}));
    app.add_flag("--fast-math", fast, "the -ffast-math flavour (no NaN accounting)");
    app.add_flag("--plain", plain, "the plain textbook loop instead of the tuned one (combines with --fast-math)");
    app.add_flag("--kernel-arithmetic", karith, "the tuned loop with the kernel's operations (strict only)")
        ->excludes("--fast-math")
        ->excludes("--plain");
    app.add_flag("--separable", separable, "separable G2 instead of height-correlated");
    app.add_option("-o,--output", output, "CSV file (default: none)");
    CLI11_PARSE(app, argc, argv);
    int w = 0, h = 0;
    if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
        std::cerr << "brdfbake-baseline: error: --size must be WIDTHxHEIGHT\n";
        return 2;
    }
    brdfbake::baseline::Request r;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            r.mu.push_back((i + 0.5) / w);
            r.alpha.push_back(std::max((j + 0.5) / h, 1e-4));
        }
    r.samples = samples;
    r.single = precision == "float";
    r.fast_math = fast;
    r.kernel_arithmetic = karith;
    r.plain = plain;
    r.correlated = !separable;
    try {
        const brdfbake::baseline::Result res = brdfbake::baseline::albedo_table(r);
        double max_err = 0.0;
        for (double e : res.error) max_err = std::max(max_err, e);
        if (!output.empty()) {
            std::ofstream out(output);
            out << "mu,alpha,E,error\n";
            out.precision(9);
            for (size_t k = 0; k < r.mu.size(); ++k)
                out << r.mu[k] << "," << r.alpha[k] << "," << res.value[k] << "," << res.error[k] << "\n";
            if (!out) throw std::runtime_error("cannot write " + output);
        }
        std::fprintf(stderr, "brdfbake-baseline: %s loop%s, %dx%d table, %llu samples, %s, %d threads: %.3f s, "
                     "max error %.2e, non-finite samples %llu\n", plain ? "plain" : "tuned",
                     fast ? " (-ffast-math)" : "", w, h, (unsigned long long)samples, precision.c_str(), res.threads,
                     res.seconds, max_err, (unsigned long long)res.non_finite);
        return res.non_finite ? 1 : 0;
    } catch (const std::exception& e) {
        std::cerr << "brdfbake-baseline: error: " << e.what() << "\n";
        return 2;
    }
}

// Options shared by the commands that integrate: how much work, by which method, or to which
// tolerance.
#include <cmath>

#include "brdfbake/error.h"
#include "cli/cli.h"

namespace brdfbake {

void add_method_options(CLI::App* cmd, std::int64_t& samples, std::string& method, double& tolerance,
                        std::int64_t& max_samples, const std::string& per) {
    CLI::Option* s = cmd->add_option("--samples", samples,
                                     "samples per " + per + " (quadrature: n = sqrt(samples/4) nodes per axis of the finer rule, n^2 per azimuth piece)")
                         ->capture_default_str();
    cmd->add_option("--method", method,
                    "integration method: importance (the model's sampler, randomised Hammersley), qmc and mc "
                    "(uniform hemisphere, randomised Hammersley or Philox), quadrature (Gauss-Legendre, in "
                    "half-vector space for microfacet lobes); auto: importance with --samples, the engine's "
                    "per-cell choice with --tolerance")
        ->check(CLI::IsMember({"auto", "importance", "qmc", "mc", "quadrature"}))
        ->capture_default_str();
    cmd->add_option("--tolerance", tolerance,
                    "absolute error to reach in every " + per + " instead of a fixed sample count: each is refined "
                    "until its error estimate is at most this")
        ->excludes(s);
    cmd->add_option("--max-samples", max_samples, "with --tolerance: the most samples to spend on one " + per)
        ->capture_default_str();
}

MethodChoice resolve_method_choice(const std::string& method, double tolerance, std::int64_t max_samples) {
    MethodChoice c;
    const bool is_auto = method == "auto";
    c.method = is_auto ? Method::Importance : parse_method(method);
    if (tolerance != 0.0) {
        if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw Error("--tolerance must be a positive number");
        if (max_samples <= 0) throw Error("--max-samples must be positive");
        c.tolerance.tolerance = tolerance;
        c.tolerance.auto_method = is_auto;
        c.tolerance.max_samples = std::uint64_t(max_samples);
    }
    return c;
}

}  // namespace brdfbake

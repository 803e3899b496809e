// The --method choice: names, the command line's sample count and tolerance, and the smallest
// tolerance a precision can certify.
#include <cmath>

#include "brdfbake/albedo.h"
#include "brdfbake/error.h"

namespace brdfbake {

const char* method_name(Method m) {
    switch (m) {
    case Method::Importance:
        return "importance";
    case Method::QuasiMonteCarlo:
        return "qmc";
    case Method::MonteCarlo:
        return "mc";
    case Method::Quadrature:
        return "quadrature";
    }
    return "?";
}

Method parse_method(const std::string& name) {
    for (Method m : {Method::Importance, Method::QuasiMonteCarlo, Method::MonteCarlo, Method::Quadrature})
        if (name == method_name(m)) return m;
    throw Error("unknown method '" + name + "'; methods: auto, importance, qmc, mc, quadrature");
}

MethodChoice choose_method(const std::string& method, double samples, double tolerance, double max_samples) {
    if (!(samples >= 1.0) || samples > 1.8e19) throw Error("--samples must be a positive number");
    MethodChoice c;
    c.samples = std::uint64_t(samples);
    const bool is_auto = method == "auto";
    c.method = is_auto ? Method::Importance : parse_method(method);
    if (tolerance != 0.0) {
        if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw Error("--tolerance must be a positive number");
        if (!(max_samples >= 1.0) || max_samples > 1.8e19) throw Error("--max-samples must be positive");
        c.tolerance.tolerance = tolerance;
        c.tolerance.auto_method = is_auto;
        c.tolerance.max_samples = std::uint64_t(max_samples);
    }
    return c;
}

void check_method_for_model(const ModelTraits& model, Method method) {
    if (model.stochastic && method == Method::Quadrature)
        throw Error(std::string("model ") + model.name +
                    " is stochastic (its value is an estimate): quadrature cannot integrate it; use --method "
                    "importance, qmc or mc");
}

double tolerance_floor(Precision precision) {
    return 8.0 * (precision == Precision::Double ? 2.220446049250313e-16 : 1.1920929e-7);
}

}  // namespace brdfbake

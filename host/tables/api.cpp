// The one-call C++ API (include/brdfbake/api.h): the specs resolved and the options checked as
// the command line and the Python module do, then the same core functions.
#include "brdfbake/api.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>

#include "brdfbake/analytic.h"
#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "models/key_reader.h"

namespace brdfbake {

namespace {

/// One engine per device selector, created on first use and kept (kernel programs stay built).
/// Calls on one engine are serialised: the returned lock is held while it runs.
Engine& engine_for(const std::string& device, std::unique_lock<std::mutex>& lock) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<Engine>> engines;
    lock = std::unique_lock<std::mutex>(mutex);
    auto& e = engines[device];
    if (!e) e = std::make_unique<Engine>(device, false);
    return *e;
}

Precision precision_of(const std::string& name) {
    if (name == "float") return Precision::Float;
    if (name == "double") return Precision::Double;
    throw Error("precision must be \"float\" or \"double\"; got \"" + name + "\"");
}

}  // namespace

AlbedoValues albedo(const std::string& model_spec, const std::vector<double>& mu, const AlbedoOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const ModelConfig model = resolve_model(model_spec);
    const FresnelConfig fresnel = resolve_fresnel(o.fresnel, o.wavelength);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; leave AlbedoOptions::fresnel at \"none\"");
    const MethodChoice choice = choose_method(o.method, o.samples, o.tolerance, o.max_samples);
    if (mu.empty()) throw Error("albedo: mu is empty");
    if (o.phi_deg.size() > 1 && o.phi_deg.size() != mu.size())
        throw Error("albedo: phi_deg has " + std::to_string(o.phi_deg.size()) + " values for " +
                    std::to_string(mu.size()) + " mu; give one, or one per mu");
    AlbedoRequest req;
    req.model = model.id;
    req.fresnel = fresnel;
    req.samples = choice.samples;
    req.method = choice.method;
    req.precision = precision_of(o.precision);
    for (size_t i = 0; i < mu.size(); ++i) {
        if (!(mu[i] > 0.0 && mu[i] <= 1.0))
            throw Error("albedo: mu = " + format_number(mu[i]) + " is out of range; mu = cos(theta_o) must lie in (0, 1]");
        const double phi = o.phi_deg.empty() ? 0.0 : o.phi_deg[o.phi_deg.size() == 1 ? 0 : i];
        req.cells.push_back(AlbedoCell{mu[i], azimuth_from_degrees(phi), model.params});
    }
    std::unique_lock<std::mutex> lock;
    Engine& engine = engine_for(o.device, lock);
    const AlbedoResult r = albedo_of_model(engine, model, fresnel, req, choice.tolerance);
    return albedo_values(r, model, fresnel, engine.device().name,
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

AlbedoValues albedo_values(const AlbedoResult& r, const ModelConfig& model, const FresnelConfig& fresnel,
                           const std::string& device, double seconds) {
    AlbedoValues out;
    for (const AlbedoValue& v : r.values) {
        out.albedo.push_back(v.value);
        out.error.push_back(v.error);
    }
    out.model = model.canonical;
    out.fresnel = fresnel.canonical;
    out.method = r.method;
    out.samples = r.samples_per_cell;
    out.device = device;
    out.seconds = seconds;
    return out;
}

AlbedoValue albedo(const std::string& model, double mu, const AlbedoOptions& options) {
    const AlbedoValues v = albedo(model, std::vector<double>{mu}, options);
    AlbedoValue one;
    one.value = v.albedo.at(0);
    one.error = v.error.at(0);
    return one;
}

Table lut(const std::string& kind, const LutOptions& o) {
    // The same merge of preset and options as `brdfbake lut` and Python's lut() (apply_preset).
    LutSettings given;
    if (!kind.empty()) given.kind = kind;
    given.preset = o.preset;
    given.model = o.model;
    given.estimator = o.estimator;
    given.fresnel = o.fresnel;
    given.wavelength_nm = o.wavelength;
    if (!o.size.empty()) given.size = o.size;
    given.mu_map = o.mu_map;
    given.alpha_map = o.alpha_map;
    given.eta_map = o.eta_map;
    given.texels = o.texels;
    const auto range = [](const std::optional<std::pair<double, double>>& lo_hi) {
        return lo_hi ? std::optional<std::vector<double>>({lo_hi->first, lo_hi->second}) : std::nullopt;
    };
    given.alpha_range = range(o.alpha_range);
    given.mu_range = range(o.mu_range);
    given.eta_range = range(o.eta_range);
    given.mu_floor = o.mu_floor;
    given.axes = o.axes;
    given.flip = o.flip;
    given.samples = o.samples;
    given.tolerance = o.tolerance;
    given.max_samples = o.max_samples;
    given.method = o.method;
    given.precision = o.precision;
    const LutRequest r = apply_preset(given).request;
    validate_lut(r);  // every input checked before the device is touched
    std::unique_lock<std::mutex> lock;
    return compute_lut(engine_for(o.device, lock), r);
}

}  // namespace brdfbake

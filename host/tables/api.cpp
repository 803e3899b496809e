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
            throw Error("albedo: mu = " + std::to_string(mu[i]) + " is out of range; mu = cos(theta_o) must lie in (0, 1]");
        const double phi = o.phi_deg.empty() ? 0.0 : o.phi_deg[o.phi_deg.size() == 1 ? 0 : i];
        req.cells.push_back(AlbedoCell{mu[i], azimuth_from_degrees(phi), model.params});
    }
    std::unique_lock<std::mutex> lock;
    Engine& engine = engine_for(o.device, lock);
    const AlbedoResult r = albedo_of_model(engine, model, fresnel, req, choice.tolerance);
    AlbedoValues out;
    for (const AlbedoValue& v : r.values) {
        out.albedo.push_back(v.value);
        out.error.push_back(v.error);
    }
    out.model = model.canonical;
    out.fresnel = fresnel.canonical;
    out.method = r.method;
    out.samples = r.samples_per_cell;
    out.device = engine.device().name;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
    LutRequest r;
    const LutPreset* preset = o.preset ? &lut_preset(*o.preset) : nullptr;
    if (kind.empty() && !preset) throw Error("lut needs a table kind (" + table_kind_names() + ")");
    r.kind = kind.empty() ? preset->kinds.front() : kind;
    if (preset) {
        if (std::find(preset->kinds.begin(), preset->kinds.end(), r.kind) == preset->kinds.end())
            throw Error("preset '" + preset->name + "' has no layout for " + r.kind + " tables");
        preset->apply(r);
    } else if (!o.model) {
        throw Error("lut: LutOptions::model is required (or give a preset)");
    }
    if (o.model) r.model = *o.model;
    if (!o.size.empty()) set_lut_size(r, o.size);
    if (o.fresnel) r.fresnel = *o.fresnel;
    if (o.wavelength) r.wavelength_nm = *o.wavelength;
    if (o.mu_map) r.mu_map = *o.mu_map;
    if (o.alpha_map) r.alpha_map = *o.alpha_map;
    if (o.alpha_range) std::tie(r.alpha_lo, r.alpha_hi) = *o.alpha_range;
    if (o.mu_range) std::tie(r.mu_lo, r.mu_hi) = *o.mu_range;
    if (o.mu_floor) r.mu_floor = *o.mu_floor;
    if (o.eta_range) std::tie(r.eta_lo, r.eta_hi) = *o.eta_range;
    if (o.eta_map) r.eta_map = *o.eta_map;
    if (o.texels) r.texels = parse_texels(*o.texels);
    if (o.axes) r.axes = *o.axes;
    if (o.flip) r.flip = *o.flip;
    if (o.samples || o.tolerance || o.method || o.max_samples) {
        const double max_samples = double(r.tolerance.max_samples ? r.tolerance.max_samples : 1u << 26);
        const MethodChoice choice = choose_method(o.method.value_or("auto"), o.samples.value_or(double(r.samples)),
                                                  o.tolerance.value_or(0.0), o.max_samples.value_or(max_samples));
        r.samples = choice.samples;
        r.method = choice.method;
        r.tolerance = choice.tolerance;
    }
    if (o.precision) r.precision = precision_of(*o.precision);
    validate_lut(r);  // every input checked before the device is touched
    std::unique_lock<std::mutex> lock;
    return compute_lut(engine_for(o.device, lock), r);
}

}  // namespace brdfbake

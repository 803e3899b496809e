#include "brdfbake/check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/analytic.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/cancel.h"
#include "brdfbake/error.h"
#include "brdfbake/progress.h"
#include "engine/device_buffer.h"
#include "integrate/launch.h"
#include "integrate/random_walk.h"

namespace brdfbake {

ReciprocityMap scan_reciprocity(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                int n_theta, int n_phi, Precision precision) {
    if (n_theta < 1 || n_theta > 1024) throw Error("--resolution must be 1 to 1024");
    if (n_phi < 1 || n_phi > 1024) throw Error("--phi-resolution must be 1 to 1024");
    ReciprocityMap m;
    m.n_theta = n_theta;
    m.n_phi = n_phi;
    m.n_phi_o = model.anisotropic ? n_phi : 1;
    m.precision = precision;
    for (int k = 0; k < n_theta; ++k) m.theta.push_back((k + 0.5) / n_theta * M_PI / 2);

    BuildRequest build;
    build.kernel_file = "scan.cl";
    build.precision = precision;
    build.model = model.id;
    build.fresnel = fresnel.kind;
    cl::Program& program = engine.program(build);

    const size_t cells = size_t(n_theta) * n_theta;
    RealBuffers bufs(engine, precision);
    cl::Buffer b_theta = bufs.input(m.theta);
    cl::Buffer b_p = bufs.input({model.params.begin(), model.params.end()});
    cl::Buffer b_fp = bufs.input({fresnel.params.begin(), fresnel.params.end()});
    cl::Buffer b_data = model_data_buffer(bufs, model.id);
    cl::Buffer b_rel = bufs.output(cells), b_phi = bufs.output(cells), b_min = bufs.output(cells);
    const NonFiniteCounts bad_counts(engine, cells);
    cl::Kernel k(program, BB_ENTRY_NAME(BB_ENTRY_RECIPROCITY_SCAN));
    set_args(k, 0, b_theta, cl_uint(n_theta), cl_uint(n_phi), cl_uint(m.n_phi_o), b_p, b_fp, b_data, b_rel, b_phi, b_min,
             bad_counts.buffer);
    m.evaluations = std::uint64_t(cells) * n_phi * m.n_phi_o * 2;
    // Work-items (theta_i, theta_o) in groups of 4 x 4; a large scan runs in slices of theta_o
    // rows (run_items), reporting progress and honouring a cancel request between them.
    LaunchShape shape;
    shape.n_items = size_t(n_theta);
    shape.columns = size_t(n_theta);
    shape.local = 4;
    shape.slice_work = double(1 << 22);  // evaluations: a progress line about every 2^22
    std::ostringstream what;
    what << "reciprocity scan of " << n_theta << "x" << n_theta << " directions x " << n_phi * m.n_phi_o << " azimuths";
    run_items(engine, k, shape, double(m.evaluations) / n_theta, what.str());
    m.max_rel = bufs.read(b_rel, cells);
    m.dphi_at_max = bufs.read(b_phi, cells);
    m.min_value = bufs.read(b_min, cells);
    for (cl_uint b : bad_counts.read(engine)) m.nonfinite += b;
    return m;
}

AlbedoRequest furnace_request(const ModelConfig& model, const FresnelConfig& fresnel, const CheckOptions& o) {
    AlbedoRequest req;
    req.model = model.id;
    req.fresnel = fresnel;
    req.samples = o.samples;
    req.precision = o.precision;
    const int nphi = model.anisotropic ? o.phis : 1;
    for (int p = 0; p < nphi; ++p)
        for (int k = 0; k < o.directions; ++k)
            req.cells.push_back({std::cos((k + 0.5) / o.directions * M_PI / 2), p * M_PI / nphi, model.params});
    return req;
}

void record_furnace(CheckReport& r, const std::vector<AlbedoValue>& values, const AlbedoRequest& req) {
    for (size_t c = 0; c < values.size(); ++c) {
        const AlbedoValue& v = values[c];
        if (c == 0 || v.value - v.error > r.max_albedo - r.max_albedo_error) {
            r.max_albedo = v.value;
            r.max_albedo_error = v.error;
            r.max_albedo_mu = req.cells[c].mu;
            r.max_albedo_phi = req.cells[c].phi;
        }
    }
    r.energy_violation = r.max_albedo - r.max_albedo_error > 1.0 + r.options.energy_tolerance;
}

CheckReport run_check(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel, const CheckOptions& o) {
    if (o.directions < 1 || o.directions > 4096) throw Error("--directions must be 1 to 4096");
    if (o.phis < 1 || o.phis > 360) throw Error("--phis must be 1 to 360");
    if (!(o.energy_tolerance >= 0) || !(o.reciprocity_tolerance >= 0)) throw Error("tolerances must be >= 0");
    if (model.simulated) return run_check_walk(engine, model, fresnel, o);  // integrate/check_walk.cpp
    CheckReport r;
    r.options = o;
    r.model = model.canonical;
    r.fresnel = fresnel.canonical;

    // Values and reciprocity, in double where the device has it (round-off then stays far
    // below any tolerance a user would set).
    const Precision scan_precision = engine.device().fp64 ? Precision::Double : Precision::Float;
    // Two parts, shown as one stage: the scan, then the furnace.
    ProgressStage stage("check of " + model.canonical, 2);
    stage.update(0, "reciprocity and value scan", 1);
    r.reciprocity_tolerance = o.reciprocity_tolerance;
    if (scan_precision == Precision::Float) r.reciprocity_tolerance = std::max(o.reciprocity_tolerance, 1e-3);
    const ReciprocityMap map = scan_reciprocity(engine, model, fresnel, o.resolution, o.phi_resolution, scan_precision);
    r.pairs = map.evaluations / 2;
    r.nonfinite = map.nonfinite;
    r.scan_nonfinite = map.nonfinite;
    r.min_value = map.min_value.empty() ? 0.0 : map.min_value[0];
    for (size_t k = 0; k < map.max_rel.size(); ++k) {
        r.min_value = std::min(r.min_value, map.min_value[k]);
        if (map.max_rel[k] > r.max_rel) {
            r.max_rel = map.max_rel[k];
            r.max_rel_theta_i = map.theta[k % size_t(map.n_theta)];
            r.max_rel_theta_o = map.theta[k / size_t(map.n_theta)];
            r.max_rel_dphi = map.dphi_at_max[k];
        }
    }
    r.reciprocity_violation = r.max_rel > r.reciprocity_tolerance;

    // White furnace over theta_o (and phi_o for anisotropic models).
    const AlbedoRequest req = furnace_request(model, fresnel, o);
    r.furnace_directions = int(req.cells.size());
    stage.update(1, "white furnace of " + std::to_string(req.cells.size()) + " directions", 1);
    try {
        const AlbedoResult res = has_analytic_albedo(model) ? analytic_albedo_result(model, fresnel, req.cells)
                                                            : compute_albedo(engine, req);
        r.furnace_samples = res.samples_per_cell;
        r.furnace_analytic = res.samples_per_cell == 0;
        record_furnace(r, res.values, req);
    } catch (const NonFiniteError& e) {
        r.nonfinite += e.count;
        std::ostringstream w;
        w << "importance samples at mu = " << req.cells[e.cell].mu;
        r.nonfinite_where = w.str();
        r.energy_violation = false;  // unknown: the furnace could not be computed
    }
    r.value_violation = r.nonfinite > 0 || r.min_value < 0.0;
    return r;
}

std::string check_report_text(const CheckReport& r) {
    constexpr double kDeg = 180.0 / M_PI;
    std::ostringstream out;
    char line[512];
    out << "check " << r.model << " (Fresnel " << r.fresnel << ")\n";
    if (r.furnace_analytic)
        std::snprintf(line, sizeof line, "  energy       %s  max E = %.6f (analytic) at mu = %.4f (%d directions)\n",
                      r.energy_violation ? "FAIL" : "pass", r.max_albedo, r.max_albedo_mu, r.furnace_directions);
    else if (r.furnace_samples == 0)
        std::snprintf(line, sizeof line, "  energy       n/a   the furnace met NaN or Inf (%s)\n", r.nonfinite_where.c_str());
    else
        std::snprintf(line, sizeof line,
                      "  energy       %s  max E = %.6f +- %.1e at mu = %.4f%s (%d directions, %llu samples each, "
                      "tolerance %.0e)\n",
                      r.energy_violation ? "FAIL" : "pass", r.max_albedo, r.max_albedo_error, r.max_albedo_mu,
                      r.max_albedo_phi != 0.0 ? (", phi = " + std::to_string(int(std::lround(r.max_albedo_phi * kDeg))) + " deg").c_str() : "",
                      r.furnace_directions, (unsigned long long)r.furnace_samples, r.options.energy_tolerance);
    out << line;
    if (r.scan_nonfinite > 0)
        std::snprintf(line, sizeof line, "  reciprocity  n/a   the scan met %llu NaN or Inf values (%llu pairs)\n",
                      (unsigned long long)r.scan_nonfinite, (unsigned long long)r.pairs);
    else if (r.reciprocity_noise)
        std::snprintf(line, sizeof line,
                      "  reciprocity  %s  max %s = %.2f standard errors (relative %.2e) at theta_i = "
                      "%.1f, theta_o = %.1f, dphi = %.1f deg (%llu pairs of walk estimates, tolerance %.0f standard "
                      "errors + %.0e)\n",
                      r.reciprocity_violation ? "FAIL" : "pass", r.reciprocity_of.c_str(), r.reciprocity_sigmas, r.max_rel,
                      r.max_rel_theta_i * kDeg, r.max_rel_theta_o * kDeg, r.max_rel_dphi * kDeg, (unsigned long long)r.pairs, kReciprocitySigmas,
                      r.reciprocity_tolerance);
    else if (r.max_rel == 0.0)
        std::snprintf(line, sizeof line, "  reciprocity  pass  f(wo,wi) = f(wi,wo) exactly at every pair (%llu pairs)\n",
                      (unsigned long long)r.pairs);
    else
        std::snprintf(line, sizeof line,
                      "  reciprocity  %s  max relative error %.2e at theta_i = %.1f, theta_o = %.1f, dphi = %.1f deg "
                      "(%llu pairs, tolerance %.0e)\n",
                      r.reciprocity_violation ? "FAIL" : "pass", r.max_rel, r.max_rel_theta_i * kDeg,
                      r.max_rel_theta_o * kDeg, r.max_rel_dphi * kDeg, (unsigned long long)r.pairs,
                      r.reciprocity_tolerance);
    out << line;
    if (r.nonfinite > 0)  // the smallest f is not a measured figure once a value is not finite
        std::snprintf(line, sizeof line, "  values       FAIL  %llu NaN or Inf\n", (unsigned long long)r.nonfinite);
    else
        std::snprintf(line, sizeof line, "  values       %s  0 NaN or Inf, smallest f = %.3g\n",
                      r.value_violation ? "FAIL" : "pass", r.min_value);
    out << line;
    out << "verdict: " << (r.passed() ? "PASS" : "VIOLATION") << "\n";
    return out.str();
}

}  // namespace brdfbake

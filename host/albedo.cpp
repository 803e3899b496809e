#include "brdfbake/albedo.h"

#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <cmath>
#include <sstream>

#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/sampling.h"
#include "brdfbake/error.h"
#include "device_buffer.h"

namespace brdfbake {

std::vector<AlbedoCell> cells_for(const std::vector<double>& mus, double phi, const ParamBlock& params) {
    std::vector<AlbedoCell> cells;
    for (double mu : mus) cells.push_back(AlbedoCell{mu, phi, params});
    return cells;
}

namespace {

// Cranley-Patterson shifts, two per replica, from Philox4x32-10 (Salmon et al. 2011) keyed by
// the seed: counter-based, so replica r's shift does not depend on how many replicas there are.
std::vector<double> replica_shifts(unsigned replicas, std::uint64_t seed) {
    using Philox = r123::Philox4x32;
    Philox rng;
    Philox::key_type key = {{std::uint32_t(seed), std::uint32_t(seed >> 32)}};
    std::vector<double> shifts;
    for (unsigned r = 0; r < replicas; ++r) {
        Philox::ctr_type ctr = {{r, 0x616c6264u /* "albd" */, 0, 0}};
        const Philox::ctr_type out = rng(ctr, key);
        // 53-bit doubles in [0, 1) from two 32-bit words each.
        shifts.push_back(r123::u01<double>(std::uint64_t(out[0]) << 32 | out[1]));
        shifts.push_back(r123::u01<double>(std::uint64_t(out[2]) << 32 | out[3]));
    }
    for (double& s : shifts)
        if (s >= 1.0) s = 0.0;
    return shifts;
}

std::string method_text(unsigned replicas, std::uint64_t points) {
    std::ostringstream m;
    m << "importance sampling, randomised Hammersley (" << replicas << " replicas x " << points << " points)";
    return m.str();
}

// Mean and error estimate of each cell from its replica means. The error is 3 standard errors of
// the replicas plus a floating-point bound: the per-sample weight carries a few ulps of rounding
// error that averaging does not remove (compensated summation keeps the sums exact to ~1 ulp).
// Throws Error if any sample of a cell was non-finite (`where(cell)` names the cell).
template <typename Where>
std::vector<AlbedoValue> summarize(const std::vector<double>& means, const std::vector<cl_uint>& bad,
                                   unsigned replicas, Precision precision, Where where) {
    const double eps = precision == Precision::Double ? 2.220446049250313e-16 : 1.1920929e-7;
    const size_t n_cells = means.size() / replicas;
    std::vector<AlbedoValue> out;
    for (size_t c = 0; c < n_cells; ++c) {
        std::uint64_t n_bad = 0;
        double sum = 0.0;
        for (unsigned r = 0; r < replicas; ++r) {
            n_bad += bad[c * replicas + r];
            sum += means[c * replicas + r];
        }
        if (n_bad > 0)
            throw NonFiniteError(where(c) + " (" + std::to_string(n_bad) + " samples); refusing to report a result", c,
                                 n_bad);
        const double mean = sum / replicas;
        double ss = 0.0;
        for (unsigned r = 0; r < replicas; ++r) ss += std::pow(means[c * replicas + r] - mean, 2);
        const double std_error = std::sqrt(ss / (replicas - 1) / replicas);
        out.push_back({mean, 3.0 * std_error + 8.0 * eps * std::max(std::fabs(mean), 1e-3)});
    }
    return out;
}

void check_sampling(std::uint64_t samples, unsigned replicas) {
    if (replicas < 2) throw Error("at least 2 replicas are needed for an error estimate");
    if (samples < replicas) throw Error("--samples must be at least " + std::to_string(replicas));
    if (samples / replicas > 0xffffffffu) throw Error("--samples is too large (at most 2^32 per replica)");
}

cl::NDRange global_range(size_t items, size_t local) { return cl::NDRange((items + local - 1) / local * local); }

constexpr size_t kLocalSize = 8;

// The cell-independent half of the vector path: the disk point bb_disk_polar(u1, u2) of every
// point of every replica (the rotated Hammersley point, as the scalar kernel forms it), laid out
// for vector loads: per replica, per step of `lanes` points, the lanes' x then their y. Computed
// here once in double with the shared functions and rounded to the kernel's real; the float
// kernel sees its shifts rounded to float, as the scalar kernel does.
std::vector<double> disk_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                               unsigned lanes, Precision precision) {
    std::vector<double> table(size_t(replicas) * points * 2);
    const unsigned n = unsigned(points);
    for (unsigned r = 0; r < replicas; ++r) {
        double s1 = shifts[2 * r], s2 = shifts[2 * r + 1];
        if (precision == Precision::Float) {
            s1 = double(float(s1));
            s2 = double(float(s2));
        }
        double* out = table.data() + size_t(r) * points * 2;
        for (unsigned i = 0; i < n; ++i) {
            const bb_vec2 d = bb_disk_polar(bb_rotate(bb_hammersley_u1(i, n), s1), bb_rotate(bb_hammersley_u2(i), s2));
            const size_t base = size_t(i / lanes) * 2 * lanes + i % lanes;
            out[base] = d.x;
            out[base + lanes] = d.y;
        }
    }
    return table;
}

}  // namespace

AlbedoResult compute_albedo(Engine& engine, const AlbedoRequest& req) {
    if (req.cells.empty()) throw Error("no directions to integrate");
    check_sampling(req.samples, req.replicas);
    for (const auto& c : req.cells)
        if (!(c.mu > 0.0 && c.mu <= 1.0) || !std::isfinite(c.phi))
            throw Error("mu must lie in (0, 1]; got " + std::to_string(c.mu));
    const std::uint64_t points = req.samples / req.replicas;

    const size_t n_cells = req.cells.size();
    const size_t n_items = n_cells * req.replicas;

    BuildRequest build;
    build.kernel_file = "albedo.cl";
    build.precision = req.precision;
    build.defines = {{"BB_MODEL", std::to_string(req.model)},
                     {"BB_FRESNEL", std::to_string(req.fresnel.kind)}};
    // The vector path: W samples per step, their disk points from a table shared by all cells.
    build.has_vector_path = bb_model_samples_disk(req.model) != 0;
    build.vector_width = req.vector_width;
    unsigned lanes = engine.vector_width(build);
    if (lanes > 1 && points % lanes != 0) {
        build.vector_width = 1;  // a ragged last step: the scalar kernel
        lanes = 1;
    }
    cl::Program& program = engine.program(build);

    std::vector<double> mus(n_cells), phis(n_cells), params(n_cells * BB_MAX_PARAMS);
    for (size_t c = 0; c < n_cells; ++c) {
        mus[c] = req.cells[c].mu;
        phis[c] = req.cells[c].phi;
        for (int k = 0; k < BB_MAX_PARAMS; ++k) params[c * BB_MAX_PARAMS + k] = req.cells[c].params[k];
    }
    const std::vector<double> fparams(req.fresnel.params.begin(), req.fresnel.params.end());
    const std::vector<double> shifts = replica_shifts(req.replicas, req.seed);

    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(mus), b_phi = bufs.input(phis), b_p = bufs.input(params),
               b_fp = bufs.input(fparams);
    cl::Buffer b_points = bufs.input(lanes > 1 ? disk_table(shifts, req.replicas, points, lanes, req.precision) : shifts);
    cl::Buffer b_mean = bufs.output(n_items);
    cl::Buffer b_bad(engine.context(), CL_MEM_WRITE_ONLY, n_items * sizeof(cl_uint));

    cl::Kernel kernel(program, lanes > 1 ? "albedo_replicas_disk" : "albedo_replicas");
    int a = 0;
    kernel.setArg(a++, b_mu);
    kernel.setArg(a++, b_phi);
    kernel.setArg(a++, b_p);
    kernel.setArg(a++, b_fp);
    kernel.setArg(a++, b_points);
    kernel.setArg(a++, cl_uint(points));
    kernel.setArg(a++, cl_uint(req.replicas));
    kernel.setArg(a++, cl_uint(n_cells));
    kernel.setArg(a++, b_mean);
    kernel.setArg(a++, b_bad);

    // An explicit small work-group: the default could give PoCL two groups for two cores, or
    // one, whatever the table size (issue 9).
    cl::Event done;
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, global_range(n_items, kLocalSize),
                                        cl::NDRange(kLocalSize), nullptr, &done);
    const std::vector<double> means = bufs.read(b_mean, n_items);
    std::vector<cl_uint> bad(n_items);
    engine.queue().enqueueReadBuffer(b_bad, CL_TRUE, 0, n_items * sizeof(cl_uint), bad.data());

    AlbedoResult result;
    result.samples_per_cell = points * req.replicas;
    result.kernel_seconds = event_seconds(done);
    result.vector_width = lanes;
    result.method = method_text(req.replicas, points);
    result.values = summarize(means, bad, req.replicas, req.precision, [&](size_t c) {
        std::ostringstream m;
        m << "the BRDF produced NaN or Inf at mu = " << req.cells[c].mu;
        return m.str();
    });
    return result;
}

DielectricResult compute_dielectric(Engine& engine, const DielectricRequest& req) {
    if (req.cells.empty()) throw Error("no cells to integrate");
    check_sampling(req.samples, req.replicas);
    for (const auto& c : req.cells)
        if (!(c.mu > 0.0 && c.mu <= 1.0) || !(c.alpha >= BB_ALPHA_MIN) || !(c.eta > 0.0) || !std::isfinite(c.eta))
            throw Error("dielectric cell out of range (mu in (0, 1], alpha >= 1e-4, eta > 0)");
    const std::uint64_t points = req.samples / req.replicas;
    const size_t n_cells = req.cells.size(), n_items = n_cells * req.replicas;

    BuildRequest build;
    build.kernel_file = "dielectric.cl";
    build.precision = req.precision;
    cl::Program& program = engine.program(build);

    std::vector<double> mus, alphas, etas;
    for (const auto& c : req.cells) {
        mus.push_back(c.mu);
        alphas.push_back(c.alpha);
        etas.push_back(c.eta);
    }
    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(mus), b_alpha = bufs.input(alphas), b_eta = bufs.input(etas),
               b_shift = bufs.input(replica_shifts(req.replicas, req.seed));
    cl::Buffer b_r = bufs.output(n_items), b_t = bufs.output(n_items);
    cl::Buffer b_bad(engine.context(), CL_MEM_WRITE_ONLY, n_items * sizeof(cl_uint));
    cl::Kernel kernel(program, "dielectric_replicas");
    int a = 0;
    kernel.setArg(a++, b_mu);
    kernel.setArg(a++, b_alpha);
    kernel.setArg(a++, b_eta);
    kernel.setArg(a++, b_shift);
    kernel.setArg(a++, cl_uint(points));
    kernel.setArg(a++, cl_uint(req.replicas));
    kernel.setArg(a++, cl_uint(n_cells));
    kernel.setArg(a++, cl_int(req.correlated ? 1 : 0));
    kernel.setArg(a++, b_r);
    kernel.setArg(a++, b_t);
    kernel.setArg(a++, b_bad);
    cl::Event done;
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, global_range(n_items, 8), cl::NDRange(8), nullptr,
                                        &done);
    const std::vector<double> r = bufs.read(b_r, n_items), t = bufs.read(b_t, n_items);
    std::vector<cl_uint> bad(n_items);
    engine.queue().enqueueReadBuffer(b_bad, CL_TRUE, 0, n_items * sizeof(cl_uint), bad.data());

    DielectricResult result;
    result.samples_per_cell = points * req.replicas;
    result.kernel_seconds = event_seconds(done);
    result.method = method_text(req.replicas, points);
    auto where = [&](size_t c) {
        std::ostringstream m;
        m << "the rough dielectric produced NaN or Inf at mu = " << req.cells[c].mu << ", alpha = " << req.cells[c].alpha
          << ", eta = " << req.cells[c].eta;
        return m.str();
    };
    result.reflected = summarize(r, bad, req.replicas, req.precision, where);
    result.transmitted = summarize(t, bad, req.replicas, req.precision, where);
    return result;
}

}  // namespace brdfbake

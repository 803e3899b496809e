#include "brdfbake/albedo.h"

#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <cmath>
#include <sstream>

#include "brdfbake/brdf/models.h"
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

}  // namespace

AlbedoResult compute_albedo(Engine& engine, const AlbedoRequest& req) {
    if (req.cells.empty()) throw Error("no directions to integrate");
    if (req.replicas < 2) throw Error("at least 2 replicas are needed for an error estimate");
    if (req.samples < req.replicas)
        throw Error("--samples must be at least " + std::to_string(req.replicas));
    for (const auto& c : req.cells)
        if (!(c.mu > 0.0 && c.mu <= 1.0) || !std::isfinite(c.phi))
            throw Error("mu must lie in (0, 1]; got " + std::to_string(c.mu));
    const std::uint64_t points = req.samples / req.replicas;
    if (points > 0xffffffffu) throw Error("--samples is too large (at most 2^32 per replica)");

    const size_t n_cells = req.cells.size();
    const size_t n_items = n_cells * req.replicas;

    BuildRequest build;
    build.kernel_file = "albedo.cl";
    build.precision = req.precision;
    build.defines = {{"BB_MODEL", std::to_string(req.model)},
                     {"BB_FRESNEL", std::to_string(req.fresnel.kind)}};
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
               b_fp = bufs.input(fparams), b_shift = bufs.input(shifts);
    cl::Buffer b_mean = bufs.output(n_items);
    cl::Buffer b_bad(engine.context(), CL_MEM_WRITE_ONLY, n_items * sizeof(cl_uint));

    cl::Kernel kernel(program, "albedo_replicas");
    int a = 0;
    kernel.setArg(a++, b_mu);
    kernel.setArg(a++, b_phi);
    kernel.setArg(a++, b_p);
    kernel.setArg(a++, b_fp);
    kernel.setArg(a++, b_shift);
    kernel.setArg(a++, cl_uint(points));
    kernel.setArg(a++, cl_uint(req.replicas));
    kernel.setArg(a++, cl_uint(n_cells));
    kernel.setArg(a++, b_mean);
    kernel.setArg(a++, b_bad);

    const size_t local = 8;
    const size_t global = (n_items + local - 1) / local * local;
    cl::Event done;
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(local),
                                        nullptr, &done);
    const std::vector<double> means = bufs.read(b_mean, n_items);
    std::vector<cl_uint> bad(n_items);
    engine.queue().enqueueReadBuffer(b_bad, CL_TRUE, 0, n_items * sizeof(cl_uint), bad.data());

    AlbedoResult result;
    result.samples_per_cell = points * req.replicas;
    result.kernel_seconds = event_seconds(done);
    {
        std::ostringstream m;
        m << "importance sampling, randomised Hammersley (" << req.replicas << " replicas x " << points
          << " points)";
        result.method = m.str();
    }
    // Floating-point bound: the per-sample weight carries a few ulps of rounding error that
    // averaging does not remove; compensated summation keeps the sum itself exact to ~1 ulp.
    const double eps = req.precision == Precision::Double ? 2.220446049250313e-16 : 1.1920929e-7;
    for (size_t c = 0; c < n_cells; ++c) {
        std::uint64_t n_bad = 0;
        double sum = 0.0;
        for (unsigned r = 0; r < req.replicas; ++r) {
            n_bad += bad[c * req.replicas + r];
            sum += means[c * req.replicas + r];
        }
        if (n_bad > 0) {
            std::ostringstream m;
            m << "the BRDF produced " << n_bad << " non-finite values (NaN or Inf) at mu = "
              << req.cells[c].mu << "; refusing to report a result";
            throw Error(m.str());
        }
        const double mean = sum / req.replicas;
        double ss = 0.0;
        for (unsigned r = 0; r < req.replicas; ++r) ss += std::pow(means[c * req.replicas + r] - mean, 2);
        const double std_error = std::sqrt(ss / (req.replicas - 1) / req.replicas);
        const double fp_bound = 8.0 * eps * std::max(std::fabs(mean), 1e-3);
        result.values.push_back({mean, 3.0 * std_error + fp_bound});
    }
    return result;
}

}  // namespace brdfbake

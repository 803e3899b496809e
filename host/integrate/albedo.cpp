// The albedo integrators: the sampling methods (importance, qmc, mc; kernels/albedo.cl's replica
// entry points) and the Gauss-Legendre product rule (its quadrature entry points).
#include "brdfbake/albedo.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "brdfbake/brdf/integrands.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "engine/device_buffer.h"
#include "integrate/distributed_compute.h"
#include "integrate/launch.h"
#include "integrate/quadrature_rules.h"
#include "integrate/replicas.h"
#include "models/key_reader.h"
#include "models/params.h"

namespace brdfbake {

std::vector<AlbedoCell> cells_for(const std::vector<double>& mus, double phi, const ParamBlock& params) {
    std::vector<AlbedoCell> cells;
    for (double mu : mus) cells.push_back(AlbedoCell{mu, phi, params});
    return cells;
}

namespace {

std::string quadrature_text(int model, unsigned n) {
    std::ostringstream m;
    m << "Gauss-Legendre product rule in "
      << (model_traits(model).halfvector_quadrature ? "half-vector space" : "the sampler's unit square")
      << ", " << n << " x " << n << " nodes per azimuth piece (2 to 8 pieces), error from the " << n / 2
      << "- and " << n / 4 << "-node rules";
    return m.str();
}

struct CellArrays {
    std::vector<double> mus, phis, params;
};

CellArrays cell_arrays(const std::vector<AlbedoCell>& cells) {
    CellArrays a;
    for (const auto& c : cells) {
        a.mus.push_back(c.mu);
        a.phis.push_back(c.phi);
        for (int k = 0; k < BB_MAX_PARAMS; ++k) a.params.push_back(c.params[k]);
    }
    return a;
}

std::string nonfinite_where(const AlbedoRequest& req, size_t c) {
    std::ostringstream m;
    m << "the BRDF produced NaN or Inf at mu = " << req.cells[c].mu;
    return m.str();
}

// Whether N uniform hemisphere samples (mc, qmc) can see the lobe of a cell. A lobe of angular
// width a (alpha of a microfacet D, sqrt(2/(n+2)) for a Blinn or Phong exponent n) around the
// mirror direction covers a fraction of about 2 a^2 of the hemisphere: with fewer than 64
// expected hits (4 per replica) the replicas may all miss it and agree on a value near 0 (the
// trade-off study: Beckmann alpha = 1e-3 from 256 samples gives 0 +- 1e-9 against 1.0).
// Such a result is reported with an error of max(1, |E|): the method cannot tell.
bool uniform_resolves_lobe(int model, const AlbedoCell& cell, std::uint64_t samples) {
    const bb_quad_dist d = bb_model_quad_dist(model, to_bb_params(cell.params));
    const int exponent_slot = model_traits(model).exponent_slot;
    double width = 1.0;
    if (d.kind == BB_QUAD_BLINN)
        width = std::sqrt(2.0 / (d.n + 2.0));
    else if (d.kind != BB_QUAD_SAMPLER)
        width = std::min(d.ax, d.ay);
    else if (exponent_slot >= 0)
        width = std::sqrt(2.0 / (cell.params[exponent_slot] + 2.0));
    return double(samples) * std::min(1.0, 2.0 * width * width) >= 64.0;
}

AlbedoResult compute_sampled(Engine& engine, const AlbedoRequest& req) {
    check_sampling(req.samples, req.replicas);
    const std::uint64_t points = req.samples / req.replicas;
    const size_t n_cells = req.cells.size();
    const size_t n_items = n_cells * req.replicas;

    BuildRequest build = albedo_build("albedo.cl", req);
    build.random123 = req.method == Method::MonteCarlo;
    // The vector paths: importance sampling (GGX's disk path, or the model's own branch-free
    // sampler) and qmc's uniform hemisphere weights for models with a branch-free evaluation.
    const ModelTraits& traits = model_traits(req.model);
    const bool uniform = req.method == Method::QuasiMonteCarlo;
    const bool disk = !uniform && traits.samples_disk;
    build.has_vector_path = (req.method == Method::Importance && (disk || traits.samples_vector)) ||
                            (uniform && traits.evals_vector);
    build.vector_width = req.vector_width;
    const VectorChunks plan = vector_chunks(engine, build, points, req.replicas);
    const unsigned lanes = plan.lanes;
    const std::vector<PointChunk>& chunks = plan.chunks;
    check_memory(launch_bytes(n_cells, n_items, lanes > 1 ? double(chunks.front().count) * req.replicas : req.replicas,
                                lanes > 1 ? (disk ? BB_DISK_VALUES : BB_POINTS_VALUES) : 1, req.precision),
                 "integrating " + std::to_string(n_cells) + (n_cells == 1 ? " direction with " : " directions with ") + std::to_string(req.samples) +
                     " samples each");
    build.vector_path = disk ? VectorPath::Default : uniform ? VectorPath::UniformPoints : VectorPath::Points;
    if (lanes > 1 && disk) {
        // A launch whose cells are all isotropic gets the disk weight without the terms that
        // vanish then (bb_model_disk_isotropic): a program of its own, cached as any other.
        build.isotropic = true;
        for (const AlbedoCell& c : req.cells)
            build.isotropic = build.isotropic && bb_model_disk_isotropic(req.model, to_bb_params(c.params));
    }
    cl::Program& program = engine.program(build);

    const CellArrays cells = cell_arrays(req.cells);
    const std::vector<double> shifts = replica_shifts(req.replicas, req.seed);

    RealBuffers bufs(engine, req.precision);
    const FresnelBuffers fb = fresnel_buffers(bufs, req.model, req.fresnel);
    cl::Buffer b_mu = bufs.input(cells.mus), b_phi = bufs.input(cells.phis), b_p = bufs.input(cells.params),
               b_fp = fb.params, b_data = fb.model_data;
    // mc: each cell's Philox stream from its content (cell_identity), not its place in the
    // launch, so that a cell has one value whichever cells share its launch (refinement rounds,
    // MPI ranks, shards).
    std::vector<cl_uint> streams;
    for (const AlbedoCell& c : req.cells) {
        const std::uint64_t id = cell_identity(c);
        streams.push_back(cl_uint(id ^ (id >> 32)));
    }
    cl::Buffer b_stream(engine.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, streams.size() * sizeof(cl_uint),
                        streams.data());
    cl::Buffer b_mean = bufs.output(n_items);
    cl::Kernel kernel(program, lanes == 1 ? BB_ENTRY_NAME(BB_ENTRY_ALBEDO_REPLICAS)
                               : disk     ? BB_ENTRY_NAME(BB_ENTRY_ALBEDO_REPLICAS_DISK)
                                          : BB_ENTRY_NAME(BB_ENTRY_ALBEDO_REPLICAS_POINTS));
    // Each chunk's launch gives the replicas' means over its points; their weighted sum is the mean.
    const ChunkSums sums = run_chunks(engine, bufs, chunks, points, n_items, {b_mean}, [&](const PointChunk& chunk, const cl::Buffer& bad) {
        cl::Buffer b_points = bufs.input(lanes == 1 ? shifts
                                         : disk   ? disk_table(shifts, req.replicas, points, lanes, req.precision, chunk)
                                                  : point_table(shifts, req.replicas, points, lanes, req.precision, chunk));
        cl_uint a = set_args(kernel, 0, b_mu, b_phi, b_p, b_fp, b_data, b_points, cl_uint(chunk.count),
                             cl_uint(req.replicas), cl_uint(n_cells));
        if (lanes == 1) {
            const int method = req.method == Method::Importance        ? BB_METHOD_IMPORTANCE
                               : req.method == Method::QuasiMonteCarlo ? BB_METHOD_QMC
                                                                       : BB_METHOD_MC;
            a = set_args(kernel, a, cl_int(method), cl_uint(req.seed), cl_uint(req.seed >> 32), b_stream);
        }
        set_args(kernel, a, b_mean, bad);
        return run_items(engine, kernel, n_items, double(chunk.count),
                         "albedo of " + std::to_string(n_cells) + " cells, " + std::to_string(req.samples) + " samples each");
    });
    AlbedoResult result;
    result.samples_per_cell = points * req.replicas;
    result.total_samples = result.samples_per_cell * n_cells;
    result.kernel_seconds = sums.kernel_seconds;
    result.vector_width = lanes;
    result.method = method_text(req.method, req.replicas, points);
    result.values = summarize(sums.means[0], sums.bad, req.replicas, result.samples_per_cell, req.precision,
                              [&](size_t c) { return nonfinite_where(req, c); });
    for (size_t c = 0; c < result.values.size(); ++c) {
        AlbedoValue& v = result.values[c];
        v.samples = result.samples_per_cell;
        v.method = req.method;
        if (req.method != Method::Importance && !uniform_resolves_lobe(req.model, req.cells[c], result.samples_per_cell))
            v.error = std::max(v.error, std::max(1.0, std::fabs(v.value)));
    }
    return result;
}

AlbedoResult compute_quadrature(Engine& engine, const AlbedoRequest& req) {
    if (req.samples == 0) throw Error("--samples must be positive");
    const unsigned n = quadrature_order(req.samples), m = n / 2, l = std::max(1u, n / 4);
    const size_t n_cells = req.cells.size(), n_items = n_cells * BB_QUAD_SLOTS;

    BuildRequest build = albedo_build("albedo.cl", req);
    build.quadrature = true;
    // The vector path (albedo_quadrature_rows, one row of the rule per lane): the half-vector
    // rule, and the sampler's square for models whose sampler (or, for the cosine warp's rule in
    // cos(theta_i), evaluation) is branch-free (-D BB_QUAD_SAMPLER_ROWS).
    const ModelTraits& traits = model_traits(req.model);
    const bool sampler_rows = !traits.halfvector_quadrature && !traits.delta &&
                              (traits.cosine_sampler ? traits.evals_vector : traits.samples_vector);
    build.has_vector_path = traits.halfvector_quadrature || sampler_rows;
    build.vector_width = req.vector_width;
    const unsigned lanes = engine.vector_width(build);
    if (sampler_rows) build.vector_path = VectorPath::SamplerRows;
    check_memory(launch_bytes(n_cells, n_items, 2.0 * (n + m + l + 3 * lanes), 1, req.precision),
                 "integrating " + std::to_string(n_cells) + (n_cells == 1 ? " direction" : " directions") + " by quadrature");
    cl::Program& program = engine.program(build);

    std::vector<double> nodes;
    append_gauss_legendre(n, nodes, lanes);
    append_gauss_legendre(m, nodes, lanes);
    append_gauss_legendre(l, nodes, lanes);
    const CellArrays cells = cell_arrays(req.cells);
    RealBuffers bufs(engine, req.precision);
    const FresnelBuffers fb = fresnel_buffers(bufs, req.model, req.fresnel);
    cl::Buffer b_mu = bufs.input(cells.mus), b_phi = bufs.input(cells.phis), b_p = bufs.input(cells.params),
               b_fp = fb.params, b_data = fb.model_data, b_nodes = bufs.input(nodes);
    cl::Buffer b_sum = bufs.output(n_items);
    const NonFiniteCounts bad_counts(engine, n_items);

    cl::Kernel kernel(program, lanes > 1 ? BB_ENTRY_NAME(BB_ENTRY_ALBEDO_QUADRATURE_ROWS)
                                         : BB_ENTRY_NAME(BB_ENTRY_ALBEDO_QUADRATURE));
    set_args(kernel, 0, b_mu, b_phi, b_p, b_fp, b_data, b_nodes, cl_uint(n), cl_uint(m), cl_uint(l), cl_uint(n_cells), b_sum,
             bad_counts.buffer);
    const double kernel_seconds =
        run_items(engine, kernel, n_items, double(n) * n / 4.0,
                  "albedo of " + std::to_string(n_cells) + " cells by quadrature, " + std::to_string(n) + " nodes");
    const std::vector<double> sums = bufs.read(b_sum, n_items);
    const std::vector<cl_uint> bad = bad_counts.read(engine);

    AlbedoResult result;
    const std::uint64_t per_piece = std::uint64_t(n) * n + std::uint64_t(m) * m + std::uint64_t(l) * l;
    result.kernel_seconds = kernel_seconds;
    result.vector_width = lanes;
    result.method = quadrature_text(req.model, n);
    const double fp_bound = tolerance_floor(req.precision);
    for (size_t c = 0; c < n_cells; ++c) {
        double fine = 0.0, coarse = 0.0, coarsest = 0.0;
        std::uint64_t n_bad = 0;
        // Slot rule * BB_QUAD_PIECES + piece of the cell (kernel_abi.h): rules fine, coarse, coarsest.
        static_assert(BB_QUAD_RULES == 3, "the error estimate takes three rules");
        const size_t base = c * BB_QUAD_SLOTS;
        for (int q = 0; q < BB_QUAD_PIECES; ++q) {
            fine += sums[base + q];
            coarse += sums[base + BB_QUAD_PIECES + q];
            coarsest += sums[base + 2 * BB_QUAD_PIECES + q];
            n_bad += bad[base + q] + bad[base + BB_QUAD_PIECES + q] + bad[base + 2 * BB_QUAD_PIECES + q];
        }
        if (n_bad > 0)
            throw NonFiniteError(nonfinite_where(req, c) + " (" + std::to_string(n_bad) +
                                     " quadrature nodes); refusing to report a result",
                                 c, n_bad);
        AlbedoValue v;
        v.value = fine;
        v.error = quadrature_error(fine, coarse, coarsest, model_traits(req.model).kinked_quadrature) +
                  fp_bound * std::max(std::fabs(fine), 1e-3);
        // The pieces the kernel ran (bb_quad_piece_empty): an isotropic lobe's quarters cut at a kink too.
        const bb_params cell_p = to_bb_params(req.cells[c].params);
        const bb_quad_dist dist = bb_model_quad_dist(req.model, cell_p);
        const bb_real kink_cos = bb_quad_cell_kink_cos(dist, req.fresnel.kind, to_bb_params(req.fresnel.params));
        const bb_vec3 wo = bb_dir_from_mu_phi(req.cells[c].mu, req.cells[c].phi);
        v.samples = per_piece * std::uint64_t(bb_quad_piece_count(req.model, cell_p, dist, req.cells[c].phi,
                                                                  bb_quad_kink_delta(wo, kink_cos)));
        result.samples_per_cell = std::max(result.samples_per_cell, v.samples);
        result.total_samples += v.samples;
        v.method = Method::Quadrature;
        result.values.push_back(v);
    }
    return result;
}

}  // namespace

double reduce_azimuth(double phi) {
    if (!std::isfinite(phi)) throw Error("phi must be a finite angle");
    // fmod is exact in IEEE arithmetic; a negative remainder moves up by one turn, and one that
    // rounds up to a whole turn is 0. The kernel's precision sees only this reduced angle, so
    // float kernels never take cos/sin of a huge argument.
    double r = std::fmod(phi, 2.0 * M_PI);
    if (r < 0.0) r += 2.0 * M_PI;
    return r < 2.0 * M_PI ? r : 0.0;
}

double azimuth_from_degrees(double degrees) {
    if (!std::isfinite(degrees)) throw Error("phi must be a finite angle");
    double turn = std::fmod(degrees, 360.0);
    if (turn < 0.0) turn += 360.0;
    if (!(turn < 360.0)) turn = 0.0;
    return reduce_azimuth(turn * (M_PI / 180.0));
}

// The Lambert part of a Smith lobe's diffuse=KD (brdf/smith.h): per cell its kd, taken out of
// the cell's parameters (the kernels integrate the specular lobe) and added back in closed form,
// the albedo of kd/pi being kd at every direction (no error of its own).
namespace {
std::vector<double> take_diffuse(AlbedoRequest& req) {
    std::vector<double> kd(req.cells.size(), 0.0);
    if (!model_traits(req.model).diffuse_key) return kd;
    for (size_t c = 0; c < req.cells.size(); ++c) {
        ParamBlock& p = req.cells[c].params;
        if (p[BB_SMITH_SCATTERING] != BB_SCATTERING_SINGLE) continue;
        kd[c] = p[BB_SMITH_DIFFUSE];
        p[BB_SMITH_DIFFUSE] = 0.0;
    }
    return kd;
}
}  // namespace

AlbedoResult compute_albedo(Engine& engine, const AlbedoRequest& request) {
    if (auto shared = shared_albedo(engine, request)) return std::move(*shared);  // MPI ranks, shards
    if (request.cells.empty()) throw Error("no directions to integrate");
    check_method_for_model(model_traits(request.model), request.method);
    AlbedoRequest req = request;
    for (auto& c : req.cells) {
        if (!(c.mu > 0.0 && c.mu <= 1.0)) throw Error("mu must lie in (0, 1]; got " + format_number(c.mu));
        c.phi = reduce_azimuth(c.phi);
    }
    const std::vector<double> kd = take_diffuse(req);
    AlbedoResult result = req.method == Method::Quadrature ? compute_quadrature(engine, req) : compute_sampled(engine, req);
    for (size_t c = 0; c < result.values.size(); ++c) result.values[c].value += kd[c];
    // The kernels count non-finite samples; this catches what the reduction of their sums could
    // still overflow (a finite BRDF whose integral exceeds the precision's range).
    for (size_t c = 0; c < result.values.size(); ++c)
        if (!std::isfinite(result.values[c].value) || !std::isfinite(result.values[c].error))
            throw NonFiniteError(nonfinite_where(req, c) + " (the integral overflows); refusing to report a result", c, 1);
    return result;
}

}  // namespace brdfbake

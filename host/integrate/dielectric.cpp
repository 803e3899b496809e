// The rough dielectric's reflected and transmitted energy fractions (kernels/dielectric.cl):
// the half-vector quadrature of brdf/dielectric_quadrature.h and visible-normal sampling.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/dielectric_quadrature.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "engine/device_buffer.h"
#include "integrate/distributed_compute.h"
#include "integrate/launch.h"
#include "integrate/quadrature_rules.h"
#include "integrate/replicas.h"

namespace brdfbake {

namespace {

// A dielectric node or sample (R and T, the refraction, the Beta function) costs about 3.5 of the
// albedo's samples, which run_items slices launches by (progress within a long round).
constexpr double kDielectricNodeCost = 3.5;

std::string dielectric_nonfinite_where(const DielectricRequest& req, size_t c) {
    std::ostringstream m;
    m << "the rough dielectric produced NaN or Inf at mu = " << req.cells[c].mu << ", alpha = " << req.cells[c].alpha
      << ", eta = " << req.cells[c].eta;
    return m.str();
}

// The kernels' `shadowing` and `transmission_shadowing` arguments are the request's enums by value.
static_assert(int(Shadowing::Separable) == BB_SHADOWING_SEPARABLE && int(Shadowing::Correlated) == BB_SHADOWING_CORRELATED &&
              int(Shadowing::Masking) == BB_SHADOWING_MASKING);
static_assert(int(TransmissionShadowing::Beta) == BB_TRANSMISSION_SHADOWING_BETA &&
              int(TransmissionShadowing::Cycles) == BB_TRANSMISSION_SHADOWING_CYCLES);


// The rule of the dielectric's quadrature for a budget of `samples`, read as the albedo's is:
// n = sqrt(samples / 4) nodes per axis of the finer rule (quadrature_order). Up to n = 32, the
// Gauss-Kronrod rule of Boost.Math's (15, 21, 31, 41, 51 or 61 points) nearest 2n - 1 from
// below, which is about as accurate as the n-node rule's finer neighbour and whose embedded
// Gauss rule estimates its error at no extra node; beyond, three Gauss-Legendre rules n, n/2
// and n/4 (quadrature_error). compute_dielectric_to_tolerance's plan (refine.cpp) spends
// n = 11, 16 and 31 (the Kronrod rules of 21, 31 and 61 points), then 128 to 512.
struct DielectricRule {
    unsigned kronrod = 0;  // points of the Gauss-Kronrod rule; 0: the Gauss-Legendre triple
    unsigned n = 0, m = 0, l = 0;
};

DielectricRule dielectric_rule(std::uint64_t samples) {
    const double n = std::sqrt(double(samples) / 4.0);
    DielectricRule rule;
    if (n <= 32.0) {
        rule.kronrod = 15;
        for (unsigned k : {21u, 31u, 41u, 51u, 61u})
            if (k <= 2.0 * n - 1.0 + 1e-9) rule.kronrod = k;
        rule.n = rule.kronrod;
        return rule;
    }
    rule.n = quadrature_order(samples), rule.m = rule.n / 2, rule.l = rule.n / 4;
    return rule;
}

// The half-vector rule of brdf/dielectric_quadrature.h: per cell, rule and azimuth piece one
// work-item; a cell's R and T are the sums over its pieces, each with an error estimate (the
// Kronrod sum's distance to its embedded Gauss sum, or quadrature_error from the three
// Gauss-Legendre rules) plus the floating-point bound and the part of the measure the rows leave
// out beyond their slope cap (at most BB_EPS_REAL / 16 of R + T).
DielectricResult compute_dielectric_quadrature(Engine& engine, const DielectricRequest& req) {
    if (req.samples == 0) throw Error("--samples must be positive");
    const DielectricRule rule = dielectric_rule(req.samples);
    constexpr size_t kSlots = BB_QUAD_RULES * BB_DIELECTRIC_QUAD_PIECES;
    const size_t n_cells = req.cells.size(), n_items = n_cells * kSlots;

    BuildRequest build;
    build.kernel_file = "dielectric.cl";
    build.precision = req.precision;
    build.model = BB_MODEL_GGX;
    build.quadrature = true;
    // The vector path (dielectric_quadrature_rows): one row of the rule per lane.
    build.has_vector_path = true;
    build.vector_width = req.vector_width;
    const unsigned lanes = engine.vector_width(build);
    check_memory(launch_bytes(n_cells, n_items * 2, 3.0 * (rule.n + rule.m + rule.l + 3 * lanes), 1, req.precision),
                 "integrating " + std::to_string(n_cells) + " dielectric cells by quadrature");
    cl::Program& program = engine.program(build);

    std::vector<double> nodes, mus, alphas, etas;
    if (rule.kronrod) {
        append_gauss_kronrod(rule.kronrod, nodes, lanes);
    } else {
        append_gauss_legendre(rule.n, nodes, lanes);
        append_gauss_legendre(rule.m, nodes, lanes);
        append_gauss_legendre(rule.l, nodes, lanes);
    }
    for (const auto& c : req.cells) {
        mus.push_back(c.mu);
        alphas.push_back(c.alpha);
        etas.push_back(c.eta);
    }
    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(mus), b_alpha = bufs.input(alphas), b_eta = bufs.input(etas),
               b_nodes = bufs.input(nodes);
    cl::Buffer b_r = bufs.output(n_items), b_t = bufs.output(n_items);
    const NonFiniteCounts bad_counts(engine, n_items);
    cl::Kernel kernel(program, lanes > 1 ? BB_ENTRY_NAME(BB_ENTRY_DIELECTRIC_QUADRATURE_ROWS)
                                         : BB_ENTRY_NAME(BB_ENTRY_DIELECTRIC_QUADRATURE));
    set_args(kernel, 0, b_mu, b_alpha, b_eta, b_nodes, cl_uint(rule.n), cl_uint(rule.m), cl_uint(rule.l),
             cl_uint(n_cells), cl_uint(rule.kronrod ? 1 : 0), cl_int(req.shadowing),
             cl_int(req.transmission_shadowing), b_r, b_t, bad_counts.buffer);
    const std::uint64_t per_piece = rule.kronrod ? std::uint64_t(rule.n) * rule.n
                                                 : std::uint64_t(rule.n) * rule.n + std::uint64_t(rule.m) * rule.m +
                                                       std::uint64_t(rule.l) * rule.l;
    const double kernel_seconds =
        run_items(engine, kernel, n_items, kDielectricNodeCost * double(per_piece) * BB_DIELECTRIC_QUAD_SEGMENTS / BB_QUAD_RULES,
                  "rough dielectric of " + std::to_string(n_cells) + " cells by quadrature, " + std::to_string(rule.n) +
                      " nodes");
    const std::vector<double> r = bufs.read(b_r, n_items), t = bufs.read(b_t, n_items);
    const std::vector<cl_uint> bad = bad_counts.read(engine);

    DielectricResult result;
    result.kernel_seconds = kernel_seconds;
    result.vector_width = lanes;
    std::ostringstream text;
    text << (rule.kronrod ? "Gauss-Kronrod" : "Gauss-Legendre") << " product rule in half-vector space, " << rule.n
         << " x " << rule.n << " nodes per azimuth piece and row segment (up to " << BB_DIELECTRIC_QUAD_PIECES << " x "
         << BB_DIELECTRIC_QUAD_SEGMENTS << "), error from the ";
    if (rule.kronrod)
        text << "embedded " << (rule.n - 1) / 2 << "-node Gauss rule";
    else
        text << rule.m << "- and " << rule.l << "-node rules";
    result.method = text.str();
    const double fp_bound = tolerance_floor(req.precision);
    const double tail = (req.precision == Precision::Double ? 2.220446049250313e-16 : 1.1920929e-7) / 16.0;
    const std::uint64_t nodes_per_cell = std::uint64_t(BB_DIELECTRIC_QUAD_PIECES) * BB_DIELECTRIC_QUAD_SEGMENTS * per_piece;
    result.samples_per_cell = nodes_per_cell;
    for (size_t c = 0; c < n_cells; ++c) {
        double sum[2][BB_QUAD_RULES] = {};
        std::uint64_t n_bad = 0;
        for (unsigned q = 0; q < BB_QUAD_RULES; ++q)
            for (unsigned piece = 0; piece < BB_DIELECTRIC_QUAD_PIECES; ++piece) {
                const size_t slot = c * kSlots + q * BB_DIELECTRIC_QUAD_PIECES + piece;
                sum[0][q] += r[slot];
                sum[1][q] += t[slot];
                n_bad += bad[slot];
            }
        if (n_bad > 0)
            throw NonFiniteError(dielectric_nonfinite_where(req, c) + " (" + std::to_string(n_bad) +
                                     " quadrature nodes); refusing to report a result",
                                 c, n_bad);
        for (int channel = 0; channel < 2; ++channel) {
            const double* q = sum[channel];
            AlbedoValue v;
            v.value = q[0];
            v.error = (rule.kronrod ? std::fabs(q[0] - q[1]) : quadrature_error(q[0], q[1], q[2], false)) +
                      fp_bound * std::max(std::fabs(v.value), 1e-3) + tail;
            v.samples = nodes_per_cell;
            v.method = Method::Quadrature;
            (channel == 0 ? result.reflected : result.transmitted).push_back(v);
        }
    }
    return result;
}

DielectricResult compute_dielectric_sampled(Engine& engine, const DielectricRequest& req) {
    check_sampling(req.samples, req.replicas);
    const std::uint64_t points = req.samples / req.replicas;
    const size_t n_cells = req.cells.size(), n_items = n_cells * req.replicas;

    BuildRequest build;
    build.kernel_file = "dielectric.cl";
    build.precision = req.precision;
    // The vector path (dielectric_replicas_disk): W samples per step, their disk points from the
    // table shared by all cells, as the albedo kernel's.
    build.has_vector_path = true;
    build.vector_width = req.vector_width;
    const VectorChunks plan = vector_chunks(engine, build, points, req.replicas);
    const unsigned lanes = plan.lanes;
    const std::vector<PointChunk>& chunks = plan.chunks;
    check_memory(launch_bytes(n_cells, n_items * 2, lanes > 1 ? double(chunks.front().count) * req.replicas : req.replicas,
                                lanes > 1 ? BB_DISK_VALUES : 1, req.precision),
                 "integrating " + std::to_string(n_cells) + " dielectric cells with " + std::to_string(req.samples) +
                     " samples each");
    cl::Program& program = engine.program(build);

    std::vector<double> mus, alphas, etas;
    for (const auto& c : req.cells) {
        mus.push_back(c.mu);
        alphas.push_back(c.alpha);
        etas.push_back(c.eta);
    }
    RealBuffers bufs(engine, req.precision);
    const std::vector<double> shifts = replica_shifts(req.replicas, req.seed);
    cl::Buffer b_mu = bufs.input(mus), b_alpha = bufs.input(alphas), b_eta = bufs.input(etas);
    cl::Buffer b_r = bufs.output(n_items), b_t = bufs.output(n_items);
    cl::Kernel kernel(program, lanes > 1 ? BB_ENTRY_NAME(BB_ENTRY_DIELECTRIC_REPLICAS_DISK)
                                         : BB_ENTRY_NAME(BB_ENTRY_DIELECTRIC_REPLICAS));
    // Each chunk's launch gives the replicas' means over its points; their weighted sum is the mean.
    const ChunkSums sums = run_chunks(engine, bufs, chunks, points, n_items, {b_r, b_t}, [&](const PointChunk& chunk, const cl::Buffer& bad) {
        cl::Buffer b_shift =
            bufs.input(lanes > 1 ? disk_table(shifts, req.replicas, points, lanes, req.precision, chunk) : shifts);
        set_args(kernel, 0, b_mu, b_alpha, b_eta, b_shift, cl_uint(chunk.count), cl_uint(req.replicas), cl_uint(n_cells),
                 cl_int(req.shadowing), cl_int(req.transmission_shadowing), b_r, b_t, bad);
        return run_items(engine, kernel, n_items, kDielectricNodeCost * double(chunk.count),
                         "rough dielectric of " + std::to_string(n_cells) + " cells, " + std::to_string(req.samples) +
                             " samples each");
    });
    DielectricResult result;
    result.samples_per_cell = points * req.replicas;
    result.kernel_seconds = sums.kernel_seconds;
    result.method = method_text(Method::Importance, req.replicas, points);
    result.vector_width = lanes;
    auto where = [&](size_t c) { return dielectric_nonfinite_where(req, c); };
    result.reflected = summarize(sums.means[0], sums.bad, req.replicas, result.samples_per_cell, req.precision, where);
    result.transmitted = summarize(sums.means[1], sums.bad, req.replicas, result.samples_per_cell, req.precision, where);
    for (auto* channel : {&result.reflected, &result.transmitted})
        for (AlbedoValue& v : *channel) {
            v.samples = result.samples_per_cell;
            v.method = Method::Importance;
        }
    return result;
}

}  // namespace

DielectricResult compute_dielectric(Engine& engine, const DielectricRequest& req) {
    if (auto shared = shared_dielectric(engine, req)) return std::move(*shared);  // MPI ranks, shards
    if (req.cells.empty()) throw Error("no cells to integrate");
    for (const auto& c : req.cells)
        if (!(c.mu > 0.0 && c.mu <= 1.0) || !(c.alpha >= BB_ALPHA_MIN) || !(c.eta > 0.0) || !std::isfinite(c.eta))
            throw Error("dielectric cell out of range (mu in (0, 1], alpha >= 1e-4, eta > 0)");
    if (req.shadowing == Shadowing::Masking)
        throw Error("the rough dielectric has no masking-only form: its transmitted lobe needs shadowing");
    if (req.method != Method::Importance && req.method != Method::Quadrature)
        throw Error(std::string("the rough dielectric is integrated by importance sampling or quadrature, not ") +
                    method_name(req.method));
    DielectricResult result =
        req.method == Method::Quadrature ? compute_dielectric_quadrature(engine, req) : compute_dielectric_sampled(engine, req);
    for (size_t c = 0; c < result.reflected.size(); ++c)
        for (const AlbedoValue* v : {&result.reflected[c], &result.transmitted[c]})
            if (!std::isfinite(v->value) || !std::isfinite(v->error))
                throw NonFiniteError(dielectric_nonfinite_where(req, c) + " (the integral overflows); refusing to report a result",
                                     c, 1);
    return result;
}

}  // namespace brdfbake

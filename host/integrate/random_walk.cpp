// The random-walk albedo (integrate/random_walk.h): the launch of kernels/random_walk.cl and the
// replicas' summary (integrate/replicas.h).
#include "integrate/random_walk.h"

#include <sstream>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/random_walk.h"
#include "brdfbake/memory_limit.h"
#include "engine/device_buffer.h"
#include "integrate/distributed_compute.h"
#include "integrate/launch.h"
#include "integrate/replicas.h"
#include "models/key_reader.h"

namespace brdfbake {

WalkResult walk_albedo(Engine& engine, const AlbedoRequest& req) {
    check_sampling(req.samples, req.replicas);
    const std::uint64_t walks = req.samples / req.replicas;
    const size_t n_cells = req.cells.size(), n_items = n_cells * req.replicas;
    check_memory(launch_bytes(n_cells, n_items * BB_WALK_SUMS, 0.0, 1, req.precision),
                 "random walks of " + std::to_string(n_cells) + " directions");

    BuildRequest build = albedo_build("random_walk.cl", req);
    build.random123 = true;
    cl::Program& program = engine.program(build);

    std::vector<double> mus, phis, params;
    std::vector<cl_uint> streams;
    for (const AlbedoCell& c : req.cells) {
        mus.push_back(c.mu);
        phis.push_back(c.phi);
        params.insert(params.end(), c.params.begin(), c.params.end());
        // Each cell's Philox stream from its content, not its place in the launch (as mc does).
        const std::uint64_t id = cell_identity(c);
        streams.push_back(cl_uint(id ^ (id >> 32)));
    }
    const std::vector<double> fparams(req.fresnel.params.begin(), req.fresnel.params.end());
    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(mus), b_phi = bufs.input(phis), b_p = bufs.input(params), b_fp = bufs.input(fparams);
    cl::Buffer b_stream(engine.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, streams.size() * sizeof(cl_uint),
                        streams.data());
    cl::Buffer b_sums = bufs.output(n_items * BB_WALK_SUMS);
    const NonFiniteCounts bad_counts(engine, n_items);
    cl::Kernel kernel(program, BB_ENTRY_NAME(BB_ENTRY_WALK_ALBEDO));
    set_args(kernel, 0, b_mu, b_phi, b_p, b_fp, cl_uint(walks), cl_uint(req.replicas), cl_uint(n_cells),
             cl_uint(req.seed), cl_uint(req.seed >> 32), b_stream, b_sums, bad_counts.buffer);

    WalkResult result;
    result.kernel_seconds = run_items(engine, kernel, n_items, double(walks),
                                      "random walks of " + std::to_string(n_cells) + " cells, " +
                                          std::to_string(req.samples) + " walks each");
    const std::vector<double> sums = bufs.read(b_sums, n_items * BB_WALK_SUMS);
    const std::vector<cl_uint> bad = bad_counts.read(engine);
    result.walks_per_cell = walks * req.replicas;
    result.total_walks = result.walks_per_cell * n_cells;
    std::ostringstream m;
    m << "random walks on the Smith microsurface (Heitz et al. 2016), Philox4x32-10, " << req.replicas
      << " replicas x " << walks << " walks";
    result.method = m.str();

    // The five replica means of each item, and R + T, one summary each; a non-finite walk
    // refuses the cell.
    constexpr int kParts = BB_WALK_SUMS + 1;
    std::vector<std::vector<double>> parts(kParts, std::vector<double>(n_items));
    for (size_t i = 0; i < n_items; ++i) {
        for (int k = 0; k < BB_WALK_SUMS; ++k) parts[k][i] = sums[BB_WALK_SUMS * i + k];
        parts[BB_WALK_SUMS][i] = sums[BB_WALK_SUMS * i] + sums[BB_WALK_SUMS * i + 3];
    }
    const auto where = [&](size_t c) {
        return "a random walk met NaN or Inf at mu = " + format_number(req.cells[c].mu);
    };
    std::vector<std::vector<AlbedoValue>> summary;
    for (int k = 0; k < kParts; ++k)
        summary.push_back(summarize(parts[k], bad, req.replicas, result.walks_per_cell, req.precision, where));
    for (size_t c = 0; c < n_cells; ++c) {
        WalkAlbedo w{summary[0][c], summary[1][c], summary[2][c], summary[3][c], summary[4][c], summary[5][c]};
        for (AlbedoValue* v : {&w.energy, &w.single, &w.cutoff, &w.transmitted, &w.single_t, &w.total}) {
            v->samples = result.walks_per_cell;
            v->method = Method::MonteCarlo;
        }
        result.values.push_back(w);
    }
    return result;
}

}  // namespace brdfbake

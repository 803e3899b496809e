// The random-walk albedo (integrate/random_walk.h): the launch of kernels/random_walk.cl and the
// replicas' summary (integrate/replicas.h).
#include "integrate/random_walk.h"

#include <cmath>
#include <sstream>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/random_walk.h"
#include "brdfbake/memory_limit.h"
#include "engine/device_buffer.h"
#include "integrate/distributed_compute.h"
#include "integrate/launch.h"
#include "integrate/refine.h"
#include "integrate/replicas.h"
#include "integrate/sheen_volume.h"
#include "models/key_reader.h"

namespace brdfbake {

namespace {

/// What one launch of a random_walk.cl entry returns: `n_sums` replica means per item, the
/// non-finite walks per item, the kernel seconds and the walks per replica.
struct WalkLaunch {
    std::vector<double> sums;
    std::vector<cl_uint> bad;
    double kernel_seconds = 0.0;
    std::uint64_t walks = 0;
};

/// The launch both entries share: `units` cells or pairs of `replicas` work-items each, `walks`
/// = samples / replicas per item; the kernel's arguments are `inputs` (one real array each, in
/// order), the Fresnel parameters, the walk counts, the Philox key, each unit's stream, the sums
/// and the non-finite counts. `what` names the units for the memory check, `progress` for the
/// progress line (the walks per unit follow it).
WalkLaunch launch_walks(Engine& engine, BuildRequest build, const char* entry, size_t units, unsigned replicas,
                        std::uint64_t samples, std::uint64_t seed, int n_sums, const FresnelConfig& fresnel,
                        const std::vector<const std::vector<double>*>& inputs, const std::vector<cl_uint>& streams,
                        const std::string& what, const std::string& progress) {
    check_sampling(samples, replicas);
    const std::uint64_t walks = samples / replicas;
    const size_t n_items = units * replicas;
    check_memory(launch_bytes(units, n_items * n_sums, 0.0, 1, build.precision), what);
    build.random123 = true;
    cl::Program& program = engine.program(build);
    RealBuffers bufs(engine, build.precision);
    cl::Kernel kernel(program, entry);
    std::vector<cl::Buffer> in;  // alive until the launch is done
    for (const std::vector<double>* v : inputs) in.push_back(bufs.input(*v));
    const std::vector<double> fparams(fresnel.params.begin(), fresnel.params.end());
    in.push_back(bufs.input(fparams));
    for (size_t k = 0; k < in.size(); ++k) kernel.setArg(cl_uint(k), in[k]);
    cl::Buffer b_stream(engine.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, streams.size() * sizeof(cl_uint),
                        const_cast<cl_uint*>(streams.data()));
    cl::Buffer b_sums = bufs.output(n_items * n_sums);
    const NonFiniteCounts bad_counts(engine, n_items);
    set_args(kernel, cl_uint(in.size()), cl_uint(walks), cl_uint(replicas), cl_uint(units), cl_uint(seed),
             cl_uint(seed >> 32), b_stream, b_sums, bad_counts.buffer);
    WalkLaunch out;
    out.walks = walks;
    out.kernel_seconds =
        run_items(engine, kernel, n_items, double(walks), progress + ", " + std::to_string(samples) + " walks each");
    out.sums = bufs.read(b_sums, n_items * n_sums);
    out.bad = bad_counts.read(engine);
    return out;
}

}  // namespace

WalkResult walk_albedo(Engine& engine, const AlbedoRequest& req) {
    if (model_traits(req.model).layer_walk) return sheen_layer_walk_albedo(engine, req);  // a layer's walk
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
    const size_t n_cells = req.cells.size(), n_items = n_cells * req.replicas;
    const WalkLaunch l = launch_walks(engine, albedo_build("random_walk.cl", req), BB_ENTRY_NAME(BB_ENTRY_WALK_ALBEDO),
                                      n_cells, req.replicas, req.samples, req.seed, BB_WALK_SUMS, req.fresnel,
                                      {&mus, &phis, &params}, streams,
                                      "random walks of " + std::to_string(n_cells) + " directions",
                                      "random walks of " + std::to_string(n_cells) + " cells");
    const std::vector<double>& sums = l.sums;
    WalkResult result;
    result.kernel_seconds = l.kernel_seconds;
    result.walks_per_cell = l.walks * req.replicas;
    result.total_walks = result.walks_per_cell * n_cells;
    std::ostringstream m;
    m << "random walks on the Smith microsurface (Heitz et al. 2016), Philox4x32-10, " << req.replicas
      << " replicas x " << l.walks << " walks";
    result.method = m.str();

    // The five replica means of each item, and R + T, one summary each; a non-finite walk
    // refuses the cell.
    constexpr int kParts = BB_WALK_SUMS + 1;
    std::vector<double> parts;
    for (size_t i = 0; i < n_items; ++i) {
        parts.insert(parts.end(), sums.begin() + BB_WALK_SUMS * i, sums.begin() + BB_WALK_SUMS * (i + 1));
        parts.push_back(sums[BB_WALK_SUMS * i] + sums[BB_WALK_SUMS * i + 3]);
    }
    const auto where = [&](size_t c) {
        return "a random walk met NaN or Inf at mu = " + format_number(req.cells[c].mu);
    };
    const auto s = summarize_columns(parts, kParts, l.bad, req.replicas, result.walks_per_cell, req.precision, where);
    for (size_t c = 0; c < n_cells; ++c) result.values.push_back({s[0][c], s[1][c], s[2][c], s[3][c], s[4][c], s[5][c]});
    return result;
}

namespace {

/// A pair's Philox stream from its content (both directions and the parameters, in that order:
/// f(a, b) and f(b, a) walk on different streams), never its place in the launch.
cl_uint pair_stream(const WalkEvalPair& p) {
    const auto id = [&](const Vec3& w) { return cell_identity(AlbedoCell{w[2], std::atan2(w[1], w[0]), p.params}); };
    const std::uint64_t h = id(p.wo) * 0x9e3779b97f4a7c15ull + id(p.wi);
    return cl_uint(h ^ (h >> 32));
}

}  // namespace

WalkEvalResult walk_eval(Engine& engine, const WalkEvalRequest& req) {
    BuildRequest build;
    build.kernel_file = "random_walk.cl";
    build.precision = req.precision;
    build.model = req.model;
    build.fresnel = req.fresnel.kind;
    std::vector<double> dirs, params;
    std::vector<cl_uint> streams;
    for (const WalkEvalPair& p : req.pairs) {
        dirs.insert(dirs.end(), p.wo.begin(), p.wo.end());
        dirs.insert(dirs.end(), p.wi.begin(), p.wi.end());
        params.insert(params.end(), p.params.begin(), p.params.end());
        streams.push_back(pair_stream(p));
    }
    const size_t n_pairs = req.pairs.size();
    const WalkLaunch l = launch_walks(engine, build, BB_ENTRY_NAME(BB_ENTRY_WALK_EVAL), n_pairs, req.replicas,
                                      req.samples, req.seed, BB_WALK_EVAL_SUMS, req.fresnel, {&dirs, &params}, streams,
                                      "walk evaluations of " + std::to_string(n_pairs) + " direction pairs",
                                      "walk evaluations of " + std::to_string(n_pairs) + " direction pairs");
    WalkEvalResult result;
    result.kernel_seconds = l.kernel_seconds;
    result.walks_per_pair = l.walks * req.replicas;
    std::ostringstream m;
    m << "next-event estimation on random walks on the Smith microsurface (Heitz et al. 2016), Philox4x32-10, "
      << req.replicas << " replicas x " << l.walks << " walks";
    result.method = m.str();
    const auto where = [&](size_t c) {
        const WalkEvalPair& p = req.pairs[c];
        return "a walk evaluation met NaN or Inf at wo.z = " + format_number(p.wo[2]) +
               ", wi.z = " + format_number(p.wi[2]);
    };
    const auto s = summarize_columns(l.sums, BB_WALK_EVAL_SUMS, l.bad, req.replicas, result.walks_per_pair,
                                     req.precision, where);
    // The walks estimate f(wo, wi) |wi.z| (the dielectric's transmitted f_t for wi below): f is that
    // over |wi.z| (0 at the horizon).
    for (size_t c = 0; c < n_pairs; ++c) {
        const double z = std::fabs(req.pairs[c].wi[2]);
        AlbedoValue f = s[0][c], single = s[1][c];
        for (AlbedoValue* v : {&f, &single}) {
            v->value = z > 0.0 ? v->value / z : 0.0;
            v->error = z > 0.0 ? v->error / z : 0.0;
        }
        result.f.push_back(f);
        result.single.push_back(single);
    }
    return result;
}

WalkResult walk_albedo_at(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tolerance, double share) {
    if (tolerance.tolerance <= 0.0) return walk_albedo(engine, req);
    ToleranceRequest t = tolerance;
    t.tolerance *= share;
    try {
        return walk_albedo_to_tolerance(engine, req, t);
    } catch (const ToleranceNotMet& e) {
        throw e.restated(tolerance.tolerance, "");
    }
}

AlbedoResult walk_albedo_result(Engine& engine, const AlbedoRequest& req, const ToleranceRequest& tolerance,
                                double share) {
    const WalkResult w = walk_albedo_at(engine, req, tolerance, share);
    AlbedoResult out;
    out.method = w.method;
    out.samples_per_cell = w.walks_per_cell;
    out.kernel_seconds = w.kernel_seconds;
    out.total_samples = w.total_walks;
    out.rounds = w.rounds;
    out.tolerance = tolerance.tolerance > 0.0 ? tolerance.tolerance * share : 0.0;
    for (const WalkAlbedo& v : w.values) {
        AlbedoValue e = v.energy;
        e.error += v.cutoff.value + v.cutoff.error;
        out.values.push_back(e);
    }
    return out;
}

}  // namespace brdfbake

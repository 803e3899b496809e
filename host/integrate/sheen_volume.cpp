// The volumetric sheen walks (integrate/sheen_volume.h): the launch of kernels/sheen_volume.cl and
// the replicas' summary (integrate/replicas.h).
#include "integrate/sheen_volume.h"

#include <cmath>
#include <sstream>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/sheen_volume.h"
#include "brdfbake/memory_limit.h"
#include "engine/device_buffer.h"
#include "engine/hash.h"
#include "integrate/launch.h"
#include "integrate/replicas.h"
#include "models/key_reader.h"

namespace brdfbake {

int SheenLobeBins::theta() { return BB_SHEEN_LOBE_THETA; }
int SheenLobeBins::phi() { return BB_SHEEN_LOBE_PHI; }
double SheenLobeBins::solid_angle(int row) {
    const double dt = 0.5 * M_PI / theta();
    return (std::cos(row * dt) - std::cos((row + 1) * dt)) * M_PI / phi();
}

double sheen_single_density(double mu, double alpha, double x, double y, double z) {
    if (z <= 0.0) return 0.0;
    const double s = bb_sheen_volume_sigma(alpha);
    const bb_vec3 wo = bb_v3(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu), w = bb_v3(x, y, z);
    const bb_vec3 h = bb_normalize(bb_add(wo, w));
    const double q = h.x * h.x + h.y * h.y + h.z * h.z / (s * s);
    const double d = 1.0 / (M_PI * s * q * q);  // SGGX D(h) [HDCD15 eq. 8]
    const double ko = bb_sggx_fiber_area(wo, s) / mu, k = bb_sggx_fiber_area(w, s) / z;
    return d / (4.0 * bb_sggx_fiber_area(wo, s)) * ko * -std::expm1(-(ko + k)) / (ko + k);
}

namespace {

// A cell's Philox stream from its content (FNV-1a over its numbers), never its place in a launch.
cl_uint cell_stream(const SheenVolumeCell& c) {
    const std::uint64_t h = Fnv1a().add(c.mu).add(c.alpha).add(c.bounces).h;
    return cl_uint(h ^ (h >> 32));
}

// Per cell and bin, the replicas' mean density and 3 standard errors.
void summarize_lobe(const std::vector<cl_uint>& hist, size_t n_cells, unsigned replicas, std::uint64_t walks,
                    std::vector<SheenVolumeValue>& values) {
    const int nb = SheenLobeBins::theta() * SheenLobeBins::phi();
    for (size_t c = 0; c < n_cells; ++c) {
        SheenVolumeValue& v = values[c];
        v.lobe.assign(nb, 0.0);
        v.lobe_error.assign(nb, 0.0);
        for (int b = 0; b < nb; ++b) {
            const double scale = 1.0 / (double(walks) * 2.0 * SheenLobeBins::solid_angle(b / SheenLobeBins::phi()));
            double s = 0, s2 = 0;
            for (unsigned r = 0; r < replicas; ++r) {
                const double x = hist[(c * replicas + r) * nb + b] * scale;
                s += x;
                s2 += x * x;
            }
            const double mean = s / replicas;
            const double var = replicas > 1 ? std::max(0.0, (s2 - replicas * mean * mean) / (replicas - 1)) : 0.0;
            v.lobe[b] = mean;
            v.lobe_error[b] = 3.0 * std::sqrt(var / replicas);
        }
    }
}

}  // namespace

SheenVolumeResult sheen_volume_walks(Engine& engine, const SheenVolumeRequest& req) {
    check_sampling(req.walks, req.replicas);
    const std::uint64_t walks = req.walks / req.replicas;
    const size_t n_cells = req.cells.size(), n_items = n_cells * req.replicas;
    const unsigned n_bins = req.lobe ? unsigned(BB_SHEEN_LOBE_THETA * BB_SHEEN_LOBE_PHI) : 0u;
    check_memory(launch_bytes(n_cells, n_items * (BB_SHEEN_SUMS + n_bins), 0.0, 1, req.precision),
                 "sheen layer walks of " + std::to_string(n_cells) + " directions");

    BuildRequest build;
    build.kernel_file = "sheen_volume.cl";
    build.precision = req.precision;
    build.random123 = true;
    cl::Program& program = engine.program(build);

    std::vector<double> mus, alphas;
    std::vector<cl_int> bounces;
    std::vector<cl_uint> streams;
    for (const SheenVolumeCell& c : req.cells) {
        mus.push_back(c.mu);
        alphas.push_back(c.alpha);
        bounces.push_back(c.bounces);
        streams.push_back(cell_stream(c));
    }
    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(mus), b_alpha = bufs.input(alphas);
    cl::Buffer b_bounces(engine.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bounces.size() * sizeof(cl_int),
                         bounces.data());
    cl::Buffer b_stream(engine.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, streams.size() * sizeof(cl_uint),
                        streams.data());
    cl::Buffer b_sums = bufs.output(n_items * BB_SHEEN_SUMS);
    cl::Buffer b_hist(engine.context(), CL_MEM_WRITE_ONLY, std::max<size_t>(1, n_items * n_bins) * sizeof(cl_uint));
    const NonFiniteCounts bad_counts(engine, n_items);
    cl::Kernel kernel(program, BB_ENTRY_NAME(BB_ENTRY_SHEEN_VOLUME));
    set_args(kernel, 0, b_mu, b_alpha, b_bounces, cl_uint(walks), cl_uint(req.replicas), cl_uint(n_cells),
             cl_uint(req.seed), cl_uint(req.seed >> 32), b_stream, cl_uint(n_bins), b_sums, b_hist, bad_counts.buffer);

    SheenVolumeResult result;
    result.kernel_seconds = run_items(engine, kernel, n_items, double(walks),
                                      "sheen layer walks of " + std::to_string(n_cells) + " cells, " +
                                          std::to_string(req.walks) + " walks each");
    const std::vector<double> sums = bufs.read(b_sums, n_items * BB_SHEEN_SUMS);
    const std::vector<cl_uint> bad = bad_counts.read(engine);
    result.walks_per_cell = walks * req.replicas;
    std::ostringstream m;
    m << "random walks through the fiber SGGX layer (Zeltner et al. 2022), Philox4x32-10, " << req.replicas
      << " replicas x " << walks << " walks";
    result.method = m.str();

    const auto where = [&](size_t c) {
        return "a sheen layer walk met NaN or Inf at mu = " + format_number(req.cells[c].mu) +
               ", roughness = " + format_number(req.cells[c].alpha);
    };
    const std::vector<std::vector<AlbedoValue>> summary =
        summarize_columns(sums, BB_SHEEN_SUMS, bad, req.replicas, result.walks_per_cell, req.precision, where);
    for (size_t c = 0; c < n_cells; ++c) {
        SheenVolumeValue v;
        AlbedoValue* slots[BB_SHEEN_SUMS] = {&v.reflectance, &v.single, &v.transmittance, &v.direct, &v.cutoff};
        for (int k = 0; k < BB_SHEEN_SUMS; ++k) *slots[k] = summary[k][c];
        result.values.push_back(v);
    }
    if (n_bins > 0) {
        std::vector<cl_uint> hist(n_items * n_bins);
        engine.queue().enqueueReadBuffer(b_hist, CL_TRUE, 0, hist.size() * sizeof(cl_uint), hist.data());
        summarize_lobe(hist, n_cells, req.replicas, walks, result.values);
    }
    return result;
}

}  // namespace brdfbake

// The volumetric sheen walks (integrate/sheen_volume.h): the launch of kernels/sheen_volume.cl and
// the replicas' summary (integrate/replicas.h).
#include "integrate/sheen_volume.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/sheen_volume.h"
#include "brdfbake/brdf/sheen_volume_model.h"
#include "brdfbake/spec.h"
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
void summarize_lobe(const std::vector<double>& hist, size_t n_cells, unsigned replicas, std::uint64_t walks,
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
    check_memory(launch_bytes(n_cells, n_items * (BB_SHEEN_SUMS + n_bins + 1), 0.0, 1, req.precision),
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
    cl::Buffer b_hist = bufs.output(std::max<size_t>(1, n_items * n_bins));
    cl::Buffer b_flights = bufs.output(n_items);
    const NonFiniteCounts bad_counts(engine, n_items);
    cl::Kernel kernel(program, BB_ENTRY_NAME(BB_ENTRY_SHEEN_VOLUME));
    set_args(kernel, 0, b_mu, b_alpha, b_bounces, cl_uint(walks), cl_uint(req.replicas), cl_uint(n_cells),
             cl_uint(req.seed), cl_uint(req.seed >> 32), b_stream, cl_uint(n_bins), cl_uint(req.next_flight), b_sums, b_hist, b_flights, bad_counts.buffer);

    SheenVolumeResult result;
    result.kernel_seconds = run_items(engine, kernel, n_items, double(walks),
                                      "sheen layer walks of " + std::to_string(n_cells) + " cells, " +
                                          std::to_string(req.walks) + " walks each");
    const std::vector<double> sums = bufs.read(b_sums, n_items * BB_SHEEN_SUMS);
    const std::vector<cl_uint> bad = bad_counts.read(engine);
    const std::vector<double> flights = bufs.read(b_flights, n_items);
    result.walks_per_cell = walks * req.replicas;
    std::ostringstream m;
    m << "random walks through the fiber SGGX layer (Zeltner et al. 2022), Philox4x32-10, " << req.replicas
      << " replicas x " << walks << " walks";
    if (n_bins > 0)
        m << "; the higher orders' lobe by " << (req.next_flight ? "next-flight tallies" : "counts of the exits");
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
        for (unsigned r = 0; r < req.replicas; ++r) v.flights += flights[c * req.replicas + r] / req.replicas;
        result.values.push_back(v);
    }
    if (n_bins > 0) {
        summarize_lobe(bufs.read(b_hist, n_items * n_bins), n_cells, req.replicas, walks, result.values);
    }
    return result;
}

// ---- the layer as a model spec -------------------------------------------------------------------

namespace {

/// The walk's cell of a model's parameters at mu: the kernel takes the roughness r = sqrt(alpha).
SheenVolumeCell layer_cell(const ParamBlock& p, double mu) {
    return {mu, std::sqrt(p[BB_SHEEN_VOLUME_MODEL_ALPHA]), int(p[BB_SHEEN_VOLUME_MODEL_BOUNCES])};
}

}  // namespace

WalkResult sheen_layer_walk_albedo(Engine& engine, const AlbedoRequest& req) {
    SheenVolumeRequest w;
    for (const AlbedoCell& c : req.cells) w.cells.push_back(layer_cell(c.params, c.mu));
    w.walks = req.samples;
    w.replicas = req.replicas;
    w.seed = req.seed;
    w.precision = req.precision;
    const SheenVolumeResult r = sheen_volume_walks(engine, w);
    WalkResult out;
    out.kernel_seconds = r.kernel_seconds;
    out.walks_per_cell = r.walks_per_cell;
    out.total_walks = r.walks_per_cell * req.cells.size();
    out.method = r.method;
    for (const SheenVolumeValue& v : r.values) {
        // R + T = 1 - cutoff on every replica (albedo 1: a walk ends in exactly one of the three)
        const AlbedoValue total{1.0 - v.cutoff.value, v.cutoff.error, v.cutoff.samples, v.cutoff.method};
        out.values.push_back({v.reflectance, v.single, v.cutoff, v.transmittance, v.direct, total});
    }
    return out;
}

namespace {

/// A bin's integral of cos theta over its solid angle (one side of phi = 0).
double bin_cos_integral(int row) {
    const double dt = 0.5 * M_PI / SheenLobeBins::theta();
    const double s0 = std::sin(row * dt), s1 = std::sin((row + 1) * dt);
    return 0.5 * (s1 * s1 - s0 * s0) * M_PI / SheenLobeBins::phi();
}

}  // namespace

std::vector<double> sheen_layer_lobe(Engine& engine, const ModelConfig& model, Precision precision,
                                     const std::vector<Vec3>& wos, const std::vector<Vec3>& wis, std::uint64_t walks,
                                     std::vector<double>* error) {
    // one walk cell per distinct incident cosine (the layer is isotropic about the normal)
    std::map<double, size_t> cell_of;
    SheenVolumeRequest req;
    req.walks = walks;
    req.precision = precision;
    req.lobe = true;
    for (const Vec3& wi : wis)
        if (wi[2] > 0.0 && cell_of.emplace(wi[2], req.cells.size()).second)
            req.cells.push_back(layer_cell(model.params, std::min(1.0, wi[2])));
    const SheenVolumeResult r = req.cells.empty() ? SheenVolumeResult{} : sheen_volume_walks(engine, req);
    std::vector<double> f;
    const double alpha = model.params[BB_SHEEN_VOLUME_MODEL_ALPHA];
    for (size_t k = 0; k < wos.size(); ++k) {
        const Vec3 &wi = wis[k], &wo = wos[k];
        if (!(wi[2] > 0.0 && wo[2] > 0.0)) {
            f.push_back(0.0);
            if (error) error->push_back(0.0);
            continue;
        }
        const SheenVolumeValue& v = r.values[cell_of.at(wi[2])];
        // wo in the walk's frame: the incident azimuth at phi = 0
        const double pi_ = std::atan2(wi[1], wi[0]), po = std::atan2(wo[1], wo[0]);
        const double c = std::cos(po - pi_), s = std::sin(po - pi_), rho = std::hypot(wo[0], wo[1]);
        const double theta = std::acos(std::min(1.0, wo[2])), dphi = std::fabs(std::atan2(s, c));
        const int row = std::min(int(theta / (0.5 * M_PI) * SheenLobeBins::theta()), SheenLobeBins::theta() - 1);
        const int col = std::min(int(dphi / M_PI * SheenLobeBins::phi()), SheenLobeBins::phi() - 1);
        const size_t b = size_t(row * SheenLobeBins::phi() + col);
        const double to_f = SheenLobeBins::solid_angle(row) / bin_cos_integral(row);
        f.push_back(v.lobe[b] * to_f + sheen_single_density(wi[2], std::sqrt(alpha), rho * c, rho * s, wo[2]) / wo[2]);
        if (error) error->push_back(v.lobe_error[b] * to_f);
    }
    return f;
}

namespace {

constexpr int kBands = 4, kPhiRanges = 4, kGauss = 3;
const double kGaussX[kGauss] = {-0.7745966692414834, 0.0, 0.7745966692414834};  // 3-point Gauss-Legendre
const double kGaussW[kGauss] = {5.0 / 9, 8.0 / 9, 5.0 / 9};

/// The mu interval of theta band a (its SheenLobeBins rows), and its Gauss node g.
std::pair<double, double> band_mu(int a) {
    const double dt = SheenLobeBins::theta() / kBands * 0.5 * M_PI / SheenLobeBins::theta();
    return {std::cos((a + 1) * dt), std::cos(a * dt)};
}
double band_node(int a, int g) {
    const auto [lo, hi] = band_mu(a);
    return 0.5 * (hi + lo) + 0.5 * (hi - lo) * kGaussX[g];
}

/// Per theta band A (rows grouped by kBands) and exit region B = (band, |phi| range): the flux
/// Q(A -> B) up to a common factor, and its error (3 standard errors, bins and nodes in quadrature).
struct BandFlux {
    std::vector<double> q, e;  // [a][b][k] at (a * kBands + b) * kPhiRanges + k
};

BandFlux band_fluxes(const SheenVolumeResult& r) {
    const int rows = SheenLobeBins::theta() / kBands, cols = SheenLobeBins::phi() / kPhiRanges;
    BandFlux out;
    out.q.assign(kBands * kBands * kPhiRanges, 0.0);
    out.e = out.q;
    for (int a = 0; a < kBands; ++a) {
        const auto [mu_lo, mu_hi] = band_mu(a);
        for (int g = 0; g < kGauss; ++g) {
            const SheenVolumeValue& v = r.values[size_t(a * kGauss + g)];
            const double weight = 0.5 * (mu_hi - mu_lo) * kGaussW[g] * band_node(a, g);  // integral of mu dmu
            for (int row = 0; row < SheenLobeBins::theta(); ++row)
                for (int col = 0; col < SheenLobeBins::phi(); ++col) {
                    const size_t bin = size_t(row * SheenLobeBins::phi() + col);
                    const double p = 2.0 * SheenLobeBins::solid_angle(row);  // density -> probability
                    const size_t i = size_t((a * kBands + row / rows) * kPhiRanges + col / cols);
                    out.q[i] += weight * p * v.lobe[bin];
                    out.e[i] += std::pow(weight * p * v.lobe_error[bin], 2);
                }
        }
    }
    for (double& e : out.e) e = std::sqrt(e);
    return out;
}

}  // namespace

void scan_layer_reciprocity(Engine& engine, const ModelConfig& model, const CheckOptions& o, CheckReport& r) {
    SheenVolumeRequest req;
    req.walks = std::max<std::uint64_t>(o.samples * 4, 1u << 16);
    req.precision = o.precision;
    req.lobe = true;
    const int rows = SheenLobeBins::theta() / kBands;
    for (int a = 0; a < kBands; ++a)
        for (int g = 0; g < kGauss; ++g) req.cells.push_back(layer_cell(model.params, band_node(a, g)));
    r.reciprocity_noise = true;
    r.reciprocity_of =
        "|Q(A->B) - Q(B->A)| (band fluxes of the orders >= 2, the first order reciprocal in closed form)";
    try {
        const BandFlux q = band_fluxes(sheen_volume_walks(engine, req));
        r.min_value = *std::min_element(q.q.begin(), q.q.end());
        bool first = true;
        for (int a = 0; a < kBands; ++a)
            for (int b = a + 1; b < kBands; ++b)
                for (int k = 0; k < kPhiRanges; ++k) {
                    const size_t ab = size_t((a * kBands + b) * kPhiRanges + k);
                    const size_t ba = size_t((b * kBands + a) * kPhiRanges + k);
                    const double d = std::fabs(q.q[ab] - q.q[ba]), noise = std::hypot(q.e[ab], q.e[ba]) / 3.0;
                    const double sigmas = noise > 0.0 ? d / noise : (d > 0.0 ? HUGE_VAL : 0.0);
                    ++r.pairs;
                    if (first || sigmas > r.reciprocity_sigmas) {
                        first = false;
                        r.reciprocity_sigmas = sigmas;
                        r.max_rel = d / std::max({q.q[ab], q.q[ba], 1e-300});
                        r.max_rel_theta_i = (a + 0.5) * rows * 0.5 * M_PI / SheenLobeBins::theta();
                        r.max_rel_theta_o = (b + 0.5) * rows * 0.5 * M_PI / SheenLobeBins::theta();
                        r.max_rel_dphi = (k + 0.5) * M_PI / kPhiRanges;
                    }
                    const double allowed =
                        kReciprocitySigmas * noise + o.reciprocity_tolerance * std::max(q.q[ab], q.q[ba]);
                    r.reciprocity_violation = r.reciprocity_violation || d > allowed;
                }
    } catch (const NonFiniteError& e) {
        r.scan_nonfinite = r.nonfinite = e.count;
    }
}

}  // namespace brdfbake

#include "brdfbake/albedo.h"

#include <Random123/philox.h>
#include <Random123/uniform.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/legendre.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "brdfbake/brdf/dielectric_quadrature.h"
#include "brdfbake/brdf/integrands.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/brdf/sampling.h"
#include "brdfbake/cancel.h"
#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "brdfbake/progress.h"
#include "engine/device_buffer.h"
#include "integrate/distributed_compute.h"
#include "models/key_reader.h"
#include "models/params.h"

namespace brdfbake {

const char* method_name(Method m) {
    switch (m) {
    case Method::Importance:
        return "importance";
    case Method::QuasiMonteCarlo:
        return "qmc";
    case Method::MonteCarlo:
        return "mc";
    case Method::Quadrature:
        return "quadrature";
    }
    return "?";
}

Method parse_method(const std::string& name) {
    for (Method m : {Method::Importance, Method::QuasiMonteCarlo, Method::MonteCarlo, Method::Quadrature})
        if (name == method_name(m)) return m;
    throw Error("unknown method '" + name + "'; methods: auto, importance, qmc, mc, quadrature");
}

MethodChoice choose_method(const std::string& method, double samples, double tolerance, double max_samples) {
    if (!(samples >= 1.0) || samples > 1.8e19) throw Error("--samples must be a positive number");
    MethodChoice c;
    c.samples = std::uint64_t(samples);
    const bool is_auto = method == "auto";
    c.method = is_auto ? Method::Importance : parse_method(method);
    if (tolerance != 0.0) {
        if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw Error("--tolerance must be a positive number");
        if (!(max_samples >= 1.0) || max_samples > 1.8e19) throw Error("--max-samples must be positive");
        c.tolerance.tolerance = tolerance;
        c.tolerance.auto_method = is_auto;
        c.tolerance.max_samples = std::uint64_t(max_samples);
    }
    return c;
}

double tolerance_floor(Precision precision) {
    return 8.0 * (precision == Precision::Double ? 2.220446049250313e-16 : 1.1920929e-7);
}

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

std::string method_text(Method method, unsigned replicas, std::uint64_t points) {
    std::ostringstream m;
    switch (method) {
    case Method::Importance:
        m << "importance sampling, randomised Hammersley";
        break;
    case Method::QuasiMonteCarlo:
        m << "uniform hemisphere sampling, randomised Hammersley";
        break;
    default:
        m << "uniform hemisphere sampling, Philox4x32-10";
        break;
    }
    m << " (" << replicas << " replicas x " << points << " points)";
    return m.str();
}

std::string quadrature_text(int model, unsigned n) {
    std::ostringstream m;
    m << "Gauss-Legendre product rule in "
      << (model_traits(model).halfvector_quadrature ? "half-vector space" : "the sampler's unit square")
      << ", " << n << " x " << n << " nodes per azimuth piece (2 to 8 pieces), error from the " << n / 2
      << "- and " << n / 4 << "-node rules";
    return m.str();
}

// Mean and error estimate of each cell from its replica means. The error is 3 standard errors of
// the replicas, plus an unseen-mass term 3 |E| / N for the N samples of the cell, plus a
// floating-point bound: the per-sample weight carries a few ulps of rounding error that
// averaging does not remove (compensated summation keeps the sums exact to ~1 ulp).
// The unseen-mass term is the rule of three: a part of the sample space of probability below
// 3/N goes unseen by all N points with probability 5% or more, and the replicas then agree
// without knowing of it; with an importance sampler the weight there is of the order of E.
// Without it the replicas claim too much in two measured ways (benchmarks/results/tradeoff-*):
// GGX alpha = 0.01 at mu = 1 from 4096 samples misses the rare grazing reflections (1e-4 of
// E) and its 16 replicas agree to 6e-8; Torrance-Sparrow at mu = 1e-4, whose weight is 2 on
// half of the square and 0 on the other, is split exactly in half by every Hammersley replica.
// Throws Error if any sample of a cell was non-finite (`where(cell)` names the cell).
template <typename Where>
std::vector<AlbedoValue> summarize(const std::vector<double>& means, const std::vector<cl_uint>& bad,
                                   unsigned replicas, std::uint64_t samples_per_cell, Precision precision,
                                   Where where) {
    const double fp_bound = tolerance_floor(precision);
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
        AlbedoValue v;
        v.value = mean;
        v.error = 3.0 * std_error + 3.0 * std::fabs(mean) / double(samples_per_cell) +
                  fp_bound * std::max(std::fabs(mean), 1e-3);
        out.push_back(v);
    }
    return out;
}

void check_sampling(std::uint64_t samples, unsigned replicas) {
    if (replicas < 2) throw Error("at least 2 replicas are needed for an error estimate");
    if (samples < replicas) throw Error("--samples must be at least " + std::to_string(replicas));
    if (samples / replicas > 0xffffffffu) throw Error("--samples is too large (at most 2^32 per replica)");
}

/// Memory a sampling launch takes, for check_memory before anything is allocated: the cell
/// arrays (mu, phi and the parameter block, in double on the host and again in the kernel's
/// precision for the upload and on the device), the shared point table (per point, `table_values`
/// numbers in double, converted and on the device) and the per-item outputs (value, square,
/// non-finite count; on the device and read back).
double sampling_bytes(size_t n_cells, size_t n_items, double table_points, unsigned table_values, Precision p) {
    const double real = p == Precision::Double ? 8.0 : 4.0;
    const double per_number = 8.0 + 2.0 * real;
    return double(n_cells) * (2 + BB_MAX_PARAMS) * per_number + table_points * table_values * per_number +
           double(n_items) * (2.0 * real + 4.0) * 2.0;
}

constexpr size_t kLocalSize = 8;

/// Sets the kernel's arguments from index `first` on, in order; returns the index after them.
template <typename... Args>
cl_uint set_args(cl::Kernel& kernel, cl_uint first, const Args&... args) {
    (kernel.setArg(first++, args), ...);
    return first;
}

/// Runs an integration kernel over n_items work-items of `points_per_item` samples each and
/// returns the kernel time in seconds. An explicit small work-group: the default could give PoCL
/// two groups for two cores, or one, whatever the table size (issue 9). A long launch (more than
/// 2^28 samples) runs in up to 64 slices of the index range (the work-items keep their global ids,
/// so the results are the same), reporting progress and honouring a cancel request between
/// slices; a short one is one launch.
double run_items(Engine& engine, cl::Kernel& kernel, size_t n_items, double points_per_item, const std::string& what) {
    throw_if_cancelled();
    const size_t groups = (n_items + kLocalSize - 1) / kLocalSize;
    const double work = double(n_items) * points_per_item;
    const size_t slices = std::min<size_t>({groups, 64, size_t(std::max(1.0, work / double(1 << 26)))});
    const size_t per_slice = slices <= 1 ? groups : (groups + slices - 1) / slices;
    double seconds = 0.0;
    if (slices > 1) report_progress(what, 0, n_items);
    for (size_t first = 0; first < groups; first += per_slice) {
        const size_t count = std::min(per_slice, groups - first);
        cl::Event done;
        engine.queue().enqueueNDRangeKernel(kernel, cl::NDRange(first * kLocalSize), cl::NDRange(count * kLocalSize),
                                            cl::NDRange(kLocalSize), nullptr, &done);
        done.wait();
        seconds += event_seconds(done);
        if (slices <= 1) break;
        report_progress(what, std::min<std::uint64_t>(std::uint64_t(first + count) * kLocalSize, n_items), n_items);
        if (first + count < groups) throw_if_cancelled();
    }
    return seconds;
}

/// The per-item counts of non-finite samples, the last output of every integration kernel.
struct NonFiniteCounts {
    NonFiniteCounts(Engine& engine, size_t n_items)
        : buffer(engine.context(), CL_MEM_WRITE_ONLY, n_items * sizeof(cl_uint)), size(n_items) {}
    /// Reads the counts back (blocking).
    std::vector<cl_uint> read(Engine& engine) const {
        std::vector<cl_uint> counts(size);
        engine.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, size * sizeof(cl_uint), counts.data());
        return counts;
    }
    cl::Buffer buffer;
    size_t size;
};

// The cell-independent half of the vector path: the disk point bb_disk_polar(u1, u2) of every
// point of every replica (the rotated Hammersley point, as the scalar kernel forms it) and
// h = sqrt(1 - x^2), laid out for vector loads: per replica, per step of `lanes` points, the
// lanes' x, then their y, then their h. Computed here once in double with the shared functions
// and rounded to the kernel's real; the float kernel sees its shifts rounded to float, as the
// scalar kernel does.
std::vector<double> disk_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                               unsigned lanes, Precision precision) {
    std::vector<double> table(size_t(replicas) * points * BB_DISK_VALUES);
    const unsigned n = unsigned(points);
    for (unsigned r = 0; r < replicas; ++r) {
        double s1 = shifts[2 * r], s2 = shifts[2 * r + 1];
        if (precision == Precision::Float) {
            s1 = double(float(s1));
            s2 = double(float(s2));
        }
        double* out = table.data() + size_t(r) * points * BB_DISK_VALUES;
        for (unsigned i = 0; i < n; ++i) {
            const bb_vec2 d = bb_disk_polar(bb_rotate(bb_hammersley_u1(i, n), s1), bb_rotate(bb_hammersley_u2(i), s2));
            const size_t base = size_t(i / lanes) * BB_DISK_VALUES * lanes + i % lanes;
            out[base] = d.x;
            out[base + lanes] = d.y;
            out[base + 2 * lanes] = bb_safe_sqrt(1.0 - d.x * d.x);
        }
    }
    return table;
}

// The cell-independent half of the generic vector path (albedo_replicas_points): the rotated
// Hammersley point (u1, u2) of every point of every replica, laid out per replica, per step of
// `lanes` points, the lanes' u1 then their u2. Computed in the kernel's precision with the
// scalar kernel's operations (bb_hammersley_u1/u2, bb_rotate), so that both kernels see the
// same points to the last bit.
template <typename T>
void fill_point_table(std::vector<double>& table, const std::vector<double>& shifts, unsigned replicas,
                      std::uint64_t points, unsigned lanes) {
    const unsigned n = unsigned(points);
    for (unsigned r = 0; r < replicas; ++r) {
        const T s1 = T(shifts[2 * r]), s2 = T(shifts[2 * r + 1]);
        double* out = table.data() + size_t(r) * points * BB_POINTS_VALUES;
        for (unsigned i = 0; i < n; ++i) {
            T u1 = (T(i) + T(0.5)) / T(n) + s1;
            u1 = u1 >= T(1) ? u1 - T(1) : u1;
            const std::uint32_t bits = bb_reverse_bits(i);
            T u2 = (std::is_same<T, float>::value ? T(bits >> 8) * T(5.9604644775390625e-8)
                                                   : T(bits) * T(2.3283064365386963e-10)) + s2;
            u2 = u2 >= T(1) ? u2 - T(1) : u2;
            const size_t base = size_t(i / lanes) * BB_POINTS_VALUES * lanes + i % lanes;
            out[base] = double(u1);
            out[base + lanes] = double(u2);
        }
    }
}

std::vector<double> point_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                                unsigned lanes, Precision precision) {
    std::vector<double> table(size_t(replicas) * points * BB_POINTS_VALUES);
    if (precision == Precision::Float)
        fill_point_table<float>(table, shifts, replicas, points, lanes);
    else
        fill_point_table<double>(table, shifts, replicas, points, lanes);
    return table;
}

}  // namespace

namespace {

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

    BuildRequest build;
    build.kernel_file = "albedo.cl";
    build.precision = req.precision;
    build.defines = {{"BB_MODEL", std::to_string(req.model)},
                     {"BB_FRESNEL", std::to_string(req.fresnel.kind)}};
    build.random123 = req.method == Method::MonteCarlo;
    // The vector paths: importance sampling (GGX's disk path, or the model's own branch-free
    // sampler) and qmc's uniform hemisphere weights for models with a branch-free evaluation.
    const ModelTraits& traits = model_traits(req.model);
    const bool uniform = req.method == Method::QuasiMonteCarlo;
    const bool disk = !uniform && traits.samples_disk;
    build.has_vector_path = (req.method == Method::Importance && (disk || traits.samples_vector)) ||
                            (uniform && traits.evals_vector);
    build.vector_width = req.vector_width;
    unsigned lanes = engine.vector_width(build);
    if (lanes > 1 && points % lanes != 0) {
        build.vector_width = 1;  // a ragged last step: the scalar kernel
        lanes = 1;
    }
    check_memory(sampling_bytes(n_cells, n_items, lanes > 1 ? double(points) * req.replicas : req.replicas,
                                lanes > 1 ? (disk ? BB_DISK_VALUES : BB_POINTS_VALUES) : 1, req.precision),
                 "integrating " + std::to_string(n_cells) + (n_cells == 1 ? " direction with " : " directions with ") + std::to_string(req.samples) +
                     " samples each");
    if (lanes > 1 && !disk) build.defines.push_back({"BB_VECTOR_POINTS", "1"});
    if (lanes > 1 && uniform) build.defines.push_back({"BB_VECTOR_UNIFORM", "1"});
    if (lanes > 1 && disk) {
        // A launch whose cells are all isotropic gets the disk weight without the terms that
        // vanish then (bb_model_disk_isotropic): a program of its own, cached as any other.
        bool isotropic = true;
        for (const AlbedoCell& c : req.cells)
            isotropic = isotropic && bb_model_disk_isotropic(req.model, to_bb_params(c.params));
        if (isotropic) build.defines.push_back({"BB_ISOTROPIC", "1"});
    }
    cl::Program& program = engine.program(build);

    const CellArrays cells = cell_arrays(req.cells);
    const std::vector<double> fparams(req.fresnel.params.begin(), req.fresnel.params.end());
    const std::vector<double> shifts = replica_shifts(req.replicas, req.seed);

    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(cells.mus), b_phi = bufs.input(cells.phis), b_p = bufs.input(cells.params),
               b_fp = bufs.input(fparams);
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
    cl::Buffer b_points = bufs.input(lanes == 1 ? shifts
                                     : disk   ? disk_table(shifts, req.replicas, points, lanes, req.precision)
                                              : point_table(shifts, req.replicas, points, lanes, req.precision));
    cl::Buffer b_mean = bufs.output(n_items);
    const NonFiniteCounts bad_counts(engine, n_items);

    cl::Kernel kernel(program, lanes == 1 ? BB_ENTRY_NAME(BB_ENTRY_ALBEDO_REPLICAS)
                               : disk     ? BB_ENTRY_NAME(BB_ENTRY_ALBEDO_REPLICAS_DISK)
                                          : BB_ENTRY_NAME(BB_ENTRY_ALBEDO_REPLICAS_POINTS));
    cl_uint a = set_args(kernel, 0, b_mu, b_phi, b_p, b_fp, b_points, cl_uint(points), cl_uint(req.replicas),
                         cl_uint(n_cells));
    if (lanes == 1) {
        const int method = req.method == Method::Importance        ? BB_METHOD_IMPORTANCE
                           : req.method == Method::QuasiMonteCarlo ? BB_METHOD_QMC
                                                                   : BB_METHOD_MC;
        a = set_args(kernel, a, cl_int(method), cl_uint(req.seed), cl_uint(req.seed >> 32), b_stream);
    }
    set_args(kernel, a, b_mean, bad_counts.buffer);
    const double kernel_seconds =
        run_items(engine, kernel, n_items, double(points),
                  "albedo of " + std::to_string(n_cells) + " cells, " + std::to_string(req.samples) + " samples each");
    const std::vector<double> means = bufs.read(b_mean, n_items);
    const std::vector<cl_uint> bad = bad_counts.read(engine);

    AlbedoResult result;
    result.samples_per_cell = points * req.replicas;
    result.total_samples = result.samples_per_cell * n_cells;
    result.kernel_seconds = kernel_seconds;
    result.vector_width = lanes;
    result.method = method_text(req.method, req.replicas, points);
    result.values = summarize(means, bad, req.replicas, result.samples_per_cell, req.precision,
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

// Gauss-Legendre nodes and weights of the n-point rule on [0, 1] (weights summing to 1):
// the zeros of P_n and 2/((1 - x^2) P_n'(x)^2) from Boost.Math, mapped from [-1, 1]. With
// lanes > 1 (the vector kernel) the abscissae and the weights are each padded to a multiple of
// lanes with abscissa 1/2 and weight 0.
void append_gauss_legendre(unsigned n, std::vector<double>& out, unsigned lanes = 1) {
    const std::vector<double> zeros = boost::math::legendre_p_zeros<double>(int(n));  // the zeros >= 0
    std::vector<std::pair<double, double>> rule;
    for (double z : zeros) {
        const double d = boost::math::legendre_p_prime(int(n), z);
        const double w = 1.0 / ((1.0 - z * z) * d * d);  // half the weight on [-1, 1]
        rule.push_back({0.5 * (1.0 + z), w});
        if (z != 0.0) rule.push_back({0.5 * (1.0 - z), w});
    }
    std::sort(rule.begin(), rule.end());
    const size_t padded = (rule.size() + lanes - 1) / lanes * lanes;
    for (const auto& r : rule) out.push_back(r.first);
    out.resize(out.size() + padded - rule.size(), 0.5);
    for (const auto& r : rule) out.push_back(r.second);
    out.resize(out.size() + padded - rule.size(), 0.0);
}

// The (2g + 1)-point Gauss-Kronrod rule on [0, 1] and its embedded g-point Gauss rule
// [Kronrod 1965; Laurie, Math. Comp. 66, 1997], from Boost.Math: the abscissae, the Kronrod
// weights, then the Gauss weights (0 at the Kronrod-only nodes), each padded to a multiple of
// lanes as append_gauss_legendre pads. One set of nodes gives both sums: the Kronrod sum is the
// value and its distance to the Gauss sum the error estimate.
template <unsigned K>
void append_gauss_kronrod(std::vector<double>& out, unsigned lanes) {
    constexpr unsigned G = (K - 1) / 2;
    using kronrod = boost::math::quadrature::gauss_kronrod<double, K>;
    using gauss = boost::math::quadrature::gauss<double, G>;
    std::vector<std::array<double, 3>> rule;  // abscissa on [0, 1], Kronrod weight, Gauss weight
    for (size_t i = 0; i < kronrod::abscissa().size(); ++i) {
        const double z = kronrod::abscissa()[i], wk = 0.5 * kronrod::weights()[i];
        double wg = 0.0;
        for (size_t j = 0; j < gauss::abscissa().size(); ++j)
            if (std::fabs(gauss::abscissa()[j] - z) < 1e-13) wg = 0.5 * gauss::weights()[j];
        rule.push_back({0.5 * (1.0 + z), wk, wg});
        if (z != 0.0) rule.push_back({0.5 * (1.0 - z), wk, wg});
    }
    std::sort(rule.begin(), rule.end());
    const size_t padded = (rule.size() + lanes - 1) / lanes * lanes;
    for (int column = 0; column < 3; ++column) {
        for (const auto& r : rule) out.push_back(r[column]);
        out.resize(out.size() + padded - rule.size(), column == 0 ? 0.5 : 0.0);
    }
}

// The error of the n-node rule from the n/2- and n/4-node rules. For an integrand that is smooth
// on the domain the Gauss-Legendre error falls geometrically, e(n) ~ r^(2n): the difference
// d1 = |Q(n) - Q(n/2)| ~ e(n/2) is then about the square of d2 = |Q(n/2) - Q(n/4)| (relative
// to the integral), and d1 bounds e(n) with a wide margin. Where it is not (a kink, such as
// Torrance-Sparrow's V-groove min(), or a feature the rules do not yet resolve), the error
// falls algebraically or erratically and d1 can be far below e(n) (22x measured at mu = 1e-4):
// then the larger of the two differences is taken. Torrance-Sparrow's integrand always has
// the kink, and at grazing its rules can agree at 8, 16 and 32 nodes on a value 2.5e-5 off
// (n = 6, mu = 1e-4) before they resolve it: for it the larger difference is always taken.
double quadrature_error(double fine, double coarse, double coarsest, bool kinked) {
    const double scale = std::max(std::fabs(fine), 1e-3);
    const double d1 = std::fabs(fine - coarse) / scale, d2 = std::fabs(coarse - coarsest) / scale;
    const bool geometric = !kinked && d1 <= std::pow(d2, 1.5);
    return scale * (geometric ? d1 : std::max(d1, d2));
}

// The fine rule's order for a sample budget: the even n nearest sqrt(samples / 4), at least 4.
unsigned quadrature_order(std::uint64_t samples) {
    const double n = std::sqrt(double(samples) / 4.0);
    unsigned order = 2 * unsigned(std::lround(n / 2.0));
    return std::clamp(order, 4u, 4096u);
}

AlbedoResult compute_quadrature(Engine& engine, const AlbedoRequest& req) {
    if (req.samples == 0) throw Error("--samples must be positive");
    const unsigned n = quadrature_order(req.samples), m = n / 2, l = std::max(1u, n / 4);
    const size_t n_cells = req.cells.size(), n_items = n_cells * BB_QUAD_SLOTS;

    BuildRequest build;
    build.kernel_file = "albedo.cl";
    build.precision = req.precision;
    build.defines = {{"BB_MODEL", std::to_string(req.model)},
                     {"BB_FRESNEL", std::to_string(req.fresnel.kind)},
                     {"BB_QUADRATURE", "1"}};
    // The vector path (albedo_quadrature_rows, one row of the rule per lane): the half-vector
    // rule, and the sampler's square for models whose sampler (or, for the cosine warp's rule in
    // cos(theta_i), evaluation) is branch-free (-D BB_QUAD_SAMPLER_ROWS).
    const ModelTraits& traits = model_traits(req.model);
    const bool sampler_rows = !traits.halfvector_quadrature && !traits.delta &&
                              (traits.cosine_sampler ? traits.evals_vector : traits.samples_vector);
    build.has_vector_path = traits.halfvector_quadrature || sampler_rows;
    build.vector_width = req.vector_width;
    const unsigned lanes = engine.vector_width(build);
    if (lanes > 1 && sampler_rows) build.defines.push_back({"BB_QUAD_SAMPLER_ROWS", "1"});
    check_memory(sampling_bytes(n_cells, n_items, 2.0 * (n + m + l + 3 * lanes), 1, req.precision),
                 "integrating " + std::to_string(n_cells) + (n_cells == 1 ? " direction" : " directions") + " by quadrature");
    cl::Program& program = engine.program(build);

    std::vector<double> nodes;
    append_gauss_legendre(n, nodes, lanes);
    append_gauss_legendre(m, nodes, lanes);
    append_gauss_legendre(l, nodes, lanes);
    const CellArrays cells = cell_arrays(req.cells);
    const std::vector<double> fparams(req.fresnel.params.begin(), req.fresnel.params.end());
    RealBuffers bufs(engine, req.precision);
    cl::Buffer b_mu = bufs.input(cells.mus), b_phi = bufs.input(cells.phis), b_p = bufs.input(cells.params),
               b_fp = bufs.input(fparams), b_nodes = bufs.input(nodes);
    cl::Buffer b_sum = bufs.output(n_items);
    const NonFiniteCounts bad_counts(engine, n_items);

    cl::Kernel kernel(program, lanes > 1 ? BB_ENTRY_NAME(BB_ENTRY_ALBEDO_QUADRATURE_ROWS)
                                         : BB_ENTRY_NAME(BB_ENTRY_ALBEDO_QUADRATURE));
    set_args(kernel, 0, b_mu, b_phi, b_p, b_fp, b_nodes, cl_uint(n), cl_uint(m), cl_uint(l), cl_uint(n_cells), b_sum,
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
        v.samples = per_piece * std::uint64_t(bb_quad_piece_count(
                                    bb_model_quad_dist(req.model, to_bb_params(req.cells[c].params)), req.cells[c].phi));
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

AlbedoResult compute_albedo(Engine& engine, const AlbedoRequest& request) {
    if (auto shared = shared_albedo(engine, request)) return std::move(*shared);  // MPI ranks, shards
    if (request.cells.empty()) throw Error("no directions to integrate");
    AlbedoRequest req = request;
    for (auto& c : req.cells) {
        if (!(c.mu > 0.0 && c.mu <= 1.0)) throw Error("mu must lie in (0, 1]; got " + format_number(c.mu));
        c.phi = reduce_azimuth(c.phi);
    }
    AlbedoResult result = req.method == Method::Quadrature ? compute_quadrature(engine, req) : compute_sampled(engine, req);
    // The kernels count non-finite samples; this catches what the reduction of their sums could
    // still overflow (a finite BRDF whose integral exceeds the precision's range).
    for (size_t c = 0; c < result.values.size(); ++c)
        if (!std::isfinite(result.values[c].value) || !std::isfinite(result.values[c].error))
            throw NonFiniteError(nonfinite_where(req, c) + " (the integral overflows); refusing to report a result", c, 1);
    return result;
}

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

int dielectric_shadowing(const DielectricRequest& req) {
    return !req.correlated            ? BB_DIELECTRIC_SHADOWING_SEPARABLE
           : req.cycles_transmission ? BB_DIELECTRIC_SHADOWING_CYCLES
                                     : BB_DIELECTRIC_SHADOWING_BETA;
}

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
    build.defines = {{"BB_MODEL", std::to_string(BB_MODEL_GGX)}, {"BB_QUADRATURE", "1"}};
    // The vector path (dielectric_quadrature_rows): one row of the rule per lane.
    build.has_vector_path = true;
    build.vector_width = req.vector_width;
    const unsigned lanes = engine.vector_width(build);
    check_memory(sampling_bytes(n_cells, n_items * 2, 3.0 * (rule.n + rule.m + rule.l + 3 * lanes), 1, req.precision),
                 "integrating " + std::to_string(n_cells) + " dielectric cells by quadrature");
    cl::Program& program = engine.program(build);

    std::vector<double> nodes, mus, alphas, etas;
    switch (rule.kronrod) {
        case 15: append_gauss_kronrod<15>(nodes, lanes); break;
        case 21: append_gauss_kronrod<21>(nodes, lanes); break;
        case 31: append_gauss_kronrod<31>(nodes, lanes); break;
        case 41: append_gauss_kronrod<41>(nodes, lanes); break;
        case 51: append_gauss_kronrod<51>(nodes, lanes); break;
        case 61: append_gauss_kronrod<61>(nodes, lanes); break;
        default:
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
             cl_uint(n_cells), cl_uint(rule.kronrod ? 1 : 0), cl_int(dielectric_shadowing(req)), b_r, b_t,
             bad_counts.buffer);
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
    unsigned lanes = engine.vector_width(build);
    if (lanes > 1 && points % lanes != 0) {
        build.vector_width = 1;  // a ragged last step: the scalar kernel
        lanes = 1;
    }
    check_memory(sampling_bytes(n_cells, n_items * 2, lanes > 1 ? double(points) * req.replicas : req.replicas,
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
    cl::Buffer b_mu = bufs.input(mus), b_alpha = bufs.input(alphas), b_eta = bufs.input(etas),
               b_shift = bufs.input(lanes > 1 ? disk_table(shifts, req.replicas, points, lanes, req.precision) : shifts);
    cl::Buffer b_r = bufs.output(n_items), b_t = bufs.output(n_items);
    const NonFiniteCounts bad_counts(engine, n_items);
    cl::Kernel kernel(program, lanes > 1 ? BB_ENTRY_NAME(BB_ENTRY_DIELECTRIC_REPLICAS_DISK)
                                         : BB_ENTRY_NAME(BB_ENTRY_DIELECTRIC_REPLICAS));
    set_args(kernel, 0, b_mu, b_alpha, b_eta, b_shift, cl_uint(points), cl_uint(req.replicas), cl_uint(n_cells),
             cl_int(dielectric_shadowing(req)),
             b_r, b_t, bad_counts.buffer);
    const double kernel_seconds =
        run_items(engine, kernel, n_items, kDielectricNodeCost * double(points),
                  "rough dielectric of " + std::to_string(n_cells) + " cells, " + std::to_string(req.samples) +
                      " samples each");
    const std::vector<double> r = bufs.read(b_r, n_items), t = bufs.read(b_t, n_items);
    const std::vector<cl_uint> bad = bad_counts.read(engine);

    DielectricResult result;
    result.samples_per_cell = points * req.replicas;
    result.kernel_seconds = kernel_seconds;
    result.method = method_text(Method::Importance, req.replicas, points);
    result.vector_width = lanes;
    auto where = [&](size_t c) { return dielectric_nonfinite_where(req, c); };
    result.reflected = summarize(r, bad, req.replicas, result.samples_per_cell, req.precision, where);
    result.transmitted = summarize(t, bad, req.replicas, result.samples_per_cell, req.precision, where);
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

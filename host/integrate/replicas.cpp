#include "integrate/replicas.h"

#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/sampling.h"

namespace brdfbake {

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
std::vector<AlbedoValue> summarize(const std::vector<double>& means, const std::vector<cl_uint>& bad,
                                   unsigned replicas, std::uint64_t samples_per_cell, Precision precision,
                                   const std::function<std::string(size_t)>& where) {
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

std::vector<std::vector<AlbedoValue>> summarize_columns(const std::vector<double>& sums, int width,
                                                        const std::vector<cl_uint>& bad, unsigned replicas,
                                                        std::uint64_t samples_per_cell, Precision precision,
                                                        const std::function<std::string(size_t)>& where) {
    const size_t n_items = sums.size() / size_t(width);
    std::vector<std::vector<AlbedoValue>> out;
    std::vector<double> column(n_items);
    for (int k = 0; k < width; ++k) {
        for (size_t i = 0; i < n_items; ++i) column[i] = sums[size_t(width) * i + size_t(k)];
        out.push_back(summarize(column, bad, replicas, samples_per_cell, precision, where));
        for (AlbedoValue& v : out.back()) {
            v.samples = samples_per_cell;
            v.method = Method::MonteCarlo;
        }
    }
    return out;
}

void check_sampling(std::uint64_t samples, unsigned replicas) {
    if (replicas < 2) throw Error("at least 2 replicas are needed for an error estimate");
    if (samples < replicas) throw Error("--samples must be at least " + std::to_string(replicas));
    if (samples / replicas > 0xffffffffu) throw Error("--samples is too large (at most 2^32 per replica)");
}

// The cell-independent half of the vector path: the disk point bb_disk_polar(u1, u2) of every
// point of every replica (the rotated Hammersley point, as the scalar kernel forms it) and
// h = sqrt(1 - x^2), laid out for vector loads: per replica, per step of `lanes` points, the
// lanes' x, then their y, then their h. Computed here once in double with the shared functions
// and rounded to the kernel's real; the float kernel sees its shifts rounded to float, as the
// scalar kernel does.
std::vector<PointChunk> table_chunks(std::uint64_t points, unsigned replicas, unsigned lanes) {
    const std::uint64_t step = std::max<std::uint64_t>(lanes, kTablePointsMax / replicas / lanes * lanes);
    std::vector<PointChunk> chunks;
    for (std::uint64_t first = 0; first < points; first += step) chunks.push_back({first, std::min(step, points - first)});
    return chunks;
}

VectorChunks vector_chunks(const Engine& engine, BuildRequest& build, std::uint64_t points, unsigned replicas) {
    VectorChunks v;
    v.lanes = engine.vector_width(build);
    if (v.lanes > 1 && points % v.lanes != 0) {
        build.vector_width = 1;  // a ragged last step: the scalar kernel
        v.lanes = 1;
    }
    v.chunks = v.lanes > 1 ? table_chunks(points, replicas, v.lanes) : std::vector<PointChunk>{{0, points}};
    return v;
}

std::vector<double> disk_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                               unsigned lanes, Precision precision, PointChunk chunk) {
    std::vector<double> table(size_t(replicas) * chunk.count * BB_DISK_VALUES);
    const unsigned n = unsigned(points);
    for (unsigned r = 0; r < replicas; ++r) {
        double s1 = shifts[2 * r], s2 = shifts[2 * r + 1];
        if (precision == Precision::Float) {
            s1 = double(float(s1));
            s2 = double(float(s2));
        }
        double* out = table.data() + size_t(r) * chunk.count * BB_DISK_VALUES;
        for (unsigned j = 0; j < unsigned(chunk.count); ++j) {
            const unsigned i = unsigned(chunk.first) + j;
            const bb_vec2 d = bb_disk_polar(bb_rotate(bb_hammersley_u1(i, n), s1), bb_rotate(bb_hammersley_u2(i), s2));
            const size_t base = size_t(j / lanes) * BB_DISK_VALUES * lanes + j % lanes;
            out[base] = d.x;
            out[base + lanes] = d.y;
            out[base + 2 * lanes] = bb_safe_sqrt(1.0 - d.x * d.x);
        }
    }
    return table;
}

namespace {

// The cell-independent half of the generic vector path (albedo_replicas_points): the rotated
// Hammersley point (u1, u2) of every point of every replica, laid out per replica, per step of
// `lanes` points, the lanes' u1 then their u2. Computed in the kernel's precision with the
// scalar kernel's operations (bb_hammersley_u1/u2, bb_rotate), so that both kernels see the
// same points to the last bit.
template <typename T>
void fill_point_table(std::vector<double>& table, const std::vector<double>& shifts, unsigned replicas,
                      std::uint64_t points, unsigned lanes, PointChunk chunk) {
    const unsigned n = unsigned(points);
    for (unsigned r = 0; r < replicas; ++r) {
        const T s1 = T(shifts[2 * r]), s2 = T(shifts[2 * r + 1]);
        double* out = table.data() + size_t(r) * chunk.count * BB_POINTS_VALUES;
        for (unsigned j = 0; j < unsigned(chunk.count); ++j) {
            const unsigned i = unsigned(chunk.first) + j;
            T u1 = (T(i) + T(0.5)) / T(n) + s1;
            u1 = u1 >= T(1) ? u1 - T(1) : u1;
            const std::uint32_t bits = bb_reverse_bits(i);
            T u2 = (std::is_same<T, float>::value ? T(bits >> 8) * T(5.9604644775390625e-8)
                                                   : T(bits) * T(2.3283064365386963e-10)) + s2;
            u2 = u2 >= T(1) ? u2 - T(1) : u2;
            const size_t base = size_t(j / lanes) * BB_POINTS_VALUES * lanes + j % lanes;
            out[base] = double(u1);
            out[base + lanes] = double(u2);
        }
    }
}

}  // namespace

std::vector<double> point_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                                unsigned lanes, Precision precision, PointChunk chunk) {
    std::vector<double> table(size_t(replicas) * chunk.count * BB_POINTS_VALUES);
    if (precision == Precision::Float)
        fill_point_table<float>(table, shifts, replicas, points, lanes, chunk);
    else
        fill_point_table<double>(table, shifts, replicas, points, lanes, chunk);
    return table;
}

}  // namespace brdfbake

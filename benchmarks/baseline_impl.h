// The baseline's inner loop, compiled once per flavour (baseline_*.cpp, each with its own
// flags). Define BASELINE_NS and BASELINE_FN first, and BB_HOST_REAL_FLOAT for the float build.
//
// Written the way a performance engineer writes it in plain C++, independently of the shared
// BRDF headers (which g++ does not vectorise: control flow, fmin/fmax calls, a sincos per
// sample): the same estimator as kernels/albedo.cl's importance path for GGX — visible-normal
// sampling [Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)], the
// weight G2/G1(wo) (height-correlated or separable Smith), F = 1 — on the same randomised
// Hammersley points, their disk warp tabulated once per replica as the kernel's vector path
// does, and a branch-free inner loop that `omp simd` vectorises (-fopt-info-vec-optimized).
// wo lies in the x-z plane (phi_o = 0), as in every table of the benchmark.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <omp.h>

namespace BASELINE_NS {
#ifdef BB_HOST_REAL_FLOAT
using real = float;
#else
using real = double;
#endif

inline std::uint32_t reverse_bits(std::uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

// Smith Lambda of GGX for a direction with cos(theta) = z (z > 0): (sqrt(1 + a^2 tan^2) - 1)/2.
inline real lambda(real a2, real z2) { return (std::sqrt(real(1) + a2 * (real(1) - z2) / z2) - real(1)) * real(0.5); }

// Replica means and non-finite counts of every (cell, replica), cell-major: exactly the work
// items of kernels/albedo.cl.
inline void BASELINE_FN(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                        std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                        std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    const long n_items = long(mus.size()) * long(replicas);
    means.assign(size_t(n_items), 0.0);
    bad.assign(size_t(n_items), 0);
    const long n = long(points);
    // The disk points sqrt(u1) (cos, sin)(2 pi u2) of every replica's rotated Hammersley set:
    // they do not depend on the cell (the kernel's vector path tabulates them too).
    std::vector<real> disk_x(size_t(replicas) * size_t(n)), disk_y(disk_x.size());
#pragma omp parallel for
    for (long k = 0; k < long(replicas) * n; ++k) {
        const long rep = k / n, i = k - rep * n;
        double u1 = (double(i) + 0.5) / double(n) + shifts[2 * size_t(rep)];
        double u2 = double(reverse_bits(std::uint32_t(i))) * 2.3283064365386963e-10 + shifts[2 * size_t(rep) + 1];
        u1 -= u1 >= 1.0 ? 1.0 : 0.0;
        u2 -= u2 >= 1.0 ? 1.0 : 0.0;
        const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
        disk_x[size_t(k)] = real(r * std::cos(phi));
        disk_y[size_t(k)] = real(r * std::sin(phi));
    }
#pragma omp parallel for schedule(dynamic, 1)
    for (long item = 0; item < n_items; ++item) {
        const long cell = item / replicas, rep = item - cell * replicas;
        const real a = real(alphas[size_t(cell)]), a2 = a * a;
        const real oz = real(mus[size_t(cell)]), ox = std::sqrt(std::max(real(0), real(1) - oz * oz));
        // The view direction in the hemisphere configuration: Vh = normalize(a ox, 0, oz), with
        // T1 = (0, 1, 0) and T2 = Vh x T1 = (-vz, 0, vx).
        const real vl = real(1) / std::sqrt(a2 * ox * ox + oz * oz);
        const real vx = a * ox * vl, vz = oz * vl;
        const real s = real(0.5) * (real(1) + vz);
        // G2/G1(wo) = c0 / (c0 + Lambda(wi)): c0 = 1 + Lambda(wo) height-correlated, 1 separable.
        const real c0 = correlated ? real(1) + lambda(a2, oz * oz) : real(1);
        const real* dx = disk_x.data() + size_t(rep) * size_t(n);
        const real* dy = disk_y.data() + size_t(rep) * size_t(n);
        // Summed in `real` over blocks of 512 points (vector lanes) and the blocks in double: the
        // float flavour's 2^16-term sums stay exact to ~1e-9 without a compensated (loop-carried)
        // sum, and the inner loop stays in the vector registers of its precision.
        double sum = 0.0;
        std::uint64_t nb = 0;
        for (long b = 0; b < n; b += 512) {
            const long e = std::min(n, b + 512);
            real block = 0;
            unsigned block_bad = 0;
#pragma omp simd reduction(+ : block, block_bad)
            for (long i = b; i < e; ++i) {
                const real t1 = dx[i];
                const real h = std::sqrt(std::max(real(0), real(1) - t1 * t1));
                const real t2 = (real(1) - s) * h + s * dy[i];
                const real t3 = std::sqrt(std::max(real(0), real(1) - t1 * t1 - t2 * t2));
                // Nh = t1 T1 + t2 T2 + t3 Vh, unstretched to the normal Ne = normalize(a Nh.x, a Nh.y, Nh.z).
                const real nx = a * (t3 * vx - t2 * vz), ny = a * t1, nz = std::max(real(0), t2 * vx + t3 * vz);
                const real inv = real(1) / std::sqrt(nx * nx + ny * ny + nz * nz);
                const real d = (ox * nx + oz * nz) * inv;
                const real iz = real(2) * d * nz * inv - oz;  // wi.z of wi = 2 (wo.Ne) Ne - wo
                const real iz2 = std::max(iz * iz, real(1e-30));
                const real li = lambda(a2, iz2);
                const real w = c0 / (c0 + li);
                const real v = iz > real(0) ? w : real(0);
                const bool ok = std::isfinite(v);
                block_bad += ok ? 0u : 1u;
                block += ok ? v : real(0);
            }
            sum += double(block);
            nb += block_bad;
        }
        means[size_t(item)] = sum / double(n);
        bad[size_t(item)] = nb;
    }
}
}  // namespace BASELINE_NS

// The baseline's inner loop, compiled once per flavour (baseline_*.cpp, each with its own
// flags). Define BASELINE_NS and BASELINE_FN first, BB_HOST_REAL_FLOAT for the float build, and
// BASELINE_KERNEL_ARITHMETIC for the row that transcribes the kernel's arithmetic.
//
// Written the way a performance engineer writes it in plain C++, independently of the shared
// BRDF headers (which g++ does not vectorise: control flow, fmin/fmax calls, a sincos per
// sample): the same estimator as kernels/albedo.cl's importance path for GGX — visible-normal
// sampling [Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)], the
// weight G2/G1(wo) (height-correlated or separable Smith), F = 1 — on the same randomised
// Hammersley points and Cranley-Patterson shifts, the same replicas and replica means; wo lies
// in the x-z plane (phi_o = 0), as in every table of the benchmark.
//
// What makes it fast, each verified with -fopt-info-vec-optimized ("loop vectorized using 32
// byte vectors" for the `omp simd` loop in every flavour) and the assembly (vsqrtps/vdivps):
//   * the work that does not depend on the cell in tables computed once per call: the disk
//     point (x, y) = sqrt(u1) (cos, sin)(2 pi u2) of every rotated Hammersley point, as the
//     kernel's vector path does (host/integrate/replicas.cpp's disk_table), and also sqrt(1 - x^2);
//   * the weight in closed form on the unnormalised normal: with n = (a Nh.x, a Nh.y,
//     max(0, Nh.z)), L = |n|^2 and z = L wi.z = 2 (wo.n) n.z - wo.z L, the weight is
//     c0 / (c0 + Lambda(wi)) = 2 c0 z / ((2 c0 - 1) z + sqrt(a^2 L^2 + (1 - a^2) z^2)),
//     c0 = 1 + Lambda(wo) (height-correlated) or 1 (separable): per sample two square roots
//     and one division, where the shared headers' form (normalise, reflect, G1(wi), G2, / G1(wo))
//     takes four of each. Algebraically the same weight; only the rounding differs;
//   * a branch-free loop body: selects written as ternaries on plain values (no std::min/max,
//     which bind references and make g++ build "simd arrays"), no select on a scalar bool (g++
//     cannot vectorise `flag ? vector : vector`), sqrt and division only, no library calls. In
//     the strict flavour -fno-trapping-math (CMakeLists.txt) lets g++ if-convert the sunk
//     weight; values and NaN/Inf semantics are unchanged (OpenCL has no FP exceptions either);
//   * non-finite weights counted, never summed, as in the kernel (std::isfinite; the
//     -ffast-math flavour may assume them away);
//   * sums in the working precision over blocks of 512 points (64 per vector lane) and the
//     blocks in double: the float sums of 2^12..2^16 terms stay accurate to ~1e-8 without a
//     compensated (loop-carried) sum, which -ffast-math would remove anyway.
// BASELINE_KERNEL_ARITHMETIC instead evaluates the weight with the operations of the shared
// headers (bb_ggx_sample_vndf_disk: normalise; bb_reflect; bb_ggx_g1's closed form;
// bb_g2_correlated_from_g1; / G1(wo); the clamps and guards) from the (x, y) table alone: the
// kernel's arithmetic, vectorised by g++, to tell the compiler's share from the arithmetic's.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <omp.h>

#include "baseline_common.h"

namespace BASELINE_NS {
#ifdef BB_HOST_REAL_FLOAT
using bb_real = float;
#else
using bb_real = double;
#endif

using brdfbake::baseline::reverse_bits;

// max(x, 0) by value (NaN gives 0, as fmax(x, 0) and the kernel's bb_max).
inline bb_real max0(bb_real x) { return x > bb_real(0) ? x : bb_real(0); }

// Replica means and non-finite counts of every (cell, replica), cell-major: exactly the work
// items of kernels/albedo.cl.
inline void BASELINE_FN(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                        std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                        std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    const long n_items = long(mus.size()) * long(replicas);
    means.assign(size_t(n_items), 0.0);
    bad.assign(size_t(n_items), 0);
    const long n = long(points);
    // The disk points sqrt(u1) (cos, sin)(2 pi u2) of every replica's rotated Hammersley set,
    // computed in double and rounded to `real` as host/integrate/replicas.cpp's disk_table does (the float
    // flavour's shifts are already rounded to float, baseline.cpp), and sqrt(1 - x^2).
    std::vector<bb_real> disk_x(size_t(replicas) * size_t(n)), disk_y(disk_x.size());
#ifndef BASELINE_KERNEL_ARITHMETIC
    std::vector<bb_real> disk_h(disk_x.size());
#endif
#pragma omp parallel for
    for (long k = 0; k < long(replicas) * n; ++k) {
        const long rep = k / n, i = k - rep * n;
        double u1 = (double(i) + 0.5) / double(n) + shifts[2 * size_t(rep)];
        double u2 = double(reverse_bits(std::uint32_t(i))) * 2.3283064365386963e-10 + shifts[2 * size_t(rep) + 1];
        u1 -= u1 >= 1.0 ? 1.0 : 0.0;
        u2 -= u2 >= 1.0 ? 1.0 : 0.0;
        const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
        const bb_real x = bb_real(r * std::cos(phi));
        disk_x[size_t(k)] = x;
        disk_y[size_t(k)] = bb_real(r * std::sin(phi));
#ifndef BASELINE_KERNEL_ARITHMETIC
        disk_h[size_t(k)] = std::sqrt(max0(bb_real(1) - x * x));
#endif
    }
#pragma omp parallel for schedule(dynamic, 1)
    for (long item = 0; item < n_items; ++item) {
        const long cell = item / replicas, rep = item - cell * replicas;
        const bb_real a = bb_real(alphas[size_t(cell)]), a2 = a * a;
        const bb_real oz = bb_real(mus[size_t(cell)]), ox = std::sqrt(std::max(bb_real(0), bb_real(1) - oz * oz));
        // The view direction in the hemisphere configuration: Vh = normalize(a ox, 0, oz), with
        // T1 = (0, 1, 0) and T2 = Vh x T1 = (-vz, 0, vx).
        const bb_real vl = bb_real(1) / std::sqrt(a2 * ox * ox + oz * oz);
        const bb_real vx = a * ox * vl, vz = oz * vl;
        const bb_real s = bb_real(0.5) * (bb_real(1) + vz), s1 = bb_real(1) - s;
        // c0 = 1 + Lambda(wo) = 1 / G1(wo), with Lambda(z) = (sqrt(1 + a^2 (1 - z^2) / z^2) - 1) / 2.
        const bb_real inv_g1o = bb_real(0.5) * (bb_real(1) + std::sqrt(bb_real(1) + a2 * (bb_real(1) - oz * oz) / (oz * oz)));
        const bb_real* dx = disk_x.data() + size_t(rep) * size_t(n);
        const bb_real* dy = disk_y.data() + size_t(rep) * size_t(n);
#ifndef BASELINE_KERNEL_ARITHMETIC
        const bb_real* dh = disk_h.data() + size_t(rep) * size_t(n);
        const bb_real c0 = correlated ? inv_g1o : bb_real(1);
        const bb_real k2 = bb_real(2) * c0, k1 = k2 - bb_real(1), b2 = bb_real(1) - a2;
#else
        const bb_real g1o = bb_real(1) / inv_g1o, corr = correlated ? bb_real(1) : bb_real(0);
#endif
        double sum = 0.0, nbad = 0.0;
        for (long b = 0; b < n; b += 512) {
            const long e = std::min(n, b + 512);
            bb_real block = 0, block_bad = 0;
#pragma omp simd reduction(+ : block, block_bad)
            for (long i = b; i < e; ++i) {
                const bb_real t1 = dx[i];
#ifndef BASELINE_KERNEL_ARITHMETIC
                const bb_real t2 = s1 * dh[i] + s * dy[i];
                const bb_real t3 = std::sqrt(max0(bb_real(1) - t1 * t1 - t2 * t2));
                // Nh = t1 T1 + t2 T2 + t3 Vh, unstretched: n = (a Nh.x, a Nh.y, max(0, Nh.z)).
                const bb_real nx = a * (t3 * vx - t2 * vz), ny = a * t1, nz = max0(t2 * vx + t3 * vz);
                const bb_real L = nx * nx + ny * ny + nz * nz;
                const bb_real z = bb_real(2) * (ox * nx + oz * nz) * nz - oz * L;  // L wi.z
                const bb_real q = std::sqrt(a2 * L * L + b2 * z * z);
                const bb_real w = k2 * z / (k1 * z + q);
                const bb_real v = z > bb_real(0) ? w : bb_real(0);  // below the horizon: 0
#else
                const bb_real t2 = s1 * std::sqrt(max0(bb_real(1) - t1 * t1)) + s * dy[i];
                const bb_real t3 = std::sqrt(max0(bb_real(1) - t1 * t1 - t2 * t2));
                const bb_real nx = a * (t3 * vx - t2 * vz), ny = a * t1, nz = max0(t2 * vx + t3 * vz);
                const bb_real l2 = nx * nx + ny * ny + nz * nz;  // bb_normalize
                const bb_real inv = l2 > bb_real(0) ? bb_real(1) / std::sqrt(l2) : bb_real(0);
                const bb_real hx = nx * inv, hy = ny * inv, hz = nz * inv;
                const bb_real d0 = ox * hx + oz * hz;  // bb_clamp_cos(wo.wh), bb_reflect
                const bb_real d1 = d0 < bb_real(1) ? d0 : bb_real(1), d = d1 > bb_real(-1) ? d1 : bb_real(-1);
                const bb_real ix = bb_real(2) * d * hx - ox, iy = bb_real(2) * d * hy, iz = bb_real(2) * d * hz - oz;
                const bb_real zi = max0(iz), r2 = a2 * (ix * ix + iy * iy);  // bb_ggx_g1(wi)
                const bb_real ga = bb_real(2) * zi * (std::sqrt(zi * zi + r2) + zi);
                const bb_real g1i = iz > bb_real(0) ? ga / (ga + r2) : bb_real(0);
                const bb_real p = g1o * g1i, den = g1o + g1i - p;  // bb_g2_correlated_from_g1
                const bb_real g2c = p > bb_real(0) ? p / (den <= bb_real(0) ? bb_real(1) : den) : bb_real(0);
                const bb_real g2 = corr > bb_real(0) ? g2c : p;
                const bb_real v = iz > bb_real(0) ? g2 / g1o : bb_real(0);
#endif
                const bool ok = std::isfinite(v);  // NaN/Inf counted, never summed
                block_bad += ok ? bb_real(0) : bb_real(1);
                block += ok ? v : bb_real(0);
            }
            sum += double(block);
            nbad += double(block_bad);
        }
        means[size_t(item)] = sum / double(n);
        bad[size_t(item)] = std::uint64_t(nbad);
    }
}
}  // namespace BASELINE_NS

#include "baseline_entry.h"

// The plain baseline's loop (issue 9's "plain C++ OpenMP loop of the same estimator"), compiled
// once per flavour (baseline_plain_*.cpp, each with its own flags). Define BASELINE_NS and
// BASELINE_FN first, and BB_HOST_REAL_FLOAT for the float build.
//
// The textbook algorithm as a competent person writes it in plain C++, independently of the
// shared BRDF headers and of the tuned loop (baseline_impl.h): `omp parallel for` over the
// (cell, replica) work items, an `omp simd` reduction over the points, and per sample
//   * the rotated Hammersley point as kernels/albedo.cl forms it (bb_hammersley_u1/u2,
//     bb_rotate): u1 = (i + 1/2)/n + shift1, u2 = radical inverse of i + shift2, each minus 1
//     if >= 1; the radical inverse is reverse_bits(i) 2^-32 in double and, as the float kernel,
//     (reverse_bits(i) >> 8) 2^-24 in float (it never rounds up to 1);
//   * visible-normal sampling, Heitz 2018 listing 1 [Heitz, "Sampling the GGX Distribution of
//     Visible Normals", JCGT 7(4)]: stretch, orthonormal basis, r = sqrt(u1), phi = 2 pi u2,
//     t1 = r cos phi, t2 = r sin phi, the (1 + Vh.z)/2 blend, reprojection onto the hemisphere,
//     unstretch, normalise; the sin and cos per sample, nothing tabulated;
//   * reflection wi = 2 (wo.m) m - wo and the weight G2/G1(wo) with the textbook Smith
//     Lambda(w) = (sqrt(1 + a^2 tan^2 theta) - 1)/2, G1 = 1/(1 + Lambda), G2 = 1/(1 + Lambda_o +
//     Lambda_i) (height-correlated) or G1(wo) G1(wi) (separable), 0 below the horizon; F = 1;
//   * non-finite weights counted, never summed; sums in the working precision over blocks of 512
//     points and in double across blocks (as baseline_impl.h).
// The same estimator, points, shifts, replicas and outputs as the kernel and the tuned loop;
// wo lies in the x-z plane (phi_o = 0) as in every table of the benchmark, but the loop treats
// it as a general vector. Selects are ternaries on plain values (no std::min/max, which bind
// references), so that the body is branch-free. With -ffast-math, glibc's <math.h> declares
// vector variants of sin/cos (libmvec, `omp declare simd`) and g++ vectorises the loop; without
// it there are no vector sin/cos and the loop runs scalar (docs in benchmarks/baseline.h).
#include <cmath>
#include <cstdint>
#include <vector>

#include <omp.h>

#include "baseline_common.h"

// g++ (12) merges sin(phi) and cos(phi) into one scalar sincos (__builtin_cexpi) before it
// vectorises, and it cannot vectorise that call: with -ffast-math, where libmvec offers vector
// sin and cos, the cosines of a block are therefore taken in a loop of their own (the same values).
#ifdef __FAST_MATH__
#define BASELINE_PLAIN_COS_LOOP 1
#else
#define BASELINE_PLAIN_COS_LOOP 0
#endif

namespace BASELINE_NS {
#ifdef BB_HOST_REAL_FLOAT
using bb_real = float;
#else
using bb_real = double;
#endif

using brdfbake::baseline::reverse_bits;

// The radical inverse in base 2 as a real in [0, 1), as the kernel's bb_unit_from_bits.
inline bb_real radical_inverse(std::uint32_t i) {
#ifdef BB_HOST_REAL_FLOAT
    return bb_real(reverse_bits(i) >> 8) * bb_real(5.9604644775390625e-8);  // 2^-24
#else
    return bb_real(reverse_bits(i)) * bb_real(2.3283064365386963e-10);  // 2^-32
#endif
}

// (x + shift) mod 1 for x, shift in [0, 1).
inline bb_real rotate(bb_real x, bb_real shift) {
    const bb_real u = x + shift;
    return u >= bb_real(1) ? u - bb_real(1) : u;
}

// Smith's Lambda for GGX: (sqrt(1 + a^2 tan^2 theta) - 1) / 2, tan^2 theta = (x^2 + y^2) / z^2.
inline bb_real smith_lambda(bb_real x, bb_real y, bb_real z, bb_real a2) {
    return bb_real(0.5) * (std::sqrt(bb_real(1) + a2 * (x * x + y * y) / (z * z)) - bb_real(1));
}

// Replica means and non-finite counts of every (cell, replica), cell-major: exactly the work
// items of kernels/albedo.cl.
inline void BASELINE_FN(const std::vector<double>& mus, const std::vector<double>& alphas, bool correlated,
                        std::uint64_t points, unsigned replicas, const std::vector<double>& shifts,
                        std::vector<double>& means, std::vector<std::uint64_t>& bad) {
    const long n_items = long(mus.size()) * long(replicas);
    means.assign(size_t(n_items), 0.0);
    bad.assign(size_t(n_items), 0);
    const long n = long(points);
    const bb_real pi2 = bb_real(6.283185307179586);
#pragma omp parallel for schedule(dynamic, 1)
    for (long item = 0; item < n_items; ++item) {
        const long cell = item / replicas, rep = item - cell * replicas;
        const bb_real a = bb_real(alphas[size_t(cell)]), a2 = a * a;
        const bb_real sh1 = bb_real(shifts[2 * size_t(rep)]), sh2 = bb_real(shifts[2 * size_t(rep) + 1]);
        // wo = (sin theta_o, 0, cos theta_o).
        const bb_real woz = bb_real(mus[size_t(cell)]);
        const bb_real wox = std::sqrt(bb_real(1) - woz * woz > bb_real(0) ? bb_real(1) - woz * woz : bb_real(0)), woy = bb_real(0);
        // Listing 1: the stretched view Vh and its basis T1, T2 (the same for every sample).
        const bb_real vlx = a * wox, vly = a * woy, vlen = std::sqrt(vlx * vlx + vly * vly + woz * woz);
        const bb_real vhx = vlx / vlen, vhy = vly / vlen, vhz = woz / vlen;
        const bb_real lensq = vhx * vhx + vhy * vhy;
        const bb_real inv_len = lensq > bb_real(0) ? bb_real(1) / std::sqrt(lensq) : bb_real(0);
        const bb_real t1x = lensq > bb_real(0) ? -vhy * inv_len : bb_real(1), t1y = lensq > bb_real(0) ? vhx * inv_len : bb_real(0);
        const bb_real t1z = bb_real(0);
        const bb_real t2x = vhy * t1z - vhz * t1y, t2y = vhz * t1x - vhx * t1z, t2z = vhx * t1y - vhy * t1x;
        const bb_real s = bb_real(0.5) * (bb_real(1) + vhz);
        // G1(wo) = 1 / (1 + Lambda(wo)).
        const bb_real lambda_o = smith_lambda(wox, woy, woz, a2);
        const bb_real g1o = bb_real(1) / (bb_real(1) + lambda_o);
        const bb_real corr = correlated ? bb_real(1) : bb_real(0);
        double sum = 0.0, nbad = 0.0;
        for (long b = 0; b < n; b += 512) {
            const long e = n < b + 512 ? n : b + 512;
            bb_real block = 0, block_bad = 0;
#if BASELINE_PLAIN_COS_LOOP
            bb_real cos_phi[512];
#pragma omp simd
            for (long i = b; i < e; ++i)
                cos_phi[i - b] = std::cos(pi2 * rotate(radical_inverse(std::uint32_t(i)), sh2));
#endif
#pragma omp simd reduction(+ : block, block_bad)
            for (long i = b; i < e; ++i) {
                // The rotated Hammersley point.
                const bb_real u1 = rotate((bb_real(i) + bb_real(0.5)) / bb_real(n), sh1);
                const bb_real u2 = rotate(radical_inverse(std::uint32_t(i)), sh2);
                // Listing 1: the disk point, warped to the projected hemisphere.
                const bb_real r = std::sqrt(u1), phi = pi2 * u2;
#if BASELINE_PLAIN_COS_LOOP
                const bb_real t1 = r * cos_phi[i - b];
#else
                const bb_real t1 = r * std::cos(phi);
#endif
                const bb_real t2d = r * std::sin(phi);
                const bb_real h = std::sqrt(bb_real(1) - t1 * t1 > bb_real(0) ? bb_real(1) - t1 * t1 : bb_real(0));
                const bb_real t2 = (bb_real(1) - s) * h + s * t2d;
                const bb_real pz = bb_real(1) - t1 * t1 - t2 * t2;
                const bb_real t3 = std::sqrt(pz > bb_real(0) ? pz : bb_real(0));
                // Reprojection Nh = t1 T1 + t2 T2 + t3 Vh, unstretched and normalised.
                const bb_real nhx = t1 * t1x + t2 * t2x + t3 * vhx;
                const bb_real nhy = t1 * t1y + t2 * t2y + t3 * vhy;
                const bb_real nhz = t1 * t1z + t2 * t2z + t3 * vhz;
                const bb_real nx = a * nhx, ny = a * nhy, nz = nhz > bb_real(0) ? nhz : bb_real(0);
                const bb_real inv_m = bb_real(1) / std::sqrt(nx * nx + ny * ny + nz * nz);
                const bb_real mx = nx * inv_m, my = ny * inv_m, mz = nz * inv_m;
                // Reflection and the weight G2 / G1(wo).
                const bb_real d = wox * mx + woy * my + woz * mz;
                const bb_real wix = bb_real(2) * d * mx - wox, wiy = bb_real(2) * d * my - woy, wiz = bb_real(2) * d * mz - woz;
                const bb_real lambda_i = smith_lambda(wix, wiy, wiz, a2);
                const bb_real g2_corr = bb_real(1) / (bb_real(1) + lambda_o + lambda_i);
                const bb_real g2_sep = g1o / (bb_real(1) + lambda_i);
                const bb_real g2 = corr > bb_real(0) ? g2_corr : g2_sep;
                const bb_real w = g2 / g1o;
                const bb_real v = wiz > bb_real(0) ? w : bb_real(0);  // below the horizon: 0
                const bool ok = std::isfinite(v);            // NaN/Inf counted, never summed
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

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
using real = float;
#else
using real = double;
#endif

using brdfbake::baseline::reverse_bits;

// The radical inverse in base 2 as a real in [0, 1), as the kernel's bb_unit_from_bits.
inline real radical_inverse(std::uint32_t i) {
#ifdef BB_HOST_REAL_FLOAT
    return real(reverse_bits(i) >> 8) * real(5.9604644775390625e-8);  // 2^-24
#else
    return real(reverse_bits(i)) * real(2.3283064365386963e-10);  // 2^-32
#endif
}

// (x + shift) mod 1 for x, shift in [0, 1).
inline real rotate(real x, real shift) {
    const real u = x + shift;
    return u >= real(1) ? u - real(1) : u;
}

// Smith's Lambda for GGX: (sqrt(1 + a^2 tan^2 theta) - 1) / 2, tan^2 theta = (x^2 + y^2) / z^2.
inline real smith_lambda(real x, real y, real z, real a2) {
    return real(0.5) * (std::sqrt(real(1) + a2 * (x * x + y * y) / (z * z)) - real(1));
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
    const real pi2 = real(6.283185307179586);
#pragma omp parallel for schedule(dynamic, 1)
    for (long item = 0; item < n_items; ++item) {
        const long cell = item / replicas, rep = item - cell * replicas;
        const real a = real(alphas[size_t(cell)]), a2 = a * a;
        const real sh1 = real(shifts[2 * size_t(rep)]), sh2 = real(shifts[2 * size_t(rep) + 1]);
        // wo = (sin theta_o, 0, cos theta_o).
        const real woz = real(mus[size_t(cell)]);
        const real wox = std::sqrt(real(1) - woz * woz > real(0) ? real(1) - woz * woz : real(0)), woy = real(0);
        // Listing 1: the stretched view Vh and its basis T1, T2 (the same for every sample).
        const real vlx = a * wox, vly = a * woy, vlen = std::sqrt(vlx * vlx + vly * vly + woz * woz);
        const real vhx = vlx / vlen, vhy = vly / vlen, vhz = woz / vlen;
        const real lensq = vhx * vhx + vhy * vhy;
        const real inv_len = lensq > real(0) ? real(1) / std::sqrt(lensq) : real(0);
        const real t1x = lensq > real(0) ? -vhy * inv_len : real(1), t1y = lensq > real(0) ? vhx * inv_len : real(0);
        const real t1z = real(0);
        const real t2x = vhy * t1z - vhz * t1y, t2y = vhz * t1x - vhx * t1z, t2z = vhx * t1y - vhy * t1x;
        const real s = real(0.5) * (real(1) + vhz);
        // G1(wo) = 1 / (1 + Lambda(wo)).
        const real lambda_o = smith_lambda(wox, woy, woz, a2);
        const real g1o = real(1) / (real(1) + lambda_o);
        const real corr = correlated ? real(1) : real(0);
        double sum = 0.0, nbad = 0.0;
        for (long b = 0; b < n; b += 512) {
            const long e = n < b + 512 ? n : b + 512;
            real block = 0, block_bad = 0;
#if BASELINE_PLAIN_COS_LOOP
            real cos_phi[512];
#pragma omp simd
            for (long i = b; i < e; ++i)
                cos_phi[i - b] = std::cos(pi2 * rotate(radical_inverse(std::uint32_t(i)), sh2));
#endif
#pragma omp simd reduction(+ : block, block_bad)
            for (long i = b; i < e; ++i) {
                // The rotated Hammersley point.
                const real u1 = rotate((real(i) + real(0.5)) / real(n), sh1);
                const real u2 = rotate(radical_inverse(std::uint32_t(i)), sh2);
                // Listing 1: the disk point, warped to the projected hemisphere.
                const real r = std::sqrt(u1), phi = pi2 * u2;
#if BASELINE_PLAIN_COS_LOOP
                const real t1 = r * cos_phi[i - b];
#else
                const real t1 = r * std::cos(phi);
#endif
                const real t2d = r * std::sin(phi);
                const real h = std::sqrt(real(1) - t1 * t1 > real(0) ? real(1) - t1 * t1 : real(0));
                const real t2 = (real(1) - s) * h + s * t2d;
                const real pz = real(1) - t1 * t1 - t2 * t2;
                const real t3 = std::sqrt(pz > real(0) ? pz : real(0));
                // Reprojection Nh = t1 T1 + t2 T2 + t3 Vh, unstretched and normalised.
                const real nhx = t1 * t1x + t2 * t2x + t3 * vhx;
                const real nhy = t1 * t1y + t2 * t2y + t3 * vhy;
                const real nhz = t1 * t1z + t2 * t2z + t3 * vhz;
                const real nx = a * nhx, ny = a * nhy, nz = nhz > real(0) ? nhz : real(0);
                const real inv_m = real(1) / std::sqrt(nx * nx + ny * ny + nz * nz);
                const real mx = nx * inv_m, my = ny * inv_m, mz = nz * inv_m;
                // Reflection and the weight G2 / G1(wo).
                const real d = wox * mx + woy * my + woz * mz;
                const real wix = real(2) * d * mx - wox, wiy = real(2) * d * my - woy, wiz = real(2) * d * mz - woz;
                const real lambda_i = smith_lambda(wix, wiy, wiz, a2);
                const real g2_corr = real(1) / (real(1) + lambda_o + lambda_i);
                const real g2_sep = g1o / (real(1) + lambda_i);
                const real g2 = corr > real(0) ? g2_corr : g2_sep;
                const real w = g2 / g1o;
                const real v = wiz > real(0) ? w : real(0);  // below the horizon: 0
                const bool ok = std::isfinite(v);            // NaN/Inf counted, never summed
                block_bad += ok ? real(0) : real(1);
                block += ok ? v : real(0);
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

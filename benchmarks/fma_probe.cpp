// FMA-throughput probe: the machine's peak in GFLOP/s, float and double, all cores.
// Each thread runs kChains independent FMA chains (acc = acc * a + b) in the widest vector
// registers -march=native offers, enough to cover the FMA latency times the number of FMA
// units of current x86 cores (4-5 cycles x 2 units). Flops = 2 per lane per FMA.
#include <immintrin.h>

#include <chrono>
#include <cstdint>

#include <omp.h>

#include "baseline.h"

namespace brdfbake {
namespace baseline {
namespace {

constexpr int kChains = 12;

// The float and double vector types of BITS-bit registers, and their FMA and broadcast, from
// the intrinsics' common naming (_mm512_fmadd_ps, _mm256_set1_pd, ...).
#define FMA_PROBE_REGISTERS(BITS)                                                             \
    using VF = __m##BITS;                                                                     \
    using VD = __m##BITS##d;                                                                  \
    constexpr int kBits = BITS;                                                               \
    inline VF fma_f(VF a, VF b, VF c) { return _mm##BITS##_fmadd_ps(a, b, c); }               \
    inline VD fma_d(VD a, VD b, VD c) { return _mm##BITS##_fmadd_pd(a, b, c); }               \
    inline VF set_f(float x) { return _mm##BITS##_set1_ps(x); }                               \
    inline VD set_d(double x) { return _mm##BITS##_set1_pd(x); }

#if defined(__AVX512F__)
FMA_PROBE_REGISTERS(512)
inline float sum_f(VF v) { return _mm512_reduce_add_ps(v); }
inline double sum_d(VD v) { return _mm512_reduce_add_pd(v); }
#elif defined(__FMA__)
FMA_PROBE_REGISTERS(256)
inline float sum_f(VF v) {
    alignas(32) float t[8];
    _mm256_store_ps(t, v);
    float s = 0;
    for (float x : t) s += x;
    return s;
}
inline double sum_d(VD v) {
    alignas(32) double t[4];
    _mm256_store_pd(t, v);
    return t[0] + t[1] + t[2] + t[3];
}
#else
#error "the FMA probe needs an x86 CPU with FMA (compile with -march=native)"
#endif

template <typename V, typename S, typename Fma, typename Set, typename Sum>
double run(double seconds, Fma fma, Set set, Sum sum, volatile double& sink) {
    constexpr int lanes = int(sizeof(V) / sizeof(S));
    const std::int64_t block = 1 << 16;  // iterations between clock reads
    double flops = 0.0, wall = 0.0;
#pragma omp parallel reduction(+ : flops) reduction(max : wall)
    {
        V acc[kChains];
        for (int k = 0; k < kChains; ++k) acc[k] = set(S(1) + S(k) * S(1e-3));
        const V a = set(S(0.999999)), b = set(S(1e-6));
        std::int64_t iters = 0;
        const auto t0 = std::chrono::steady_clock::now();
        double t = 0.0;
        do {
            for (std::int64_t i = 0; i < block; ++i)
                for (int k = 0; k < kChains; ++k) acc[k] = fma(acc[k], a, b);
            iters += block;
            t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        } while (t < seconds);
        S s = 0;
        for (int k = 0; k < kChains; ++k) s += sum(acc[k]);
        sink = sink + double(s);
        flops += 2.0 * lanes * kChains * double(iters);
        wall = t;
    }
    return flops / wall * 1e-9;
}

}  // namespace

Peak fma_peak(double seconds) {
    volatile double sink = 0.0;
    Peak p;
    p.threads = omp_get_max_threads();
    p.vector_bits = kBits;
    // Lambdas (one type each) so that the FMAs are inlined into the chains, not called.
    p.gflops_float = run<VF, float>(
        seconds, [](VF a, VF b, VF c) { return fma_f(a, b, c); }, [](float x) { return set_f(x); },
        [](VF v) { return sum_f(v); }, sink);
    p.gflops_double = run<VD, double>(
        seconds, [](VD a, VD b, VD c) { return fma_d(a, b, c); }, [](double x) { return set_d(x); },
        [](VD v) { return sum_d(v); }, sink);
    return p;
}

}  // namespace baseline
}  // namespace brdfbake

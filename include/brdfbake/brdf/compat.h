/* brdfbake shared-math compatibility layer.
 *
 * Every header in include/brdfbake/brdf/ is written in the subset of C that both C++17 and
 * OpenCL C 1.2 accept, and includes this file first. It defines:
 *   BB_FN        the qualifier of every shared function (inlined on both sides; PoCL leaves
 *                helpers without always_inline as calls)
 *   bb_real      the working type: double on the host (float with -D BB_HOST_REAL_FLOAT); float,
 *                or double with -D BB_REAL_DOUBLE, in kernels; with -D BB_VECTOR_WIDTH=W a vector
 *                of W lanes (float16, double8): one source for scalar and vector kernels
 *   bb_scalar    the element type of bb_real; bb_mask the type of a comparison of reals
 *   bb_first(x), bb_all(m)  the first lane of x and whether every lane of m holds (for values
 *                that are equal in every lane; the value itself in scalar builds)
 *   BB_R(x)       a literal of type bb_real
 *   bb_select(a, b, c)   c ? b : a, branch-free (OpenCL select() semantics)
 *   bb_clamp, bb_min, bb_max, bb_sqrt ...  math that maps to the OpenCL built-ins
 *   bb_vec3      a 3-vector of bb_real with bb_v3, bb_dot, bb_normalize, ...
 * No templates, references, namespaces or overloading in shared code (docs/architecture.md).
 */
#ifndef BRDFBAKE_BRDF_COMPAT_H
#define BRDFBAKE_BRDF_COMPAT_H

#ifdef __OPENCL_C_VERSION__
/* ---------------------------------------------------------------- OpenCL C */
#define BB_FN static inline __attribute__((always_inline))
#define BB_CAT_(a, b) a##b
#define BB_CAT(a, b) BB_CAT_(a, b)
#ifdef BB_REAL_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double bb_scalar;
#define BB_EPS_REAL 2.220446049250313e-16
#define BB_REAL_MAX 1.7976931348623157e308
#else
typedef float bb_scalar;
#define BB_REAL_IS_FLOAT 1
#define BB_EPS_REAL 1.1920929e-7f
#define BB_REAL_MAX 3.4028235e38f
#endif
/* -D BB_VECTOR_WIDTH=W makes `bb_real` an OpenCL vector of W lanes (float16, double8, ...): every
 * shared function then evaluates W samples at once, which PoCL turns into SIMD code (it does not
 * vectorise across scalar work-items whose code calls built-ins). bb_mask is the type of a
 * comparison of reals: int for scalars (0/1), the signed integer vector of the lane size for
 * vectors (0/-1); bb_select treats both alike. */
#ifdef BB_VECTOR_WIDTH
#ifdef BB_REAL_DOUBLE
typedef BB_CAT(double, BB_VECTOR_WIDTH) bb_real;
typedef BB_CAT(long, BB_VECTOR_WIDTH) bb_mask;
#else
typedef BB_CAT(float, BB_VECTOR_WIDTH) bb_real;
typedef BB_CAT(int, BB_VECTOR_WIDTH) bb_mask;
#endif
#define bb_vload(p) BB_CAT(vload, BB_VECTOR_WIDTH)(0, (p))
/* For values and masks that are equal in every lane (a cell's parameters broadcast): the first
 * lane, and whether the mask holds (in every lane). Scalar builds: the value itself. */
#define bb_first(x) ((x).s0)
#define bb_all(m) all(m)
/* Wider vectors than the CPU's registers (float16 on AVX2) make clang warn, once per helper,
 * that passing them "changes the ABI": every helper is inlined (BB_FN), so no call passes one. */
#pragma clang diagnostic ignored "-Wpsabi"
#else
typedef bb_scalar bb_real;
typedef int bb_mask;
#define bb_first(x) (x)
#define bb_all(m) (m)
#endif
#define BB_R(x) ((bb_real)(x))
/* The ternary operator: for vector operands OpenCL C applies it per component, like select(). */
#define bb_select(a, b, c) ((c) ? (b) : (a))
#define bb_sqrt sqrt
#define bb_exp exp
#define bb_log log
#define bb_erf erf
#define bb_pow pow
#define bb_sin sin
#define bb_cos cos
#define bb_atan2 atan2
#define bb_atan atan
#define bb_signbit signbit
#define bb_floor floor
#define bb_fabs fabs
#define bb_fma fma
#define bb_min fmin
#define bb_max fmax
#define bb_clamp(x, lo, hi) clamp((x), (lo), (hi))
#define bb_isfinite(x) isfinite(x)

#else
/* ---------------------------------------------------------------- host C++ */
#include <cmath>
/* double on the host; -D BB_HOST_REAL_FLOAT (a float host build of the shared math)
 * gives float, as a --precision float kernel computes. */
#ifdef BB_HOST_REAL_FLOAT
typedef float bb_real;
#define BB_REAL_IS_FLOAT 1
#define BB_EPS_REAL 1.1920929e-7f
#define BB_REAL_MAX 3.4028235e38f
#else
typedef double bb_real;
#define BB_EPS_REAL 2.220446049250313e-16
#define BB_REAL_MAX 1.7976931348623157e308
#endif
typedef bb_real bb_scalar;
typedef int bb_mask;
#define bb_first(x) (x)
#define bb_all(m) (m)
#define BB_FN static inline
#define BB_R(x) ((bb_real)(x))
/* OpenCL's select(a, b, c) for scalars: c ? b : a */
#define bb_select(a, b, c) ((c) ? (b) : (a))
#define bb_sqrt std::sqrt
#define bb_exp std::exp
#define bb_log std::log
#define bb_erf std::erf
#define bb_pow std::pow
#define bb_sin std::sin
#define bb_cos std::cos
#define bb_atan2 std::atan2
#define bb_atan std::atan
#define bb_signbit std::signbit
#define bb_floor std::floor
#define bb_fabs std::fabs
#define bb_fma std::fma
#define bb_min std::fmin
#define bb_max std::fmax
#define bb_clamp(x, lo, hi) std::fmin(std::fmax((x), (lo)), (hi))
#define bb_isfinite(x) std::isfinite(x)
#endif

#define BB_PI BB_R(3.14159265358979323846)
#define BB_INV_PI BB_R(0.31830988618379067154)
#define BB_2PI BB_R(6.28318530717958647692)

/* A point in the plane (e.g. on the unit disk). */
typedef struct {
    bb_real x, y;
} bb_vec2;

BB_FN bb_vec2 bb_v2(bb_real x, bb_real y) {
    bb_vec2 v = {x, y};
    return v;
}

/* ----------------------------------------------------------- 3-vectors
 * A plain struct rather than OpenCL's real3, so that host and device share the code. */
typedef struct {
    bb_real x, y, z;
} bb_vec3;

BB_FN bb_vec3 bb_v3(bb_real x, bb_real y, bb_real z) {
    bb_vec3 v = {x, y, z};
    return v;
}
BB_FN bb_real bb_dot(bb_vec3 a, bb_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
BB_FN bb_vec3 bb_add(bb_vec3 a, bb_vec3 b) { return bb_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
BB_FN bb_vec3 bb_scale(bb_vec3 a, bb_real s) { return bb_v3(a.x * s, a.y * s, a.z * s); }
BB_FN bb_vec3 bb_cross(bb_vec3 a, bb_vec3 b) {
    return bb_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* Edge-case policy: a zero-length vector normalises to (0,0,0) rather than NaN; callers
 * treat a zero half vector as "no contribution". */
BB_FN bb_vec3 bb_normalize(bb_vec3 a) {
    bb_real len2 = bb_dot(a, a);
    bb_real inv = bb_select(BB_R(0.0), BB_R(1.0) / bb_sqrt(len2), len2 > BB_R(0.0));
    return bb_scale(a, inv);
}

/* ------------------------------------------------------ scalar helpers */
/* sqrt that never returns NaN for a tiny negative argument produced by rounding. */
BB_FN bb_real bb_safe_sqrt(bb_real x) { return bb_sqrt(bb_max(x, BB_R(0.0))); }
BB_FN bb_real bb_sqr(bb_real x) { return x * x; }
/* Cosines are clamped to [-1, 1] everywhere (edge-case policy). */
BB_FN bb_real bb_clamp_cos(bb_real c) { return bb_clamp(c, BB_R(-1.0), BB_R(1.0)); }
/* sin^2 from cos written as (1-c)(1+c): exact near c = 1 where 1 - c*c cancels. */
BB_FN bb_real bb_sin2_from_cos(bb_real c) { return bb_max((BB_R(1.0) - c) * (BB_R(1.0) + c), BB_R(0.0)); }

/* The direction with cos(theta) = mu and azimuth phi in the local frame (n = +z). */
BB_FN bb_vec3 bb_dir_from_mu_phi(bb_real mu, bb_real phi) {
    bb_real s = bb_safe_sqrt(bb_sin2_from_cos(mu));
    return bb_v3(s * bb_cos(phi), s * bb_sin(phi), mu);
}
/* Mirror reflection of w about the unit vector m: 2(w.m)m - w. */
BB_FN bb_vec3 bb_reflect(bb_vec3 w, bb_vec3 m) {
    return bb_add(bb_scale(m, BB_R(2.0) * bb_dot(w, m)), bb_scale(w, BB_R(-1.0)));
}

#if defined(__OPENCL_C_VERSION__) && defined(BB_VECTOR_WIDTH)
/* The vector kernels' sums: per lane, plain sums over blocks of BB_VECTOR_BLOCK steps (at most
 * 32 terms, exact to a few ulps), the blocks added with Kahan compensation; then the reductions
 * over lanes. */
#define BB_VECTOR_BLOCK 32u

/* The sum of the lanes of v - c (a per-lane sum and its Kahan compensation), compensated. */
BB_FN bb_scalar bb_lane_sum(bb_real v, bb_real c) {
    bb_scalar a[BB_VECTOR_WIDTH], b[BB_VECTOR_WIDTH];
    BB_CAT(vstore, BB_VECTOR_WIDTH)(v, 0, a);
    BB_CAT(vstore, BB_VECTOR_WIDTH)(c, 0, b);
    bb_scalar sum = 0, comp = 0;
    for (int k = 0; k < BB_VECTOR_WIDTH; ++k) {
        const bb_scalar y = (a[k] - b[k]) - comp;
        const bb_scalar t = sum + y;
        comp = (t - sum) - y;
        sum = t;
    }
    return sum;
}

/* The sum of the lanes of a per-lane count. */
BB_FN unsigned int bb_lane_count(bb_mask m) {
    unsigned int n[BB_VECTOR_WIDTH], total = 0;
    BB_CAT(vstore, BB_VECTOR_WIDTH)(BB_CAT(convert_uint, BB_VECTOR_WIDTH)(m), 0, n);
    for (int k = 0; k < BB_VECTOR_WIDTH; ++k) total += n[k];
    return total;
}
#endif

/* Kernel helpers both kernel files use (kernels/albedo.cl, kernels/dielectric.cl). */
/* Kahan-compensated accumulation: a float sum of 2^16 terms keeps ~1e-7 relative accuracy. */
#define BB_KAHAN_ADD(sum, comp, x)       \
    do {                                 \
        const bb_real y_ = (x) - (comp);    \
        const bb_real t_ = (sum) + y_;      \
        (comp) = (t_ - (sum)) - y_;      \
        (sum) = t_;                      \
    } while (0)

/* The length of a rule's array of nodes: padded to a multiple of the vector width. */
#ifdef BB_VECTOR_WIDTH
#define BB_QUAD_PADDED(m) (((m) + BB_VECTOR_WIDTH - 1u) / BB_VECTOR_WIDTH * BB_VECTOR_WIDTH)
#else
#define BB_QUAD_PADDED(m) (m)
#endif

/* The nodes and weights of rule `rule` (0 fine, 1 coarse, 2 coarsest) in the host's node table:
 * each rule's nodes then its weights, each padded to the vector width. */
#define BB_QUAD_RULE_NODES(nodes, rule, n_fine, n_coarse)                                   \
    ((nodes) + ((rule) == 0u ? 0u                                                           \
                             : ((rule) == 1u ? 2u * BB_QUAD_PADDED(n_fine)                  \
                                             : 2u * (BB_QUAD_PADDED(n_fine) + BB_QUAD_PADDED(n_coarse)))))

#endif /* BRDFBAKE_BRDF_COMPAT_H */

/* Fresnel reflectance terms, shared by host and kernels.
 *
 * A Fresnel term is a kind (BB_FRESNEL_*) and a parameter block; bb_fresnel_eval dispatches on
 * the kind. Kernels pass a compile-time constant kind, so the switch folds away.
 *
 * Conventions. cos_theta is the cosine between the direction and the (micro)surface normal.
 * eta (and k) is the index of the far side relative to the side the light arrives from:
 * eta = 1.5 is glass seen from air, eta = 1/1.5 the same interface seen from inside the glass,
 * eta + ik a metal seen from air. Rs is the reflectance of s-polarised light (electric field
 * perpendicular to the plane of incidence, "r_perp"), Rp of p-polarised light ("r_par");
 * the unpolarised reflectance is F = (Rs + Rp)/2.
 *
 * Edge-case policy (written once, here):
 *   - cos_theta is clamped to [-1, 1]. A dielectric seen with cos_theta < 0 is seen from the
 *     other side (eta -> 1/eta, cos -> |cos|), as in pbrt-v4 FrDielectric. Conductors clamp
 *     cos_theta to [0, 1] (light does not arrive from inside a metal), as pbrt-v4 FrComplex.
 *   - Total internal reflection returns Rs = Rp = F = 1.
 *   - An index of exactly 1 (eta = 1, k = 0) returns 0 at every angle, grazing included, for
 *     the exact forms.
 *   - F -> 1 at grazing incidence (cos_theta = 0) for every other index.
 *   - Every value is finite for eta in [1e-4, 1e4] and k in [0, 1e3] in float and double: the
 *     exact forms are written with squared magnitudes of moderate size only (|n^2| <= ~1e8).
 *
 * References:
 *   [BW]   Born & Wolf, "Principles of Optics", 7th ed., sec. 1.5.2 eq. 21 (amplitude
 *          coefficients for dielectrics), sec. 14.2 (absorbing media: the complex index
 *          n = eta + ik replaces eta, cos_theta_t becomes complex).
 *   [PBR4] Pharr, Jakob, Humphreys, "Physically Based Rendering", 4th ed., sec. 9.3.5-9.3.6
 *          (FrDielectric, FrComplex).
 *   [PBR2] Pharr & Humphreys, "Physically Based Rendering", 2nd ed., sec. 8.2.1 eq. 8.3
 *          (FrCond: the approximate conductor reflectance of the course notes).
 *   [S94]  Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 24.
 *   [H19]  Hoffman 2019, "Fresnel Equations Considered Harmful" (MAM workshop): Schlick's form
 *          with a free F90 and exponent, and the F82 edge term that fits metals' dip near 82 deg.
 *   [K21]  Kutz, Hasan, Edmondson 2021, "Novel aspects of the Adobe Standard Material" (Adobe
 *          technical report): F82-tint, which the OpenPBR Surface specification adopts for metals.
 *   Thin-film interference (the Airy sum over one film) is in thin_film.h [BW 1.6.4; Belcour &
 *   Barla 2017].
 */
#ifndef BRDFBAKE_BRDF_FRESNEL_H
#define BRDFBAKE_BRDF_FRESNEL_H

#include "brdfbake/brdf/params.h"

#define BB_FRESNEL_NONE 0
#define BB_FRESNEL_SCHLICK 1
#define BB_FRESNEL_DIELECTRIC 2
#define BB_FRESNEL_CONDUCTOR 3
#define BB_FRESNEL_CONDUCTOR_APPROX 4
#define BB_FRESNEL_GEN_SCHLICK 5
#define BB_FRESNEL_GEN_SCHLICK_IOR 6
#define BB_FRESNEL_THIN_FILM 7 /* one film on a substrate at one wavelength: thin_film.h */
#define BB_FRESNEL_TABLE 8     /* a curve F(cos) tabulated by the host (a colour channel): below */

/* Parameter slots. */
#define BB_SCHLICK_F0 0
#define BB_FRESNEL_ETA 0 /* dielectric, conductor, conductor-approx: real part of the index */
#define BB_FRESNEL_K 1   /* conductor, conductor-approx: extinction coefficient k >= 0 */
/* dielectric: eta - 1, computed where eta is exact (the host, in double), or 0: then the
 * functions compute it from eta. float cannot hold an eta close to 1 (1.0001f = 1 + 1.00017e-4,
 * 1.7e-4 off in eta - 1, and F ~ (eta - 1)^2); its distance from 1 it holds exactly. */
#define BB_FRESNEL_ETA_M1 1
/* generalized Schlick (and F82-tint): F = f0 + (f90 - f0)(1 - cos)^exponent - b cos (1 - cos)^6 */
#define BB_GEN_SCHLICK_F0 0
#define BB_GEN_SCHLICK_F90 1
#define BB_GEN_SCHLICK_EXPONENT 2
#define BB_GEN_SCHLICK_B 3
/* generalized Schlick driven by a dielectric (f0 and f90 in slots 0 and 1):
 * F = f0 + (f90 - f0) clamp((F_dielectric(cos, eta) - F0) / (1 - F0), 0, 1) */
#define BB_GEN_SCHLICK_IOR_ETA 2
#define BB_GEN_SCHLICK_IOR_ETA_M1 3 /* eta - 1, exact (see BB_FRESNEL_ETA_M1) */

/* The two polarised reflectances of one evaluation. */
typedef struct {
    bb_real rs; /* s-polarised (perpendicular, TE) */
    bb_real rp; /* p-polarised (parallel, TM) */
} bb_fresnel_sp;

BB_FN bb_fresnel_sp bb_make_fresnel_sp(bb_real rs, bb_real rp) {
    bb_fresnel_sp r = {rs, rp};
    return r;
}

/* num / den, or `fallback` where den is 0 (a 0/0 that the caller's limit defines). */
BB_FN bb_real bb_ratio_or(bb_real num, bb_real den, bb_real fallback) {
    return bb_select(num / bb_select(den, BB_R(1.0), den == BB_R(0.0)), fallback, den == BB_R(0.0));
}

/* ------------------------------------------------------------------ Schlick */

/* [S94] eq. 24: F = F0 + (1 - F0)(1 - cos)^5. Relative error against the exact dielectric below
 * 1% for eta in [1.3, 1.7] away from grazing; no polarisation, so Rs = Rp = F. */
BB_FN bb_real bb_fresnel_schlick(bb_real cos_theta, bb_real f0) {
    bb_real m = bb_clamp(BB_R(1.0) - cos_theta, BB_R(0.0), BB_R(1.0));
    bb_real m2 = m * m;
    return f0 + (BB_R(1.0) - f0) * (m2 * m2 * m);
}

/* ------------------------------------------------------ generalized Schlick */

/* Schlick's form with a free f90 and exponent (Blender Cycles' generalized Schlick) and the F82
 * edge term of [H19] and [K21]:
 *   F = f0 + (f90 - f0)(1 - cos)^exponent - b cos (1 - cos)^6.
 * Linear in f0, f90 and b, so a table of the lobe weighted by (1 - cos)^exponent (f0 = 0,
 * f90 = 1) and by cos (1 - cos)^6 serves every colour. Not clamped: an F82-tint term with a
 * small f0 can go below 0, which resolve_fresnel rejects for the f82-tint spelling. exponent = 0
 * gives f90 at every angle (pow(0, 0) = 1); cos is clamped to [0, 1]. */
BB_FN bb_real bb_fresnel_gen_schlick(bb_real cos_theta, bb_real f0, bb_real f90, bb_real exponent, bb_real b) {
    bb_real m = bb_clamp(BB_R(1.0) - cos_theta, BB_R(0.0), BB_R(1.0));
    bb_real m3 = m * m * m;
    return f0 + (f90 - f0) * bb_pow(m, exponent) - b * (BB_R(1.0) - m) * (m3 * m3);
}

/* F82-tint [K21; H19]: the b of bb_fresnel_gen_schlick (f90 = 1, exponent 5) that makes F at
 * mu_bar = 1/7 (about 82 deg) tint times Schlick's value there:
 *   b = (1 - tint) F_schlick(mu_bar) / (mu_bar (1 - mu_bar)^6). */
BB_FN bb_real bb_f82_tint_b(bb_real f0, bb_real tint) {
    bb_real mu_bar = BB_R(1.0) / BB_R(7.0), m = BB_R(1.0) - mu_bar;
    bb_real m3 = m * m * m;
    return (BB_R(1.0) - tint) * bb_fresnel_schlick(mu_bar, f0) / (mu_bar * m3 * m3);
}

/* --------------------------------------------------------- exact dielectric */

/* Rs and Rp of a dielectric interface with relative index eta > 0 [BW eq. 21; PBR4 9.3.5]:
 *   r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t),  r_p = (eta cos_i - cos_t) / (eta cos_i + cos_t),
 * with Snell's law sin_t = sin_i / eta. With w = eta cos_t = sqrt(eta^2 - sin_i^2) =
 * sqrt(d + cos_i^2), d = (eta - 1)(eta + 1), the numerators are rewritten free of cancellation
 * (they vanish as eta -> 1, and r_p at Brewster's angle):
 *   cos_i - w = -d / (cos_i + w)                      =>  r_s = -d / (cos_i + w)^2,
 *   eta^2 cos_i - w = d ((eta^2 + 1) cos_i^2 - 1) / (eta^2 cos_i + w)
 *                                                     =>  r_p = d ((eta^2 + 1) cos_i^2 - 1) / (eta^2 cos_i + w)^2
 * (r_p multiplied through by eta). Total internal reflection (d + cos_i^2 <= 0) gives 1,
 * eta = 1 gives 0. */
BB_FN bb_fresnel_sp bb_fresnel_dielectric_sp_m1(bb_real cos_theta, bb_real eta, bb_real eta_m1) {
    bb_real c = bb_clamp_cos(cos_theta);
    /* Seen from the other side: invert the relative index [PBR4 FrDielectric];
     * 1/eta - 1 = -(eta - 1)/eta. */
    bb_mask back = c < BB_R(0.0);
    bb_real e = bb_select(eta, BB_R(1.0) / eta, back);
    bb_real em1 = bb_select(eta_m1, -eta_m1 / eta, back);
    c = bb_fabs(c);
    bb_real d = em1 * (e + BB_R(1.0)); /* eta^2 - 1, exact near eta = 1 */
    bb_real q = d + c * c;                         /* eta^2 - sin_i^2 = (eta cos_t)^2 */
    bb_real w = bb_safe_sqrt(q);                   /* eta cos_t */
    bb_real e2 = e * e;
    bb_real ds = c + w, dp = e2 * c + w;
    bb_real rs = bb_ratio_or(-d, ds * ds, BB_R(0.0));
    bb_real rp = bb_ratio_or(d * ((e2 + BB_R(1.0)) * c * c - BB_R(1.0)), dp * dp, BB_R(0.0));
    bb_mask tir = q <= BB_R(0.0);
    bb_mask unit = em1 == BB_R(0.0);
    /* |r| <= 1 exactly, but near grazing (cos_i -> 0) (cos_i + w)^2 -> w^2 = d only up to the
     * rounding of w = sqrt(d + cos_i^2): |r| may round to 1 + 2 ulp. Clamp to 1. */
    bb_real Rs = bb_select(bb_select(bb_min(rs * rs, BB_R(1.0)), BB_R(1.0), tir), BB_R(0.0), unit);
    bb_real Rp = bb_select(bb_select(bb_min(rp * rp, BB_R(1.0)), BB_R(1.0), tir), BB_R(0.0), unit);
    return bb_make_fresnel_sp(Rs, Rp);
}

/* The same with eta - 1 computed from eta. */
BB_FN bb_fresnel_sp bb_fresnel_dielectric_sp(bb_real cos_theta, bb_real eta) {
    return bb_fresnel_dielectric_sp_m1(cos_theta, eta, eta - BB_R(1.0));
}

BB_FN bb_real bb_fresnel_dielectric_rs(bb_real cos_theta, bb_real eta) {
    return bb_fresnel_dielectric_sp(cos_theta, eta).rs;
}
BB_FN bb_real bb_fresnel_dielectric_rp(bb_real cos_theta, bb_real eta) {
    return bb_fresnel_dielectric_sp(cos_theta, eta).rp;
}
/* Unpolarised: F = (Rs + Rp) / 2. */
BB_FN bb_real bb_fresnel_dielectric(bb_real cos_theta, bb_real eta) {
    bb_fresnel_sp r = bb_fresnel_dielectric_sp(cos_theta, eta);
    return BB_R(0.5) * (r.rs + r.rp);
}

/* The exact dielectric's curve between its own F0 = ((eta - 1)/(eta + 1))^2 and 1, remapped to
 * f0..f90 (Blender Cycles' generalized Schlick with a negative exponent, the Principled BSDF's
 * dielectric specular: intern/cycles/kernel/closure/bsdf_microfacet.h). The weight is clamped to
 * [0, 1] as Cycles clamps it: a high index's unpolarised F dips below its F0 before Brewster's
 * angle. */
BB_FN bb_real bb_fresnel_gen_schlick_ior(bb_real cos_theta, bb_real f0, bb_real f90, bb_real eta, bb_real eta_m1) {
    bb_fresnel_sp r = bb_fresnel_dielectric_sp_m1(cos_theta, eta, eta_m1);
    bb_real q = eta_m1 / (eta + BB_R(1.0)); /* (eta - 1)/(eta + 1), exact near eta = 1 */
    bb_real F0 = q * q;
    bb_real w = bb_clamp((BB_R(0.5) * (r.rs + r.rp) - F0) / (BB_R(1.0) - F0), BB_R(0.0), BB_R(1.0));
    return f0 + (f90 - f0) * w;
}

/* ---------------------------------------------------------- exact conductor */

/* A complex number, for the conductor only. */
typedef struct {
    bb_real re, im;
} bb_complex;

/* The square root of z = a + ib on the branch with Im >= 0 (and Re >= 0), the physical one for
 * the transmitted wave n cos_t in an absorbing medium (it decays into the metal) [BW 14.2].
 * For Im(z) >= 0 this is the principal root; taking |b| makes a signed zero in b (a negative
 * real z, total internal reflection of a k = 0 "conductor") land on +i sqrt(-a) instead of
 * depending on the sign of zero. Written without a branch on the sign of a:
 *   t = sqrt((|z| + |a|)/2),  sqrt(z) = (t, |b|/(2t)) for a >= 0, (|b|/(2t), t) for a < 0,
 * which avoids the cancellation of |z| - |a| (Kahan, "Branch cuts for complex elementary
 * functions", 1987). z = 0 gives 0. */
BB_FN bb_complex bb_complex_sqrt_upper(bb_real a, bb_real b) {
    bb_real ab = bb_fabs(b);
    bb_real mag = bb_sqrt(a * a + ab * ab);
    bb_real t = bb_sqrt(BB_R(0.5) * (mag + bb_fabs(a)));
    bb_real other = bb_ratio_or(ab, BB_R(2.0) * t, BB_R(0.0));
    bb_mask pos = a >= BB_R(0.0);
    bb_complex root = {bb_select(other, t, pos), bb_select(t, other, pos)};
    return root;
}

/* Rs and Rp of a conductor with complex relative index n = eta + ik (eta > 0, k >= 0)
 * [BW 14.2; PBR4 9.3.6 FrComplex]: the dielectric formulas with complex n,
 *   r_s = (cos_i - n cos_t) / (cos_i + n cos_t),
 *   r_p = (n cos_i - cos_t) / (n cos_i + cos_t) = (n^2 cos_i - n cos_t) / (n^2 cos_i + n cos_t),
 * where w = n cos_t = sqrt(n^2 - sin_i^2) on the branch of bb_complex_sqrt_upper, and
 *   n^2 - sin_i^2 = ((eta - 1)(eta + 1) - k^2 + cos_i^2) + i 2 eta k,
 * the real part written with (eta - 1)(eta + 1) to keep eta near 1 accurate. Then
 *   Rs = |cos_i - w|^2 / |cos_i + w|^2,  Rp = |n^2 cos_i - w|^2 / |n^2 cos_i + w|^2.
 * For k = 0 this is the exact dielectric, total internal reflection included. */
BB_FN bb_fresnel_sp bb_fresnel_conductor_sp(bb_real cos_theta, bb_real eta, bb_real k) {
    bb_real c = bb_clamp(cos_theta, BB_R(0.0), BB_R(1.0));
    bb_real n2_re = (eta - k) * (eta + k); /* Re n^2 = eta^2 - k^2 */
    bb_real n2_im = BB_R(2.0) * eta * k;   /* Im n^2 */
    bb_complex w = bb_complex_sqrt_upper((eta - BB_R(1.0)) * (eta + BB_R(1.0)) - k * k + c * c, n2_im);
    /* Rs */
    /* Both ratios are <= 1 exactly (Re w >= 0, and Re(n^2 cos_i conj(w)) >= 0 for a passive
     * medium), but at grazing numerator and denominator agree to rounding and the ratio may be
     * 1 + 2 ulp: clamp to 1. */
    bb_real dm = c - w.re, dp = c + w.re, w_im2 = w.im * w.im;
    bb_real Rs = bb_min(bb_ratio_or(dm * dm + w_im2, dp * dp + w_im2, BB_R(0.0)), BB_R(1.0));
    /* Rp */
    bb_real a_re = n2_re * c, a_im = n2_im * c; /* n^2 cos_i */
    bb_real pm_re = a_re - w.re, pm_im = a_im - w.im;
    bb_real pp_re = a_re + w.re, pp_im = a_im + w.im;
    bb_real Rp = bb_min(bb_ratio_or(pm_re * pm_re + pm_im * pm_im, pp_re * pp_re + pp_im * pp_im, BB_R(0.0)), BB_R(1.0));
    return bb_make_fresnel_sp(Rs, Rp);
}

BB_FN bb_real bb_fresnel_conductor_rs(bb_real cos_theta, bb_real eta, bb_real k) {
    return bb_fresnel_conductor_sp(cos_theta, eta, k).rs;
}
BB_FN bb_real bb_fresnel_conductor_rp(bb_real cos_theta, bb_real eta, bb_real k) {
    return bb_fresnel_conductor_sp(cos_theta, eta, k).rp;
}
BB_FN bb_real bb_fresnel_conductor(bb_real cos_theta, bb_real eta, bb_real k) {
    bb_fresnel_sp r = bb_fresnel_conductor_sp(cos_theta, eta, k);
    return BB_R(0.5) * (r.rs + r.rp);
}

#include "brdfbake/brdf/thin_film.h"

/* ---------------------------------------------------- approximate conductor */

/* The closed form of the course notes [PBR2 eq. 8.3, FrCond], which drops the sin^2 terms
 * of the exact expressions (so it is exact at normal incidence and at grazing):
 *   r_perp = ((eta^2 + k^2) - 2 eta cos + cos^2) / ((eta^2 + k^2) + 2 eta cos + cos^2),
 *   r_par  = ((eta^2 + k^2) cos^2 - 2 eta cos + 1) / ((eta^2 + k^2) cos^2 + 2 eta cos + 1),
 *   F = (r_perp + r_par) / 2.
 * Error: good for metals (eta^2 + k^2 >> 1): for aluminium at 550 nm (Rakic 1995) the largest
 * |F - F_exact| is 2.3e-3, at 78 deg; gold, silver, copper at 550 nm 5.9e-3, 0.8e-3, 7.1e-3
 * (docs/fresnel.md). Poor for dielectrics: 0.099 off for eta = 1.5, not 0 for eta = 1, and
 * no total internal reflection. cos is clamped to [0, 1].
 * The numerators are evaluated as sums of squares, (eta^2 + k^2) - 2 eta cos + cos^2 =
 * (eta - cos)^2 + k^2 and (eta^2 + k^2) cos^2 - 2 eta cos + 1 = (eta cos - 1)^2 + (k cos)^2 (the
 * denominators likewise with +): the expanded forms cancel where a numerator vanishes (k = 0 and
 * cos = eta, or cos = 1/eta) and there rounded to small negative values (-1e-16 in double,
 * -6e-8 in float). The sums of squares are >= 0 and each numerator <= its denominator in
 * floating point, so both values lie in [0, 1]. */
BB_FN bb_fresnel_sp bb_fresnel_conductor_approx_sp(bb_real cos_theta, bb_real eta, bb_real k) {
    bb_real c = bb_clamp(cos_theta, BB_R(0.0), BB_R(1.0));
    bb_real k2 = k * k, kc2 = bb_sqr(k * c);
    bb_real r_perp = (bb_sqr(eta - c) + k2) / (bb_sqr(eta + c) + k2);
    bb_real r_par = (bb_sqr(eta * c - BB_R(1.0)) + kc2) / (bb_sqr(eta * c + BB_R(1.0)) + kc2);
    return bb_make_fresnel_sp(r_perp, r_par);
}

BB_FN bb_real bb_fresnel_conductor_approx(bb_real cos_theta, bb_real eta, bb_real k) {
    bb_fresnel_sp r = bb_fresnel_conductor_approx_sp(cos_theta, eta, k);
    return BB_R(0.5) * (r.rs + r.rp);
}

/* ------------------------------------------------------------ tabulated curve */

/* A Fresnel curve the host tabulates: one colour channel of a spectral term, F_c(cos) =
 * sum_lambda w_c(lambda) F(lambda, cos) (host/tables/spectral_fresnel.cpp). The albedo is linear
 * in F and F depends on the angle alone, so the albedo at F_c is the channel of the spectral
 * integral of the albedo: three integrations, not one per wavelength. F_c is not clamped: a
 * colour outside the gamut (gold's linear-sRGB red, 1.04 at normal incidence) goes beyond
 * [0, 1]. The n node values (at cos_i = i / (n - 1), i = 0 .. n - 1) are in the model data
 * (BB_MODEL_DATA_ARG), from number BB_FRESNEL_TABLE_ALIGN * fp.v[BB_FRESNEL_TABLE_BLOCK] on
 * (an offset in blocks, so that float parameters hold it exactly); F is their piecewise-linear
 * interpolant, whose error the host measures. Unpolarised: Rs = Rp = F. cos is clamped to [0, 1]. */
#define BB_FRESNEL_TABLE_NODES 0 /* n >= 2 */
#define BB_FRESNEL_TABLE_BLOCK 1 /* where node 0 is, in blocks of BB_FRESNEL_TABLE_ALIGN numbers */
#define BB_FRESNEL_TABLE_ID 2    /* the host's hash of the values: curves differ in their parameters */
#define BB_FRESNEL_TABLE_ALIGN 64

/* The interpolant at one (scalar) cosine, from the node values y[0 .. n - 1]. */
#ifdef __OPENCL_C_VERSION__
BB_FN bb_scalar bb_fresnel_table_at(bb_scalar cos_theta, int n, __global const bb_scalar* y) {
#else
BB_FN bb_scalar bb_fresnel_table_at(bb_scalar cos_theta, int n, const double* y) {
#endif
    bb_scalar t = (cos_theta < (bb_scalar)0 ? (bb_scalar)0 : (cos_theta > (bb_scalar)1 ? (bb_scalar)1 : cos_theta)) *
                  (bb_scalar)(n - 1);
    int i = (int)t;
    i = i > n - 2 ? n - 2 : i;
    bb_scalar f = t - (bb_scalar)i;
    return y[i] + (y[i + 1] - y[i]) * f;
}

#ifdef __OPENCL_C_VERSION__
/* F at cos_theta from the model data: per lane in a vector build (a gather). */
BB_FN bb_real bb_fresnel_table(bb_real cos_theta, bb_params fp) {
    int n = (int)bb_first(fp.v[BB_FRESNEL_TABLE_NODES]);
    __global const bb_scalar* y =
        fp.data + (size_t)bb_first(fp.v[BB_FRESNEL_TABLE_BLOCK]) * (size_t)BB_FRESNEL_TABLE_ALIGN;
#ifdef BB_VECTOR_WIDTH
    bb_scalar lanes[BB_VECTOR_WIDTH];
    BB_CAT(vstore, BB_VECTOR_WIDTH)(cos_theta, 0, lanes);
    for (int l = 0; l < BB_VECTOR_WIDTH; ++l) lanes[l] = bb_fresnel_table_at(lanes[l], n, y);
    return BB_CAT(vload, BB_VECTOR_WIDTH)(0, lanes);
#else
    return bb_fresnel_table_at(cos_theta, n, y);
#endif
}
#endif

/* ---------------------------------------------------------------- dispatch */

/* Rs and Rp for the given kind. The unpolarised kinds (none, Schlick) return Rs = Rp = F.
 * Unknown kinds behave as none (1). */
BB_FN bb_fresnel_sp bb_fresnel_eval_sp(int kind, bb_params fp, bb_real cos_theta) {
    switch (kind) {
    case BB_FRESNEL_SCHLICK: {
        bb_real f = bb_fresnel_schlick(cos_theta, fp.v[BB_SCHLICK_F0]);
        return bb_make_fresnel_sp(f, f);
    }
    case BB_FRESNEL_DIELECTRIC:
        return bb_fresnel_dielectric_sp_m1(
            cos_theta, fp.v[BB_FRESNEL_ETA],
            bb_select(fp.v[BB_FRESNEL_ETA] - BB_R(1.0), fp.v[BB_FRESNEL_ETA_M1], fp.v[BB_FRESNEL_ETA_M1] != BB_R(0.0)));
    case BB_FRESNEL_CONDUCTOR:
        return bb_fresnel_conductor_sp(cos_theta, fp.v[BB_FRESNEL_ETA], fp.v[BB_FRESNEL_K]);
    case BB_FRESNEL_CONDUCTOR_APPROX:
        return bb_fresnel_conductor_approx_sp(cos_theta, fp.v[BB_FRESNEL_ETA], fp.v[BB_FRESNEL_K]);
    case BB_FRESNEL_GEN_SCHLICK: {
        bb_real f = bb_fresnel_gen_schlick(cos_theta, fp.v[BB_GEN_SCHLICK_F0], fp.v[BB_GEN_SCHLICK_F90],
                                        fp.v[BB_GEN_SCHLICK_EXPONENT], fp.v[BB_GEN_SCHLICK_B]);
        return bb_make_fresnel_sp(f, f);
    }
    case BB_FRESNEL_GEN_SCHLICK_IOR: {
        bb_real f = bb_fresnel_gen_schlick_ior(cos_theta, fp.v[BB_GEN_SCHLICK_F0], fp.v[BB_GEN_SCHLICK_F90],
                                            fp.v[BB_GEN_SCHLICK_IOR_ETA], fp.v[BB_GEN_SCHLICK_IOR_ETA_M1]);
        return bb_make_fresnel_sp(f, f);
    }
    case BB_FRESNEL_THIN_FILM:
        return bb_fresnel_thin_film_sp(cos_theta, fp.v[BB_THIN_FILM_ETA], fp.v[BB_THIN_FILM_K],
                                       fp.v[BB_THIN_FILM_THICKNESS], fp.v[BB_THIN_FILM_BASE_ETA],
                                       fp.v[BB_THIN_FILM_BASE_K], fp.v[BB_THIN_FILM_WAVELENGTH]);
#ifdef __OPENCL_C_VERSION__
    case BB_FRESNEL_TABLE: { /* the host has no model data here: it reads FresnelConfig::curve */
        bb_real f = bb_fresnel_table(cos_theta, fp);
        return bb_make_fresnel_sp(f, f);
    }
#endif
    default:
        return bb_make_fresnel_sp(BB_R(1.0), BB_R(1.0));
    }
}

BB_FN bb_real bb_fresnel_eval_rs(int kind, bb_params fp, bb_real cos_theta) {
    return bb_fresnel_eval_sp(kind, fp, cos_theta).rs;
}
BB_FN bb_real bb_fresnel_eval_rp(int kind, bb_params fp, bb_real cos_theta) {
    return bb_fresnel_eval_sp(kind, fp, cos_theta).rp;
}

/* F(cos_theta) for the given kind: (Rs + Rp)/2, or F itself for the unpolarised kinds. */
BB_FN bb_real bb_fresnel_eval(int kind, bb_params fp, bb_real cos_theta) {
    switch (kind) {
    case BB_FRESNEL_NONE:
        return BB_R(1.0);
    case BB_FRESNEL_SCHLICK:
        return bb_fresnel_schlick(cos_theta, fp.v[BB_SCHLICK_F0]);
    case BB_FRESNEL_GEN_SCHLICK:
        return bb_fresnel_gen_schlick(cos_theta, fp.v[BB_GEN_SCHLICK_F0], fp.v[BB_GEN_SCHLICK_F90],
                                      fp.v[BB_GEN_SCHLICK_EXPONENT], fp.v[BB_GEN_SCHLICK_B]);
    case BB_FRESNEL_GEN_SCHLICK_IOR:
        return bb_fresnel_gen_schlick_ior(cos_theta, fp.v[BB_GEN_SCHLICK_F0], fp.v[BB_GEN_SCHLICK_F90],
                                          fp.v[BB_GEN_SCHLICK_IOR_ETA], fp.v[BB_GEN_SCHLICK_IOR_ETA_M1]);
    default: {
        bb_fresnel_sp r = bb_fresnel_eval_sp(kind, fp, cos_theta);
        return BB_R(0.5) * (r.rs + r.rp);
    }
    }
}

#endif /* BRDFBAKE_BRDF_FRESNEL_H */

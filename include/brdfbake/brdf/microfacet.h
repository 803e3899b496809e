/* Microfacet distributions and Smith masking-shadowing, shared by host and kernels.
 *
 * Distributions (all anisotropic with roughness alpha_x, alpha_y along the local x and y axes;
 * the isotropic model is alpha_x = alpha_y), each with D, Smith Lambda/G1 where it has one, and a
 * sampler:
 *   - Trowbridge-Reitz (GGX): D, Lambda, G1, G2, visible-normal sampling [H18], D cos sampling.
 *   - Beckmann: D, Lambda (erf form), G1, G2, visible-normal sampling [HD14, J14], D cos sampling.
 *   - normalised Blinn (exponent N, isotropic): D and D cos sampling [B77, WMLT07 eq. 30].
 * References:
 *   [B77]    Blinn, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH 1977.
 *   [WMLT07] Walter, Marschner, Li, Torrance, "Microfacet Models for Refraction through Rough
 *            Surfaces", EGSR 2007 (eq. 25-27: Beckmann D and G1, eq. 28: Beckmann sampling,
 *            eq. 30: Phong/Blinn D, eq. 33: GGX D, eq. 34: GGX G1, eq. 35-36: GGX sampling).
 *   [H14]    Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
 *            JCGT 3(2), 2014 (eq. 72 and 86: anisotropic Lambda of Beckmann and GGX; eq. 80:
 *            projected roughness; eq. 98/99: separable and height-correlated G2).
 *   [HD14]   Heitz, d'Eon, "Importance Sampling Microfacet-Based BSDFs using the Distribution of
 *            Visible Normals", EGSR 2014 (sec. 4: stretch, sample the slopes of the unit
 *            configuration, rotate, unstretch).
 *   [J14]    Jakob, "An Improved Visible Normal Sampling Routine for the Beckmann Distribution",
 *            technical note, 2014 (the slope CDF in the erf domain, the initial guess and the
 *            bracketed Newton iteration used below).
 *   [H18]    Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018.
 *   [G10]    Giles, "Approximating the erfinv function", GPU Computing Gems Jade, 2010.
 *   [D17]    Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
 *
 * Edge-case policy (written once, here, for every microfacet-style model):
 *   - D = 0 for back-facing microfacets (m.z <= 0); a model returns 0 when wo or wi is at or
 *     below the horizon, and for a zero half vector (bb_normalize returns 0, so m.z = 0).
 *   - G1 = 0 at and below the horizon, G1 = 1 exactly at normal incidence; G2 forms reach 0,
 *     never NaN, at the horizon.
 *   - Grazing: no tan(theta) = sin/cos anywhere; D and Lambda are written with the squared
 *     components ((m.x/ax)^2 + (m.y/ay)^2) / m.z^2, which is finite for every m.z > 0.
 *   - cos^4 underflow: Beckmann's exp(-s/m.z^2) / m.z^4 returns 0 wherever the exponential
 *     underflows, so that 0/0 never occurs (the exponential underflows long before m.z^4).
 *   - Huge exponents (Blinn, Phong up to N = 1e4): cos^N is evaluated as exp(N log1p(-d)) with
 *     d = 1 - cos computed without cancellation ((m.x^2 + m.y^2)/(1 + m.z) for a unit m), and
 *     its samplers take cos = exp(log1p(-u)/(N+1)), sin^2 = -expm1(2 log1p(-u)/(N+1)), which
 *     keeps sin(theta) accurate in float where 1 - cos^2 would be 0.
 *   - alpha floor: every function is finite for alpha >= BB_ALPHA_MIN; the host refuses
 *     smaller alpha (a smooth surface is the `mirror` model).
 *   - Uniform numbers u may be 0 and approach 1; samplers map them through 1 - u, never log(0). */
#ifndef BRDFBAKE_BRDF_MICROFACET_H
#define BRDFBAKE_BRDF_MICROFACET_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Built-ins that compat.h does not (yet) name; both OpenCL C and <cmath> have them. */
#ifdef __OPENCL_C_VERSION__
#ifndef bb_erfc
#define bb_erfc erfc
#endif
#ifndef bb_expm1
#define bb_expm1 expm1
#endif
#ifndef bb_log1p
#define bb_log1p log1p
#endif
#else
#ifndef bb_erfc
#define bb_erfc std::erfc
#endif
#ifndef bb_expm1
#define bb_expm1 std::expm1
#endif
#ifndef bb_log1p
#define bb_log1p std::log1p
#endif
#endif

#define BB_SQRT_PI BB_R(1.77245385090551602730)
#define BB_INV_SQRT_PI BB_R(0.56418958354775628695)

/* ------------------------------------------------------------ shared helpers */

/* (1 - d)^e for d in [0, 1] and e >= 0, as exp(e log1p(-d)): accurate for d near 0 where
 * pow(1 - d, e) would first round 1 - d (the relative error of pow(c, e) is e times that of c,
 * 1e-3 in float for e = 1e4). Returns 0 for d >= 1 (the lobe's cosine is <= 0), also for e = 0. */
BB_FN bb_real bb_pow1m(bb_real d, bb_real e) {
    bb_real dd = bb_min(d, BB_R(1.0));
    bb_real l = bb_log1p(-bb_select(dd, BB_R(0.0), dd >= BB_R(1.0)));
    return bb_select(BB_R(0.0), bb_exp(e * l), d < BB_R(1.0));
}

/* 1 - m.z for a unit vector m with m.z > -1, as (m.x^2 + m.y^2) / (1 + m.z): no cancellation
 * near the pole, where 1 - m.z loses every digit of a narrow lobe. */
BB_FN bb_real bb_one_minus_z(bb_vec3 m) {
    return (m.x * m.x + m.y * m.y) / (BB_R(1.0) + bb_max(m.z, BB_R(0.0)));
}

/* A direction about +z with density (e + 1)/(2 pi) cos^e(theta) (the cosine-power lobe of
 * Phong and Blinn [WMLT07 eq. 30 with e = N + 1 for D cos]): cos = (1 - u1)^(1/(e+1)),
 * sin^2 = 1 - (1 - u1)^(2/(e+1)) = -expm1(2 log1p(-u1)/(e+1)), phi = 2 pi u2. */
BB_FN bb_vec3 bb_sample_cos_power(bb_real e, bb_real u1, bb_real u2) {
    bb_real l = bb_log1p(-u1) / (e + BB_R(1.0));
    bb_real cos_t = bb_exp(l);
    bb_real sin_t = bb_safe_sqrt(-bb_expm1(BB_R(2.0) * l));
    bb_real phi = BB_2PI * u2;
    return bb_v3(sin_t * bb_cos(phi), sin_t * bb_sin(phi), cos_t);
}

/* Local direction d in the frame whose z axis is the unit vector n [D17, listing 3]. */
BB_FN bb_vec3 bb_to_frame(bb_vec3 n, bb_vec3 d) {
    bb_real sign = bb_select(BB_R(-1.0), BB_R(1.0), n.z >= BB_R(0.0));
    bb_real a = BB_R(-1.0) / (sign + n.z);
    bb_real b = n.x * n.y * a;
    bb_vec3 t1 = bb_v3(BB_R(1.0) + sign * n.x * n.x * a, sign * b, -sign * n.x);
    bb_vec3 t2 = bb_v3(b, sign + n.y * n.y * a, -n.y);
    return bb_add(bb_add(bb_scale(t1, d.x), bb_scale(t2, d.y)), bb_scale(n, d.z));
}

/* The forms of G2 a model's shadowing choice names (the spec's shadowing=separable|correlated|
 * masking; smith.h's shadowing slot, the rough dielectric's `shadowing` argument), compared by
 * equality. */
#define BB_SHADOWING_SEPARABLE 0  /* G1(wo) G1(wi) [H14 eq. 98] */
#define BB_SHADOWING_CORRELATED 1 /* 1 / (1 + Lambda(wo) + Lambda(wi)) [H14 eq. 99] */
#define BB_SHADOWING_MASKING 2    /* G1(wo): the masking term alone (smith.h) */

/* Smith masking-shadowing G2 from the two G1 = 1 / (1 + Lambda) [H14 eq. 43] of any
 * distribution (bb_ggx_g1, bb_beckmann_g1 below): G1o = G1(wo), G1i = G1(wi).
 * Separable G2 = G1(wo) G1(wi) [H14 eq. 98]. */
BB_FN bb_real bb_g2_separable_from_g1(bb_real g1o, bb_real g1i) { return g1o * g1i; }

/* Height-correlated G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) [H14 eq. 99], written as
 * 1/(1/G1o + 1/G1i - 1) so that it reaches 0, not NaN, at the horizon. */
BB_FN bb_real bb_g2_correlated_from_g1(bb_real g1o, bb_real g1i) {
    bb_real p = g1o * g1i;
    bb_real den = g1o + g1i - p;
    bb_real g = p / bb_select(den, BB_R(1.0), den <= BB_R(0.0));
    return bb_select(BB_R(0.0), g, p > BB_R(0.0));
}

/* Below this alpha a float kernel cannot resolve the lobe (D ~ 1/(pi alpha^2) overflows the
 * sample weights' useful range); the host refuses smaller values. */
#define BB_ALPHA_MIN BB_R(1e-4)

/* GGX D(m) [WMLT07 eq. 33] written without tan(): for a unit m with m.z > 0,
 * D = 1 / (pi ax ay ((mx/ax)^2 + (my/ay)^2 + mz^2)^2). Returns 0 for m.z <= 0. */
BB_FN bb_real bb_ggx_d(bb_vec3 m, bb_real ax, bb_real ay) {
    bb_real x = m.x / ax, y = m.y / ay;
    bb_real q = x * x + y * y + m.z * m.z;
    bb_real d = BB_R(1.0) / (BB_PI * ax * ay * q * q);
    return bb_select(BB_R(0.0), d, m.z > BB_R(0.0));
}

/* Smith Lambda for GGX [H14 eq. 86], anisotropic through the projected roughness [H14 eq. 80]:
 * with r2 = (wx ax)^2 + (wy ay)^2 and z = w.z, alpha^2 tan^2 = r2 / z^2 and
 * Lambda = (sqrt(1 + r2/z^2) - 1)/2 = r2 / (2 z (sqrt(z^2 + r2) + z)),
 * the last form free of cancellation at small roughness. Infinite at the horizon. */
BB_FN bb_real bb_ggx_lambda(bb_vec3 w, bb_real ax, bb_real ay) {
    bb_real z = bb_fabs(w.z);
    bb_real r2 = bb_sqr(w.x * ax) + bb_sqr(w.y * ay);
    bb_real den = BB_R(2.0) * z * (bb_sqrt(z * z + r2) + z);
    return r2 / den;
}

/* Smith G1 = 1 / (1 + Lambda) [H14 eq. 43], in the closed form
 * G1 = 2z(s + z) / (2z(s + z) + r2), s = sqrt(z^2 + r2): finite everywhere, exactly 1 at
 * normal incidence and 0 at the horizon. Returns 0 for w.z <= 0. */
BB_FN bb_real bb_ggx_g1(bb_vec3 w, bb_real ax, bb_real ay) {
    bb_real z = bb_max(w.z, BB_R(0.0));
    bb_real r2 = bb_sqr(w.x * ax) + bb_sqr(w.y * ay);
    bb_real a = BB_R(2.0) * z * (bb_sqrt(z * z + r2) + z);
    bb_real g = a / (a + r2);
    return bb_select(BB_R(0.0), g, w.z > BB_R(0.0));
}

/* Sample a visible normal of GGX seen from wo (wo.z > 0) [H18, listing 1], from the point d of
 * the unit disk that bb_disk_polar(u1, u2) gives (sec. 4.2: d = sqrt(u1) (cos 2 pi u2,
 * sin 2 pi u2); it does not depend on wo, so the fast kernels tabulate it). The density of the
 * result is D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z. */
BB_FN bb_vec3 bb_ggx_sample_vndf_disk(bb_vec3 wo, bb_real ax, bb_real ay, bb_vec2 d) {
    /* Section 3.2: stretch the view vector to the hemisphere configuration. */
    bb_vec3 vh = bb_normalize(bb_v3(ax * wo.x, ay * wo.y, wo.z));
    /* Section 4.1: orthonormal basis (with the special case at normal incidence). */
    bb_real lensq = vh.x * vh.x + vh.y * vh.y;
    bb_real inv_len = BB_R(1.0) / bb_sqrt(bb_select(BB_R(1.0), lensq, lensq > BB_R(0.0)));
    bb_vec3 t1 = bb_v3(bb_select(BB_R(1.0), -vh.y * inv_len, lensq > BB_R(0.0)),
                       bb_select(BB_R(0.0), vh.x * inv_len, lensq > BB_R(0.0)), BB_R(0.0));
    bb_vec3 t2 = bb_cross(vh, t1);
    /* Section 4.2: parameterisation of the projected area. */
    bb_real p1 = d.x;
    bb_real p2 = d.y;
    bb_real s = BB_R(0.5) * (BB_R(1.0) + vh.z);
    p2 = (BB_R(1.0) - s) * bb_safe_sqrt(BB_R(1.0) - p1 * p1) + s * p2;
    /* Section 4.3: reprojection onto the hemisphere. */
    bb_real p3 = bb_safe_sqrt(BB_R(1.0) - p1 * p1 - p2 * p2);
    bb_vec3 nh = bb_add(bb_add(bb_scale(t1, p1), bb_scale(t2, p2)), bb_scale(vh, p3));
    /* Section 3.4: unstretch back to the ellipsoid configuration. */
    return bb_normalize(bb_v3(ax * nh.x, ay * nh.y, bb_max(BB_R(0.0), nh.z)));
}

/* Sample a visible normal of GGX seen from wo (wo.z > 0) [H18, listing 1].
 * u1, u2 in [0, 1). The density of the result is D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z. */
BB_FN bb_vec3 bb_ggx_sample_vndf(bb_vec3 wo, bb_real ax, bb_real ay, bb_real u1, bb_real u2) {
    return bb_ggx_sample_vndf_disk(wo, ax, ay, bb_disk_polar(u1, u2));
}

/* Sample a GGX microfacet normal with density D(m) cos(theta_m) [WMLT07 eq. 35-36], through the
 * slopes: the unit-roughness slope radius has r^2 = u1/(1 - u1), stretched by (ax, ay) [HD14
 * sec. 3]; m = normalize(r ax cos phi, r ay sin phi, 1), multiplied through by sqrt(1 - u1). */
BB_FN bb_vec3 bb_ggx_sample_dcos(bb_real ax, bb_real ay, bb_real u1, bb_real u2) {
    bb_real r = bb_sqrt(u1), z = bb_safe_sqrt(BB_R(1.0) - u1);
    bb_real phi = BB_2PI * u2;
    return bb_normalize(bb_v3(r * ax * bb_cos(phi), r * ay * bb_sin(phi), z));
}

/* ------------------------------------------------------------------ Beckmann */

/* Beckmann D(m) [WMLT07 eq. 25; H14 eq. 71 for the anisotropic form] without tan():
 *   D = exp(-tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2)) / (pi ax ay cos^4)
 *     = exp(-s / m.z^2) / (pi ax ay m.z^4),  s = (m.x/ax)^2 + (m.y/ay)^2.
 * cos^4 underflow guard: wherever the exponential is 0 the result is 0 (see the policy above;
 * e > 0 implies m.z^2 > s/104 >= (1 - m.z^2)/(104 alpha_max^2), far from underflow). */
BB_FN bb_real bb_beckmann_d(bb_vec3 m, bb_real ax, bb_real ay) {
    bb_real x = m.x / ax, y = m.y / ay;
    bb_real z2 = m.z * m.z;
    bb_real s = x * x + y * y;
    bb_real e = bb_exp(-s / bb_select(z2, BB_R(1.0), z2 <= BB_R(0.0)));
    bb_real d = e / (BB_PI * ax * ay * z2 * z2);
    return bb_select(BB_R(0.0), d, m.z > BB_R(0.0) && e > BB_R(0.0));
}

/* Smith Lambda for Beckmann [WMLT07 eq. 27 (as 1/G1 - 1); H14 eq. 72], with
 * a = 1/(alpha_proj tan theta) = w.z / sqrt(r2), r2 = (wx ax)^2 + (wy ay)^2 [H14 eq. 80]:
 *   Lambda = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)) = (exp(-a^2)/(a sqrt(pi)) - erfc(a))/2,
 * the erfc form avoiding the cancellation of erf(a) - 1. Infinite at the horizon, 0 at the
 * normal. */
BB_FN bb_real bb_beckmann_lambda(bb_vec3 w, bb_real ax, bb_real ay) {
    bb_real z = bb_fabs(w.z);
    bb_real r2 = bb_sqr(w.x * ax) + bb_sqr(w.y * ay);
    bb_real rr = bb_sqrt(r2);
    bb_real a = z / rr;
    /* exp(-a^2)/a written as exp(-z^2/r2) rr / z: 0, not NaN, at the normal (r2 = 0). */
    bb_real ea = bb_exp(-(z * z) / r2) * rr / z;
    return BB_R(0.5) * (ea * BB_INV_SQRT_PI - bb_erfc(a));
}

/* Smith G1 = 1 / (1 + Lambda) for Beckmann [H14 eq. 43 with eq. 72], multiplied through by
 * 2 sqrt(pi):
 *   G1 = 2 sqrt(pi) / (sqrt(pi) (1 + erf(a)) + exp(-a^2)/a),
 * finite everywhere: exactly 1 at normal incidence (a = inf), 0 at the horizon (a = 0).
 * Returns 0 for w.z <= 0. Published check: alpha = 0.1, theta = 0.98 pi/2 gives 0.67333597. */
BB_FN bb_real bb_beckmann_g1(bb_vec3 w, bb_real ax, bb_real ay) {
    bb_real z = bb_max(w.z, BB_R(0.0));
    bb_real r2 = bb_sqr(w.x * ax) + bb_sqr(w.y * ay);
    bb_real rr = bb_sqrt(r2);
    bb_real a = z / rr;
    bb_real ea = bb_exp(-(z * z) / r2) * rr / bb_select(z, BB_R(1.0), z <= BB_R(0.0));
    bb_real g = BB_R(2.0) * BB_SQRT_PI / (BB_SQRT_PI * (BB_R(1.0) + bb_erf(a)) + ea);
    return bb_select(BB_R(0.0), g, w.z > BB_R(0.0));
}

/* Sample a Beckmann microfacet normal with density D(m) cos(theta_m) [WMLT07 eq. 28], through
 * the slopes: the unit-roughness slope radius has r^2 = -log(1 - u1), stretched by (ax, ay). */
BB_FN bb_vec3 bb_beckmann_sample_dcos(bb_real ax, bb_real ay, bb_real u1, bb_real u2) {
    bb_real r = bb_safe_sqrt(-bb_log1p(-u1));
    bb_real phi = BB_2PI * u2;
    return bb_normalize(bb_v3(r * ax * bb_cos(phi), r * ay * bb_sin(phi), BB_R(1.0)));
}

/* erf^-1(x) for x in (-1, 1) [G10, the single-precision version]: maximum relative error
 * about 2e-7 for |x| <= 1 - 2e-6, the range the samplers use (tests/test_models.cpp measures it
 * against Boost.Math; beyond, in double's far tail, it degrades to ~1e-2); enough for sampling,
 * where it perturbs the sampled density by the same relative amount. x is clamped to
 * [-1 + eps, 1 - eps] so that the result is finite. */
BB_FN bb_real bb_erfinv(bb_real x) {
    bb_real xc = bb_clamp(x, BB_R(-1.0) + BB_EPS_REAL, BB_R(1.0) - BB_EPS_REAL);
    bb_real w = -bb_log((BB_R(1.0) - xc) * (BB_R(1.0) + xc));
    /* central region, w < 5 */
    bb_real v = w - BB_R(2.5);
    bb_real p = BB_R(2.81022636e-08);
    p = BB_R(3.43273939e-07) + p * v;
    p = BB_R(-3.5233877e-06) + p * v;
    p = BB_R(-4.39150654e-06) + p * v;
    p = BB_R(0.00021858087) + p * v;
    p = BB_R(-0.00125372503) + p * v;
    p = BB_R(-0.00417768164) + p * v;
    p = BB_R(0.246640727) + p * v;
    p = BB_R(1.50140941) + p * v;
    /* tails, w >= 5 */
    bb_real t = bb_sqrt(w) - BB_R(3.0);
    bb_real q = BB_R(-0.000200214257);
    q = BB_R(0.000100950558) + q * t;
    q = BB_R(0.00134934322) + q * t;
    q = BB_R(-0.00367342844) + q * t;
    q = BB_R(0.00573950773) + q * t;
    q = BB_R(-0.0076224613) + q * t;
    q = BB_R(0.00943887047) + q * t;
    q = BB_R(1.00167406) + q * t;
    q = BB_R(2.83297682) + q * t;
    return bb_select(q, p, w < BB_R(5.0)) * xc;
}

/* Iterations of the bracketed Newton solve in bb_beckmann_sample_slope11. A fixed count (no
 * early exit) keeps host and device on the same arithmetic path. Jakob's initial guess is good
 * enough that after 2 steps the CDF residual is at the level of the erfinv approximation
 * (2.3e-8 over theta in [0, pi/2] and u in [0, 1]); tests/test_models.cpp checks that 4 steps
 * leave it below 1e-7. */
#ifndef BB_BECKMANN_VNDF_ITERATIONS
#define BB_BECKMANN_VNDF_ITERATIONS 4
#endif

/* Slopes (x, y) of the visible normals of the unit Beckmann distribution (alpha = 1) seen from
 * a direction at angle theta in the xz-plane (phi = 0), microfacet normal (-x, -y, 1)/|.|
 * [HD14 sec. 4, J14]. The x-slope CDF, parameterised by b = erf(x), is
 *   C(b) = (1 + b + tan(theta)/sqrt(pi) exp(-erfinv(b)^2)) / (1 + erf(cot) + tan/sqrt(pi) exp(-cot^2)),
 * for x < cot(theta), inverted by Newton's method inside the bracket [-1, erf(cot theta)] from
 * Jakob's fitted initial guess [J14]; y = erfinv(2 u2 - 1) is independent of x. Normal incidence
 * (sin_t = 0) needs no special case: cot = inf, tan = 0 and C(b) = (1 + b)/2.
 * u1 is clamped to [1e-6, 1 - 1e-6] as in [J14] (the bias is below 1e-6 of a bounded weight). */
BB_FN bb_vec3 bb_beckmann_sample_slope11(bb_real cos_t, bb_real sin_t, bb_real u1, bb_real u2) {
    bb_real tan_t = sin_t / cos_t;
    bb_real cot_t = cos_t / sin_t;
    bb_real theta = bb_atan2(sin_t, cos_t);
    bb_real u = bb_clamp(u1, BB_R(1e-6), BB_R(1.0) - BB_R(1e-6));
    bb_real a = BB_R(-1.0);
    bb_real c = bb_erf(cot_t);
    bb_real fit = BB_R(1.0) + theta * (BB_R(-0.876) + theta * (BB_R(0.4265) - BB_R(0.0594) * theta));
    bb_real b = c - (BB_R(1.0) + c) * bb_pow(BB_R(1.0) - u, fit);
    bb_real k = tan_t * BB_INV_SQRT_PI;
    bb_real norm = BB_R(1.0) / (BB_R(1.0) + c + k * bb_exp(-cot_t * cot_t));
    for (int it = 0; it < BB_BECKMANN_VNDF_ITERATIONS; ++it) {
        b = bb_select(b, BB_R(0.5) * (a + c), !(b >= a && b <= c));
        bb_real x = bb_erfinv(b);
        bb_real value = norm * (BB_R(1.0) + b + k * bb_exp(-x * x)) - u;
        bb_real deriv = norm * (BB_R(1.0) - x * tan_t);
        bb_mask above = value > BB_R(0.0);
        c = bb_select(c, b, above);
        a = bb_select(b, a, above);
        b = b - value / deriv;
    }
    b = bb_select(b, BB_R(0.5) * (a + c), !(b >= a && b <= c));
    bb_real v = bb_clamp(u2, BB_R(1e-6), BB_R(1.0) - BB_R(1e-6));
    return bb_v3(bb_erfinv(b), bb_erfinv(BB_R(2.0) * v - BB_R(1.0)), BB_R(0.0));
}

/* A visible normal of Beckmann [HD14 sec. 4] from the view stretched to the unit configuration,
 * v = normalize(ax wo.x, ay wo.y, wo.z): sample its slopes, rotate them to v's azimuth, unstretch,
 * and turn the slope into a normal. cos_t is the cosine the slope sampler takes: v.z clamped to
 * >= 0 (bb_beckmann_sample_vndf), or signed, theta up to pi, for the random walk's directions
 * below the horizon (random_walk.h). */
BB_FN bb_vec3 bb_beckmann_sample_vndf_stretched(bb_vec3 v, bb_real cos_t, bb_real ax, bb_real ay, bb_real u1,
                                                bb_real u2) {
    bb_real sin_t = bb_sqrt(v.x * v.x + v.y * v.y);
    bb_vec3 s = bb_beckmann_sample_slope11(cos_t, sin_t, u1, u2);
    bb_real inv = BB_R(1.0) / bb_select(sin_t, BB_R(1.0), sin_t <= BB_R(0.0));
    bb_real cphi = bb_select(v.x * inv, BB_R(1.0), sin_t <= BB_R(0.0));
    bb_real sphi = bb_select(v.y * inv, BB_R(0.0), sin_t <= BB_R(0.0));
    bb_real x = (cphi * s.x - sphi * s.y) * ax;
    bb_real y = (sphi * s.x + cphi * s.y) * ay;
    return bb_normalize(bb_v3(-x, -y, BB_R(1.0)));
}

/* Sample a visible normal of Beckmann seen from wo (wo.z > 0) [HD14 sec. 4]. The density of the
 * result is D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z. */
BB_FN bb_vec3 bb_beckmann_sample_vndf(bb_vec3 wo, bb_real ax, bb_real ay, bb_real u1, bb_real u2) {
    bb_vec3 v = bb_normalize(bb_v3(ax * wo.x, ay * wo.y, wo.z));
    return bb_beckmann_sample_vndf_stretched(v, bb_max(v.z, BB_R(0.0)), ax, ay, u1, u2);
}

/* ---------------------------------------------------------- normalised Blinn */

/* Normalised Blinn distribution [B77; WMLT07 eq. 30]: D = (N + 2)/(2 pi) cos^N(theta_m), so that
 * the integral of D cos(theta_m) over the hemisphere is 1. cos^N as exp(N log1p(-(1 - m.z))) with
 * 1 - m.z from bb_one_minus_z: finite and accurate for N up to 1e4 in float. 0 for m.z <= 0. */
BB_FN bb_real bb_blinn_d(bb_vec3 m, bb_real n) {
    bb_real d = (n + BB_R(2.0)) * (BB_R(0.5) * BB_INV_PI) * bb_pow1m(bb_one_minus_z(m), n);
    return bb_select(BB_R(0.0), d, m.z > BB_R(0.0));
}

/* Sample a Blinn microfacet normal with density D(m) cos(theta_m) = (N+2)/(2 pi) cos^(N+1). */
BB_FN bb_vec3 bb_blinn_sample_dcos(bb_real n, bb_real u1, bb_real u2) {
    return bb_sample_cos_power(n + BB_R(1.0), u1, u2);
}

#endif /* BRDFBAKE_BRDF_MICROFACET_H */

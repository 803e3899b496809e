/* Low-discrepancy point sets and warps, shared by host and kernels. */
#ifndef BRDFBAKE_BRDF_SAMPLING_H
#define BRDFBAKE_BRDF_SAMPLING_H

#include "brdfbake/brdf/compat.h"

/* Van der Corput radical inverse in base 2 by bit reversal (Hacker's Delight 7-1). */
BB_FN unsigned int bb_reverse_bits(unsigned int v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

/* A 32-bit fraction as a real in [0, 1): float keeps the top 24 bits so that the result can
 * never round up to 1. */
BB_FN bb_real bb_unit_from_bits(unsigned int v) {
#ifdef BB_REAL_IS_FLOAT
    return (bb_real)(v >> 8) * BB_R(5.9604644775390625e-8); /* 2^-24 */
#else
    return (bb_real)v * BB_R(2.3283064365386963e-10); /* 2^-32 */
#endif
}

/* Cranley-Patterson rotation: (x + shift) mod 1, for x and shift in [0, 1). */
BB_FN bb_real bb_rotate(bb_real x, bb_real shift) {
    bb_real u = x + shift;
    return bb_select(u, u - BB_R(1.0), u >= BB_R(1.0));
}

/* Point i of the n-point Hammersley set: ((i + 1/2)/n, radical_inverse_2(i)). */
BB_FN bb_real bb_hammersley_u1(unsigned int i, unsigned int n) { return ((bb_real)i + BB_R(0.5)) / (bb_real)n; }
BB_FN bb_real bb_hammersley_u2(unsigned int i) { return bb_unit_from_bits(bb_reverse_bits(i)); }

/* The polar map of the unit square onto the unit disk: radius sqrt(u1), angle 2 pi u2 (uniform
 * density; the warp of Malley's method and of the visible-normal sampling [H18 sec. 4.2]).
 * It does not depend on the cell of a table, so the fast kernels take it from a table. */
BB_FN bb_vec2 bb_disk_polar(bb_real u1, bb_real u2) {
    bb_real r = bb_sqrt(u1);
    bb_real phi = BB_2PI * u2;
    return bb_v2(r * bb_cos(phi), r * bb_sin(phi));
}

/* Cosine-weighted direction on the hemisphere (Malley's method), pdf = cos(theta)/pi:
 * cos(theta) = sqrt(u1) and sin(theta) = sqrt(1 - u1), the mirror image u1 -> 1 - u1 of the
 * disk warp above. Grazing directions come from small u1, where a float keeps full relative
 * precision; with cos(theta) = sqrt(1 - u1) they would come from u1 near 1, where float
 * resolves cos(theta) only in steps of about 2.4e-4 and integrands that grow like 1/cos(theta)
 * near the horizon (Oren-Nayar) are biased by ~1e-4. */
BB_FN bb_vec3 bb_cosine_hemisphere(bb_real u1, bb_real u2) {
    bb_real s = bb_safe_sqrt(BB_R(1.0) - u1);
    bb_real phi = BB_2PI * u2;
    return bb_v3(s * bb_cos(phi), s * bb_sin(phi), bb_sqrt(u1));
}

/* ------------------------------------------------------------------ one-sample mixtures
 * A lobe's sampler beside the cosine warp of a Lambert part f = kd/pi, one of the two chosen per
 * sample: Veach's one-sample model with the balance heuristic (Veach 1997, sec. 9.2.4; PBRT 4th
 * ed. sec. 2.2.3): the cosine warp with chance c, else the lobe's sampler, u1 rescaled into
 * [0, 1) within the part it chose (a stratified u1 stays stratified within each part), and the
 * weight f cos / (c cos/pi + (1 - c) pdf_lobe), unbiased for the whole f (lobe plus Lambert) at any
 * c in [0, 1] where the lobe's pdf is positive wherever the lobe is. The Smith lobes' diffuse=KD
 * uses it (smith.h, bb_smith_sample). */

/* Whether the mask holds in any lane (a vector build's lanes share a cell's parameters, so a test
 * of them is uniform); a scalar mask itself elsewhere. */
#if defined(__OPENCL_C_VERSION__) && defined(BB_VECTOR_WIDTH)
#define bb_any_lane(m) any(m)
#else
#define bb_any_lane(m) (m)
#endif

/* The chance of the Lambert part: its albedo kd against an estimate e of the lobe's albedo,
 * c = kd / (kd + e) (1 where both are 0: the caller samples the mixture only for kd > 0). */
BB_FN bb_real bb_mixture_lambert_chance(bb_real kd, bb_real e) {
    bb_real sum = kd + bb_max(e, BB_R(0.0));
    return bb_select(BB_R(1.0), kd / sum, sum > BB_R(0.0));
}

/* u rescaled to [0, 1) in the part it chose: u / c below c, (u - c) / (1 - c) from c on. */
BB_FN bb_real bb_mixture_rescale(bb_real u, bb_real c) {
    bb_real below = u / bb_select(BB_R(1.0), c, c > BB_R(0.0));
    bb_real above = (u - c) / bb_select(BB_R(1.0), BB_R(1.0) - c, c < BB_R(1.0));
    return bb_min(bb_select(above, below, u < c), BB_R(1.0) - BB_R(0.5) * BB_EPS_REAL);
}

/* The mixture's weight of a direction with f cos = f_cos and cos(theta_i) = cos_i: f cos over the
 * mixture's density c cos/pi + (1 - c) pdf_lobe; 0 where that density is 0. */
BB_FN bb_real bb_mixture_weight(bb_real f_cos, bb_real cos_i, bb_real c, bb_real pdf_lobe) {
    bb_real pdf = c * bb_max(cos_i, BB_R(0.0)) * BB_INV_PI + (BB_R(1.0) - c) * pdf_lobe;
    return bb_select(BB_R(0.0), f_cos / bb_select(BB_R(1.0), pdf, pdf > BB_R(0.0)), pdf > BB_R(0.0));
}

#endif /* BRDFBAKE_BRDF_SAMPLING_H */

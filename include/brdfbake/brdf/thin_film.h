/* Thin-film interference: the reflectance of one film of thickness d on a substrate, seen from
 * an ambient medium of index 1, at one wavelength (wave optics; the iridescence of a soap
 * bubble, an oil slick, an oxide on a metal). Shared by host and kernels; included by fresnel.h,
 * whose complex square root and conventions it uses.
 *
 * The film has the complex index n1 = eta1 + i k1, the substrate n2 = eta2 + i k2 (the same sign
 * convention as the conductor term in fresnel.h: k >= 0 absorbs, and the transmitted wave
 * exp(i (2 pi / lambda) n cos_t z) decays into the medium). Angles: sin_0 = sin(theta) in the
 * ambient medium, and in medium j the products w_j = n_j cos_j = sqrt(n_j^2 - sin_0^2) (Snell:
 * n_j sin_j = sin_0), on the branch of bb_complex_sqrt_upper; w_0 = cos(theta).
 *
 * References:
 *   [BW]  Born & Wolf, "Principles of Optics", 7th ed., sec. 1.6.4 eq. (57)-(58): the reflection
 *         coefficient of a homogeneous film as the sum of its multiply reflected waves,
 *           r = (r01 + r12 e^{2 i beta}) / (1 + r01 r12 e^{2 i beta}),
 *           beta = (2 pi / lambda) n1 d cos_1   (so 2 beta = (4 pi d / lambda) w_1),
 *         the Airy summation; sec. 1.5.2 eq. 21 for the interface coefficients, here written with
 *         w_j, which needs no cos_j alone and stays finite at grazing incidence:
 *           s:  r_ij = (w_i - w_j) / (w_i + w_j),
 *           p:  r_ij = (n_j^2 w_i - n_i^2 w_j) / (n_j^2 w_i + n_i^2 w_j).
 *   [BB17] Belcour & Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of
 *          Varying Iridescence" (ACM TOG 36(4)), sec. 3-4: the same Airy reflectance per
 *          polarisation, the model of glTF's KHR_materials_iridescence.
 * R_s = |r_s|^2 and R_p = |r_p|^2 are computed separately: the two polarisations do not mix.
 * Thickness 0 gives the bare substrate (r = (r01 + r12)/(1 + r01 r12) = r02), a film of index 1
 * gives the substrate too (r01 = 0, |e^{2 i beta}| = 1), and every value lies in [0, 1]. */
#ifndef BRDFBAKE_BRDF_THIN_FILM_H
#define BRDFBAKE_BRDF_THIN_FILM_H

/* Parameter slots of the thin-film term (its fp block). */
#define BB_THIN_FILM_ETA 0        /* film index, real part */
#define BB_THIN_FILM_K 1          /* film extinction coefficient (0: a transparent film) */
#define BB_THIN_FILM_THICKNESS 2  /* film thickness d, nanometres */
#define BB_THIN_FILM_BASE_ETA 3   /* substrate index, real part */
#define BB_THIN_FILM_BASE_K 4     /* substrate extinction coefficient (0: a dielectric) */
#define BB_THIN_FILM_WAVELENGTH 5 /* vacuum wavelength lambda, nanometres */

BB_FN bb_complex bb_cx(bb_real re, bb_real im) {
    bb_complex z = {re, im};
    return z;
}
BB_FN bb_complex bb_cx_add(bb_complex a, bb_complex b) { return bb_cx(a.re + b.re, a.im + b.im); }
BB_FN bb_complex bb_cx_sub(bb_complex a, bb_complex b) { return bb_cx(a.re - b.re, a.im - b.im); }
BB_FN bb_complex bb_cx_mul(bb_complex a, bb_complex b) {
    return bb_cx(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
}
BB_FN bb_real bb_cx_abs2(bb_complex a) { return a.re * a.re + a.im * a.im; }
/* a / b, and 0 where b is 0 (the callers' 0/0 limits are handled before). */
BB_FN bb_complex bb_cx_div(bb_complex a, bb_complex b) {
    bb_real d = bb_cx_abs2(b);
    bb_real s = bb_select(BB_R(1.0) / bb_select(d, BB_R(1.0), d == BB_R(0.0)), BB_R(0.0), d == BB_R(0.0));
    return bb_cx((a.re * b.re + a.im * b.im) * s, (a.im * b.re - a.re * b.im) * s);
}
/* e^{i z} = e^{-Im z} (cos Re z + i sin Re z). */
BB_FN bb_complex bb_cx_exp_i(bb_complex z) {
    bb_real m = bb_exp(-z.im);
    return bb_cx(m * bb_cos(z.re), m * bb_sin(z.re));
}

/* The Airy sum [BW eq. 58] of the two interface coefficients and the round-trip phase factor. */
BB_FN bb_complex bb_thin_film_airy(bb_complex r01, bb_complex r12, bb_complex phase) {
    bb_complex t = bb_cx_mul(r12, phase);
    return bb_cx_div(bb_cx_add(r01, t), bb_cx_add(bb_cx(BB_R(1.0), BB_R(0.0)), bb_cx_mul(r01, t)));
}

/* The s interface coefficient (w_i - w_j)/(w_i + w_j). */
BB_FN bb_complex bb_thin_film_rs(bb_complex wi, bb_complex wj) {
    return bb_cx_div(bb_cx_sub(wi, wj), bb_cx_add(wi, wj));
}
/* The p interface coefficient (n_j^2 w_i - n_i^2 w_j)/(n_j^2 w_i + n_i^2 w_j). */
BB_FN bb_complex bb_thin_film_rp(bb_complex n2i, bb_complex wi, bb_complex n2j, bb_complex wj) {
    bb_complex a = bb_cx_mul(n2j, wi), b = bb_cx_mul(n2i, wj);
    return bb_cx_div(bb_cx_sub(a, b), bb_cx_add(a, b));
}

/* Rs and Rp of the film on its substrate at cos_theta (clamped to [0, 1]: light arrives from the
 * ambient side). */
BB_FN bb_fresnel_sp bb_fresnel_thin_film_sp(bb_real cos_theta, bb_real eta1, bb_real k1, bb_real thickness_nm,
                                            bb_real eta2, bb_real k2, bb_real wavelength_nm) {
    bb_real c = bb_clamp(cos_theta, BB_R(0.0), BB_R(1.0));
    bb_real c2 = c * c; /* n_j^2 - sin_0^2 = n_j^2 - 1 + cos^2 */
    bb_complex n0sq = bb_cx(BB_R(1.0), BB_R(0.0));
    bb_complex n1sq = bb_cx((eta1 - k1) * (eta1 + k1), BB_R(2.0) * eta1 * k1);
    bb_complex n2sq = bb_cx((eta2 - k2) * (eta2 + k2), BB_R(2.0) * eta2 * k2);
    bb_complex w0 = bb_cx(c, BB_R(0.0));
    bb_complex w1 = bb_complex_sqrt_upper((eta1 - k1) * (eta1 + k1) - BB_R(1.0) + c2, n1sq.im);
    bb_complex w2 = bb_complex_sqrt_upper((eta2 - k2) * (eta2 + k2) - BB_R(1.0) + c2, n2sq.im);
    /* e^{2 i beta}, 2 beta = (4 pi d / lambda) w_1 [BW eq. 57]. */
    bb_real scale = BB_R(4.0) * BB_R(3.14159265358979323846) * thickness_nm / wavelength_nm;
    bb_complex phase = bb_cx_exp_i(bb_cx(scale * w1.re, scale * w1.im));
    bb_complex rs = bb_thin_film_airy(bb_thin_film_rs(w0, w1), bb_thin_film_rs(w1, w2), phase);
    bb_complex rp = bb_thin_film_airy(bb_thin_film_rp(n0sq, w0, n1sq, w1), bb_thin_film_rp(n1sq, w1, n2sq, w2), phase);
    /* |r| <= 1 for passive media; rounding near grazing may give 1 + a few ulp: clamp. */
    return bb_make_fresnel_sp(bb_min(bb_cx_abs2(rs), BB_R(1.0)), bb_min(bb_cx_abs2(rp), BB_R(1.0)));
}

#endif /* BRDFBAKE_BRDF_THIN_FILM_H */

/* The Phong lobe, reciprocal (`phong`) and original (`phong-original`) forms.
 *
 *   [P75] Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975: the specular
 *         term ks cos^N(angle between the view direction and the mirror direction of the light).
 *   [L94] Lewis, "Making Shaders More Physically Plausible", Computer Graphics Forum 13(2), 1994:
 *         the reciprocal BRDF f = ks (wo.R(wi))^N and its normalisation (N + 2)/(2 pi), with which
 *         the albedo at normal incidence is at most 1.
 *   [LW94] Lafortune, Willems, "Using the Modified Phong Reflectance Model for Physically Based
 *         Rendering", tech. report CW197, KU Leuven, 1994: sampling the lobe about the mirror
 *         direction with density (N + 1)/(2 pi) cos^N.
 *
 * Models, with R(w) = 2 (w.n) n - w:
 *   phong:           f = K max(0, wo.R(wi))^N,              K = ks, or ks (N + 2)/(2 pi) if normalized
 *   phong-original:  f = K max(0, wo.R(wi))^N / cos(theta_i), K = ks  (not reciprocal: Phong's
 *                    shading term as a BRDF; kept as the counter-example for the reciprocity tests)
 * wo.R(wi) = R(wo).wi, so `phong` is symmetric in wo and wi.
 *
 * Edge cases (besides microfacet.h's policy): the lobe is 0 where wo.R(wi) <= 0 (also for N = 0);
 * cos^N is evaluated as exp(N log1p(-d)) with d = 1 - R(wo).wi = |R(wo) - wi|^2 / 2, exact near
 * the peak, so N up to 1e4 stays accurate in float; phong-original divides by max(cos_i, 1e-30),
 * finite in float for every direction above the horizon. */
#ifndef BRDFBAKE_BRDF_PHONG_H
#define BRDFBAKE_BRDF_PHONG_H

#include "brdfbake/brdf/microfacet.h"

/* Parameter slots (shared by phong and phong-original). */
#define BB_PHONG_N 0
#define BB_PHONG_KS 1
#define BB_PHONG_NORMALIZED 2 /* 1: K = ks (N + 2)/(2 pi); phong-original always uses K = ks */

/* The smallest cos(theta_i) phong-original divides by. */
#define BB_PHONG_ORIGINAL_MIN_COS BB_R(1e-30)

BB_FN bb_real bb_phong_k(bb_params p) {
    bb_real n = p.v[BB_PHONG_N];
    return p.v[BB_PHONG_KS] *
           bb_select(BB_R(1.0), (n + BB_R(2.0)) * (BB_R(0.5) * BB_INV_PI), p.v[BB_PHONG_NORMALIZED] > BB_R(0.5));
}

/* The mirror direction R(w) = 2 (w.n) n - w about the macro normal n = +z. */
BB_FN bb_vec3 bb_mirror_dir(bb_vec3 w) { return bb_v3(-w.x, -w.y, w.z); }

/* max(0, wo.R(wi))^N, with 1 - wo.R(wi) = |R(wo) - wi|^2 / 2 (unit vectors). */
BB_FN bb_real bb_phong_lobe(bb_real n, bb_vec3 wo, bb_vec3 wi) {
    bb_vec3 r = bb_mirror_dir(wo);
    bb_vec3 d = bb_v3(r.x - wi.x, r.y - wi.y, r.z - wi.z);
    return bb_pow1m(BB_R(0.5) * bb_dot(d, d), n);
}

BB_FN bb_real bb_phong_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_real v = bb_phong_k(p) * bb_phong_lobe(p.v[BB_PHONG_N], wo, wi);
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wi.z > BB_R(0.0));
}

BB_FN bb_real bb_phong_original_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_real v = p.v[BB_PHONG_KS] * bb_phong_lobe(p.v[BB_PHONG_N], wo, wi) /
             bb_max(wi.z, BB_PHONG_ORIGINAL_MIN_COS);
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wi.z > BB_R(0.0));
}

/* wi drawn about R(wo) with density (N + 1)/(2 pi) cos^N(angle to R(wo)) [LW94]. */
BB_FN bb_vec3 bb_phong_sample_dir(bb_real n, bb_vec3 wo, bb_real u1, bb_real u2) {
    return bb_to_frame(bb_mirror_dir(wo), bb_sample_cos_power(n, u1, u2));
}

/* Phong lobe sampling [LW94]: f cos_i / pdf = K 2 pi cos_i / (N + 1) where wi is above the
 * horizon, 0 elsewhere (samples below the horizon are the lobe's part that the surface cuts). */
BB_FN bb_sample bb_phong_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_real n = p.v[BB_PHONG_N];
    bb_vec3 wi = bb_phong_sample_dir(n, wo, u1, u2);
    bb_real w = bb_phong_k(p) * BB_2PI * wi.z / (n + BB_R(1.0));
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, wo.z > BB_R(0.0) && wi.z > BB_R(0.0)));
}

/* The same lobe for phong-original: the 1/cos_i cancels the cosine, the weight is the constant
 * ks 2 pi / (N + 1) above the horizon (exactly, for cos_i >= BB_PHONG_ORIGINAL_MIN_COS). */
BB_FN bb_sample bb_phong_original_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_real n = p.v[BB_PHONG_N];
    bb_vec3 wi = bb_phong_sample_dir(n, wo, u1, u2);
    bb_real w = p.v[BB_PHONG_KS] * BB_2PI * wi.z / (bb_max(wi.z, BB_PHONG_ORIGINAL_MIN_COS) * (n + BB_R(1.0)));
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, wo.z > BB_R(0.0) && wi.z > BB_R(0.0)));
}

#endif /* BRDFBAKE_BRDF_PHONG_H */

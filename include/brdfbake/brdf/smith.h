/* The Smith microfacet reflection lobe, parameterised by its distribution of normals, as
 * Mitsuba 3 (MicrofacetDistribution) and Cycles (bsdf_microfacet.h) do: one body for the
 * evaluation, the visible-normal importance sample, and the half-vector quadrature weight, the
 * distributions differing only in D, the Smith G1 (from Lambda) and the visible-normal sampler
 * (microfacet.h):
 *   f = D(wh) G2(wo, wi) F(wo.wh) / (4 cos_theta_o cos_theta_i)      [WMLT07 eq. 20]
 *   sample: wh from the visible normals of wo, wi = reflect(wo, wh), weight
 *   f cos_theta_i / pdf = F(wo.wh) G2(wo, wi) / G1(wo)                [HD14 eq. 9; H18 eq. 19]
 * with G2 separable G1(wo) G1(wi) [H14 eq. 98], height-correlated [H14 eq. 99], or the masking
 * term alone, G2 = G1(wo) [H14 eq. 43 with the shadowing of wi left out]: the lobe Blender Cycles'
 * albedo estimator integrates (intern/cycles/app/cycles_precompute.cpp averages a weight over
 * the visible normals of wo, counting a reflection below the horizon as 0), whose sample weight
 * is F(wo.wh) alone. It is no physical masking-shadowing: with no shadowing its albedo exceeds
 * the separable and the height-correlated lobes' (up to 1 at F = 1, the visible normals'
 * reflections that stay above the horizon).
 * The distribution is a constant of the model (ggx.h, beckmann.h), so each branch on it below
 * is resolved when the call is inlined.
 *
 * Validity of the sample weight, one rule for every distribution: the weight is 0 unless
 * wi.z > 0 and G1(wo) > 0 (so wo.z > 0). A visible-normal sampler draws wh with wo.wh > 0 and
 * wh.z >= 0 [HD14 sec. 4], and wi.z > 0 implies wo.wh > 0 in floating point too:
 * wi.z = 2 (wo.wh) wh.z - wo.z, and 2 (wo.wh) wh.z <= 0 (its sign survives rounding) would give
 * wi.z <= -wo.z < 0. So no separate test of wo.wh is needed (tests/test_microfacet.cpp checks
 * it on samples of both distributions).
 *
 * [WMLT07], [H14], [HD14], [H18]: see microfacet.h. */
#ifndef BRDFBAKE_BRDF_SMITH_H
#define BRDFBAKE_BRDF_SMITH_H

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/quad_dist.h"

/* The distributions. */
#define BB_SMITH_GGX 0
#define BB_SMITH_BECKMANN 1

/* Parameter slots of every Smith lobe. */
#define BB_SMITH_ALPHA_X 0
#define BB_SMITH_ALPHA_Y 1
#define BB_SMITH_SHADOWING 2 /* the reflection's G2: one of BB_SHADOWING_* */
/* Slot 3 is ggx.h's transmission shadowing; slots 4-7 the random walk's (random_walk.h) under
 * scattering=multiple. Under scattering=single slot 7 holds the Lambert weight kd of the spec's
 * diffuse=KD (the host refuses diffuse with scattering=multiple):
 *   f = f_spec + kd / pi,
 * the specular lobe plus a Lambertian base, the sum Ngan, Durand and Matusik 2005 fit to the MERL
 * materials (sec. 4: every model they fit carries a Lambert term). The kd/pi is not multiplied by
 * the Fresnel term. Only the evaluation adds it: the albedo of the Lambert part is kd exactly (the
 * integral of kd/pi cos theta_i over the hemisphere), which the host adds in closed form
 * (host/integrate/albedo.cpp, compute_albedo) while the kernels integrate the specular lobe with
 * the slot set to 0; the quadrature weights below are those of the specular lobe. The sampler
 * (bb_smith_sample) samples the whole f where kd > 0: a one-sample mixture with the cosine warp. */
#define BB_SMITH_SCATTERING 4 /* BB_SCATTERING_SINGLE or BB_SCATTERING_MULTIPLE */
#define BB_SMITH_DIFFUSE 7
#define BB_SCATTERING_SINGLE 0
#define BB_SCATTERING_MULTIPLE 1

/* kd of diffuse=KD: slot 7 under scattering=single, else 0. */
BB_FN bb_real bb_smith_diffuse(bb_params p) {
    return bb_select(BB_R(0.0), p.v[BB_SMITH_DIFFUSE], p.v[BB_SMITH_SCATTERING] == BB_R(BB_SCATTERING_SINGLE));
}

/* The shadowing slot holds one of microfacet.h's BB_SHADOWING_* (the spec's
 * shadowing=separable|correlated|masking). The rough dielectric's transmitted lobe has a choice
 * of its own, in a slot of its own (ggx.h's BB_GGX_TRANSMISSION_SHADOWING). */

/* D(m) of the distribution. */
BB_FN bb_real bb_smith_d(int dist, bb_vec3 m, bb_real ax, bb_real ay) {
    if (dist == BB_SMITH_BECKMANN) return bb_beckmann_d(m, ax, ay);
    return bb_ggx_d(m, ax, ay);
}

/* Smith G1 = 1 / (1 + Lambda) of the distribution. */
BB_FN bb_real bb_smith_g1(int dist, bb_vec3 w, bb_real ax, bb_real ay) {
    if (dist == BB_SMITH_BECKMANN) return bb_beckmann_g1(w, ax, ay);
    return bb_ggx_g1(w, ax, ay);
}

/* A visible normal of the distribution seen from wo (wo.z > 0). */
BB_FN bb_vec3 bb_smith_sample_vndf(int dist, bb_vec3 wo, bb_real ax, bb_real ay, bb_real u1, bb_real u2) {
    if (dist == BB_SMITH_BECKMANN) return bb_beckmann_sample_vndf(wo, ax, ay, u1, u2);
    return bb_ggx_sample_vndf(wo, ax, ay, u1, u2);
}

/* G2 as the shadowing slot chooses, from the distribution's G1 (microfacet.h). Each form takes
 * its own pair of G1 calls, which the compiler merges: the form the kernels were tuned with
 * (one named pair, or a call through bb_smith_g1, changes the code the compiler lays out). */
BB_FN bb_real bb_smith_g2(int dist, bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_real ax = p.v[BB_SMITH_ALPHA_X], ay = p.v[BB_SMITH_ALPHA_Y];
    bb_real separable, correlated, masking;
    if (dist == BB_SMITH_BECKMANN) {
        separable = bb_g2_separable_from_g1(bb_beckmann_g1(wo, ax, ay), bb_beckmann_g1(wi, ax, ay));
        correlated = bb_g2_correlated_from_g1(bb_beckmann_g1(wo, ax, ay), bb_beckmann_g1(wi, ax, ay));
        masking = bb_beckmann_g1(wo, ax, ay);
    } else {
        separable = bb_g2_separable_from_g1(bb_ggx_g1(wo, ax, ay), bb_ggx_g1(wi, ax, ay));
        correlated = bb_g2_correlated_from_g1(bb_ggx_g1(wo, ax, ay), bb_ggx_g1(wi, ax, ay));
        masking = bb_ggx_g1(wo, ax, ay);
    }
    bb_real g2 = bb_select(separable, correlated, p.v[BB_SMITH_SHADOWING] == BB_R(BB_SHADOWING_CORRELATED));
    return bb_select(g2, masking, p.v[BB_SMITH_SHADOWING] == BB_R(BB_SHADOWING_MASKING));
}

/* f(wo, wi) without the cosine, the Lambert part kd/pi of diffuse=KD included; 0 unless wo and wi
 * are above the horizon (the specular part also unless wh is). */
BB_FN bb_real bb_smith_eval(int dist, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    bb_vec3 wh = bb_normalize(bb_add(wo, wi));
    bb_real d = bb_smith_d(dist, wh, p.v[BB_SMITH_ALPHA_X], p.v[BB_SMITH_ALPHA_Y]);
    bb_real f = bb_fresnel_eval(fkind, fp, bb_clamp_cos(bb_dot(wo, wh)));
    bb_real den = BB_R(4.0) * wo.z * wi.z;
    bb_real v = d * bb_smith_g2(dist, p, wo, wi) * f / bb_select(BB_R(1.0), den, den > BB_R(0.0));
    v = bb_select(BB_R(0.0), v, wh.z > BB_R(0.0)) + bb_smith_diffuse(p) * BB_INV_PI;
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wi.z > BB_R(0.0));
}

/* The specular lobe's visible-normal importance sample and its weight F(wo.wh) G2(wo, wi) / G1(wo). */
BB_FN bb_sample bb_smith_lobe_sample(int dist, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_real ax = p.v[BB_SMITH_ALPHA_X], ay = p.v[BB_SMITH_ALPHA_Y];
    bb_vec3 wh = bb_smith_sample_vndf(dist, wo, ax, ay, u1, u2);
    bb_real cos_oh = bb_clamp_cos(bb_dot(wo, wh));
    bb_vec3 wi = bb_reflect(wo, wh);
    bb_real g1o = bb_smith_g1(dist, wo, ax, ay);
    bb_real w = bb_fresnel_eval(fkind, fp, cos_oh) * bb_smith_g2(dist, p, wo, wi) /
             bb_select(BB_R(1.0), g1o, g1o > BB_R(0.0));
    return bb_make_sample(wi, bb_select(BB_R(0.0), w, wi.z > BB_R(0.0) && g1o > BB_R(0.0)));
}

/* The density of wi under bb_smith_lobe_sample: the visible normals' D_wo(wh) = G1(wo) max(0, wo.wh)
 * D(wh) / wo.z [H18 sec. 2] times the reflection's Jacobian 1 / (4 wo.wh) [Walter et al. 2007 eq. 14],
 * G1(wo) D(wh) / (4 wo.z) with wh = normalize(wo + wi); 0 where wh faces away from wo or the normal. */
BB_FN bb_real bb_smith_lobe_pdf(int dist, bb_params p, bb_vec3 wo, bb_vec3 wi) {
    bb_real ax = p.v[BB_SMITH_ALPHA_X], ay = p.v[BB_SMITH_ALPHA_Y];
    bb_vec3 wh = bb_normalize(bb_add(wo, wi));
    bb_real v = bb_smith_g1(dist, wo, ax, ay) * bb_smith_d(dist, wh, ax, ay) /
                (BB_R(4.0) * bb_select(BB_R(1.0), wo.z, wo.z > BB_R(0.0)));
    return bb_select(BB_R(0.0), v, wo.z > BB_R(0.0) && wh.z > BB_R(0.0) && bb_dot(wo, wh) > BB_R(0.0));
}

/* The importance sample of f = f_spec + kd/pi where kd > 0: the one-sample mixture of the lobe's
 * sampler and the cosine warp (sampling.h), the Lambert part chosen with chance
 * kd / (kd + F(cos theta_o)): the Fresnel term at wo, a bound from above on the lobe's albedo that
 * costs no integral (any chance keeps the weight unbiased). Measured by quadrature of the variance
 * (benchmarks/mixture_variance.py, 240 cells of GGX): the lobe's own albedo E(mu, alpha) in place of
 * F lowers it > 1.2x at 73 cells (alpha >= 0.4), raises it > 1.2x at 11, median 1.04x; c = 1/2 is
 * worse at 148. The weight is the whole f cos over the mixture's density. */
BB_FN bb_sample bb_smith_mixture_sample(int dist, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_real kd = bb_smith_diffuse(p);
    bb_real c = bb_mixture_lambert_chance(kd, bb_fresnel_eval(fkind, fp, bb_clamp_cos(wo.z)));
    bb_real v1 = bb_mixture_rescale(u1, c);
    bb_mask lambert = u1 < c;
    bb_vec3 wl = bb_cosine_hemisphere(v1, u2);
    bb_vec3 ws = bb_reflect(wo, bb_smith_sample_vndf(dist, wo, p.v[BB_SMITH_ALPHA_X], p.v[BB_SMITH_ALPHA_Y], v1, u2));
    bb_vec3 wi = bb_v3(bb_select(ws.x, wl.x, lambert), bb_select(ws.y, wl.y, lambert), bb_select(ws.z, wl.z, lambert));
    bb_real f_cos = bb_smith_eval(dist, p, fkind, fp, wo, wi) * bb_max(wi.z, BB_R(0.0));
    return bb_make_sample(wi, bb_mixture_weight(f_cos, wi.z, c, bb_smith_lobe_pdf(dist, p, wo, wi)));
}

/* The model's sampler: the mixture above where kd > 0, else the lobe's sample. The albedo kernels
 * (kernels/albedo.cl) define BB_SMITH_LOBE_SAMPLER_ONLY: compute_albedo has taken kd out of their
 * cells (host/integrate/albedo.cpp, take_diffuse), so they keep the lobe's sampler without the
 * test per sample (which cost Beckmann's vector path 8% of its CPU time). */
BB_FN bb_sample bb_smith_sample(int dist, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1, bb_real u2) {
#ifndef BB_SMITH_LOBE_SAMPLER_ONLY
    if (bb_any_lane(bb_smith_diffuse(p) > BB_R(0.0))) return bb_smith_mixture_sample(dist, p, fkind, fp, wo, u1, u2);
#endif
    return bb_smith_lobe_sample(dist, p, fkind, fp, wo, u1, u2);
}

/* The coordinate system of the half-vector quadrature (integrands.h): the radial CDF of D cos. */
BB_FN bb_quad_dist bb_smith_quad_dist(int dist, bb_params p) {
    return bb_make_quad_dist(dist == BB_SMITH_BECKMANN ? BB_QUAD_BECKMANN : BB_QUAD_GGX, p.v[BB_SMITH_ALPHA_X],
                             p.v[BB_SMITH_ALPHA_Y], BB_R(0.0));
}

/* The half-vector quadrature's integrand f cos_theta_i 4 (wo.h) / (D cos_theta_h) times
 * djc = D J cos(theta_h) (integrands.h, bb_quad_halfvector_point): with f = D G2 F / (4 co ci)
 * it is F G2 oh / (co ch) djc. f_oh = F(wo.h), oh = wo.h, co = cos_theta_o, ch = cos_theta_h. */
BB_FN bb_real bb_smith_halfvector_weight(int dist, bb_params p, bb_real f_oh, bb_vec3 wo, bb_vec3 wi, bb_real oh, bb_real co,
                                      bb_real ch, bb_real djc) {
    return f_oh * bb_smith_g2(dist, p, wo, wi) * oh / (co * ch) * djc;
}

/* The functions a Smith lobe model registers (model_registry.h: bb_<name>_eval, _sample,
 * _quad_dist and _halfvector_weight), those of the body above with the distribution `dist`:
 * BB_SMITH_LOBE(ggx, BB_SMITH_GGX) in ggx.h, BB_SMITH_LOBE(beckmann, BB_SMITH_BECKMANN) in
 * beckmann.h. */
#define BB_SMITH_LOBE(name, dist)                                                                                \
    BB_FN bb_real bb_##name##_eval(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {                 \
        return bb_smith_eval(dist, p, fkind, fp, wo, wi);                                                        \
    }                                                                                                            \
    BB_FN bb_sample bb_##name##_sample(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1, bb_real u2) {     \
        return bb_smith_sample(dist, p, fkind, fp, wo, u1, u2);                                                  \
    }                                                                                                            \
    BB_FN bb_quad_dist bb_##name##_quad_dist(bb_params p) { return bb_smith_quad_dist(dist, p); }                \
    BB_FN bb_real bb_##name##_halfvector_weight(bb_params p, bb_real f_oh, bb_vec3 wo, bb_vec3 wi, bb_real oh, bb_real co,   \
                                             bb_real ch, bb_real djc) {                                                \
        return bb_smith_halfvector_weight(dist, p, f_oh, wo, wi, oh, co, ch, djc);                               \
    }

#endif /* BRDFBAKE_BRDF_SMITH_H */

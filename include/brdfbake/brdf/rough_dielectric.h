/* Rough dielectric interface (GGX microfacets, Walter et al. 2007): the fractions of the energy
 * arriving from wo that the interface reflects and transmits.
 *
 * wo lies on the upper side (wo.z > 0); eta is the index of the far side relative to the near
 * side (eta > 1: glass seen from air; eta < 1: the same interface seen from inside the glass,
 * with total internal reflection). Directions below the surface are transmitted directions.
 *
 * Estimator: a visible normal wh of GGX seen from wo [H18]. At that microfacet the energy splits
 * into F(wo.wh) reflected and 1 - F transmitted [WMLT07 eq. 22]; both branches are scored (no
 * random choice between them), each weighted by G2 / G1(wo) as in microfacet.h:
 *   R += F G2_R(wo, wr) / G1(wo),        wr = reflect(wo, wh), counted if wr.z > 0
 *   T += (1 - F) G2_T(wo, wt) / G1(wo),  wt = refract(wo, wh, eta), counted if wt.z < 0
 * These are energy (flux) fractions: R + T <= 1, and transmitted radiance is scaled by eta^2
 * on top of T [WMLT07 eq. 21 and Veach 1997 ch. 5]. G2 is separable G1(wo) G1(wi), or
 * height-correlated: 1/(1 + L(wo) + L(wi)) for reflection [H14 eq. 99] and the Beta function
 * B(1 + L(wo), 1 + L(wt)) for transmission [H14 eq. 100], which follows from integrating
 * u^L(wo) (1 - u)^L(wt) over the height CDF u. Two arguments pick the forms: `shadowing`
 * (microfacet.h's BB_SHADOWING_SEPARABLE or _CORRELATED; masking alone has no transmitted form)
 * for both lobes, and under BB_SHADOWING_CORRELATED `transmission_shadowing`
 * (BB_TRANSMISSION_SHADOWING_*) for T: the Beta function (the default), or
 * 1/(1 + L(wo) + L(wt)) as for R, the form Blender
 * Cycles evaluates for both lobes (intern/cycles/kernel/closure/bsdf_microfacet.h), which
 * treats the transmitted direction as if it were reflected and so ignores that a microsurface
 * point seen from above and below at once must lie at a height both can reach; the two forms
 * differ most at grazing angles and high roughness. */
#ifndef BRDFBAKE_BRDF_ROUGH_DIELECTRIC_H
#define BRDFBAKE_BRDF_ROUGH_DIELECTRIC_H

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/sampling.h"

/* The transmission_shadowing argument of the functions below (and the value of ggx.h's
 * BB_GGX_TRANSMISSION_SHADOWING slot): T's G2 when `shadowing` is BB_SHADOWING_CORRELATED. */
#define BB_TRANSMISSION_SHADOWING_BETA 0   /* B(1 + L_o, 1 + L_t) [H14 eq. 100] */
#define BB_TRANSMISSION_SHADOWING_CYCLES 1 /* 1/(1 + L_o + L_t) (Cycles) */

/* Whether T takes the Beta function, whose log Gamma(1 + L_o) the cell computes once. */
BB_FN int bb_dielectric_beta_transmission(int shadowing, int transmission_shadowing) {
    return shadowing == BB_SHADOWING_CORRELATED && transmission_shadowing == BB_TRANSMISSION_SHADOWING_BETA;
}

typedef struct {
    bb_real r; /* reflected energy fraction of this sample */
    bb_real t; /* transmitted energy fraction of this sample */
} bb_rt;

/* Refraction of wo through the microfacet wh (wo.wh = c > 0) into the far side; the direction
 * points away from the surface on the far side. cos_t from sin^2_t = (1 - c^2)/eta^2. Returns
 * the zero vector under total internal reflection. */
BB_FN bb_vec3 bb_refract(bb_vec3 wo, bb_vec3 wh, bb_real c, bb_real eta) {
    bb_real inv_eta = BB_R(1.0) / eta; /* the same for every sample of a cell: computed once */
    bb_real sin2_t = bb_sin2_from_cos(c) * (inv_eta * inv_eta);
    bb_real cos_t = bb_safe_sqrt(BB_R(1.0) - sin2_t);
    bb_vec3 wt = bb_add(bb_scale(wo, -inv_eta), bb_scale(wh, c * inv_eta - cos_t));
    return bb_scale(wt, bb_select(BB_R(1.0), BB_R(0.0), sin2_t >= BB_R(1.0)));
}

/* The Stirling series of log Gamma(z) without its (z - 1/2) log z - z + log(2 pi)/2 part, for
 * z >= 8: 1/(12 z) - 1/(360 z^3) + 1/(1260 z^5) - 1/(1680 z^7) + 1/(1188 z^9), truncation
 * below 691/(360360 z^11) < 2.2e-13. */
BB_FN bb_real bb_stirling_tail_inv(bb_real r) { /* given r = 1/z (the caller has it) */
    bb_real r2 = r * r;
    bb_real s = BB_R(1.0) / BB_R(1680.0) - r2 * (BB_R(1.0) / BB_R(1188.0));
    s = BB_R(1.0) / BB_R(1260.0) - r2 * s;
    s = BB_R(1.0) / BB_R(360.0) - r2 * s;
    return r * (BB_R(1.0) / BB_R(12.0) - r2 * s);
}

/* B(a, b) = Gamma(a) Gamma(b) / Gamma(a + b) for a, b >= 1. log Gamma(a) by the built-in
 * lgamma (a is the same for every sample of a cell: computed once); the rest,
 * D = log Gamma(b) - log Gamma(a + b), from the Stirling series at b' = b + s, c' = a + b + t
 * (shifted by 8 below 8, through Gamma(x + 8) = x (x + 1) ... (x + 7) Gamma(x)) written as a
 * difference, so that no two large logarithms cancel (at b = 1e6 each is about 1.3e7):
 *   D = -(b' - 1/2) log1p(d/b') - d log c' + d + tail(b') - tail(c') - log(P_b / P_c),
 * d = c' - b', P the shift's product (1 without a shift). Branch-free: the vector kernels use it. */
BB_FN bb_real bb_lgamma(bb_real a) {
#ifdef __OPENCL_C_VERSION__
    return lgamma(a);
#else
    return std::lgamma(a);
#endif
}

/* B(a, b) given lga = log Gamma(a) (a cell's constant: the quadrature computes it once). */
BB_FN bb_real bb_beta_lga(bb_real a, bb_real b, bb_real lga) {
    bb_real c = a + b;
    bb_mask sb = b < BB_R(8.0), sc = c < BB_R(8.0);
    bb_real pb = BB_R(1.0), pc = BB_R(1.0);
    for (int k = 0; k < 8; ++k) {
        pb = pb * (b + (bb_real)k);
        pc = pc * (c + (bb_real)k);
    }
    bb_real bs = bb_select(b, b + BB_R(8.0), sb), cs = bb_select(c, c + BB_R(8.0), sc);
    pb = bb_select(BB_R(1.0), pb, sb);
    pc = bb_select(BB_R(1.0), pc, sc);
    /* d = c' - b' from a and the shifts, not by subtracting c' (rounded) from b' */
    bb_real d = a + bb_select(BB_R(0.0), BB_R(8.0), sc) - bb_select(BB_R(0.0), BB_R(8.0), sb);
    /* two divisions for 1/b', 1/c' and P_c / P_b: q = 1/(c' P_b) gives the last two (c' P_b
     * stays below 1e31 where b' does: P_b = 1 from b' = 8 on) */
    bb_real inv_bs = BB_R(1.0) / bs, q = BB_R(1.0) / (cs * pb);
    bb_real diff = -(bs - BB_R(0.5)) * bb_log1p(d * inv_bs) - d * bb_log(cs) + d + bb_stirling_tail_inv(inv_bs) -
                bb_stirling_tail_inv(q * pb);
    /* exp(-log(P_b / P_c)) as the quotient itself: P_c / P_b lies within 1e-8 and 1e9 */
    return bb_exp(lga + diff) * (pc * cs * q);
}

BB_FN bb_real bb_beta(bb_real a, bb_real b) { return bb_beta_lga(a, b, bb_lgamma(a)); }

/* The split of the energy arriving from wo at one microfacet wh (wo.wh > 0) [WMLT07 eq. 22]:
 * F G2_R(wo, wr) reflected into wr = reflect(wo, wh) where wr.z > 0, and (1 - F) G2_T(wo, wt)
 * transmitted into wt = refract(wo, wh, eta) where wt.z < 0 and there is no total internal
 * reflection (the shadowing forms of the head of this file). g1o = G1(wo), lo = Lambda(wo) and
 * lga_o = log Gamma(1 + lo) are the cell's (bb_rough_dielectric_cell). The
 * importance sampler (below) divides both by G1(wo), the visible-normal density having taken
 * G1(wo) D(wh) (wo.wh) / wo.z; the quadrature (dielectric_quadrature.h) multiplies them by
 * D(wh) (wo.wh) / wo.z. Branch-free: the vector kernels evaluate it on float16/double8 lanes. */
BB_FN bb_rt bb_rough_dielectric_split(bb_vec3 wo, bb_vec3 wh, bb_real ax, bb_real ay, bb_real eta, int shadowing,
                                      int transmission_shadowing, bb_real g1o, bb_real lo, bb_real lga_o) {
    bb_rt out;
    bb_real c = bb_clamp(bb_dot(wo, wh), BB_R(0.0), BB_R(1.0));
    bb_real f = bb_fresnel_dielectric(c, eta);

    bb_vec3 wr = bb_reflect(wo, wh);
    /* each G2 from its own G1 calls, merged by the compiler (as bb_smith_g2) */
    bb_real g1r = bb_ggx_g1(wr, ax, ay);
    bb_real g2r = bb_select(bb_g2_separable_from_g1(g1o, g1r), bb_g2_correlated_from_g1(g1o, g1r),
                         shadowing == BB_SHADOWING_CORRELATED);
    out.r = bb_select(BB_R(0.0), f * g2r, wr.z > BB_R(0.0));

    bb_vec3 wt = bb_refract(wo, wh, c, eta);
    bb_vec3 wt_up = bb_v3(wt.x, wt.y, -wt.z); /* masking from below mirrors the direction */
    /* the shadowing arguments are the same for every sample (and every lane): only their branch
     * is computed (the Beta function's log-gammas are the costliest part of a sample) */
    bb_real g2t;
    if (bb_dielectric_beta_transmission(shadowing, transmission_shadowing)) {
        /* G1(wt) = 1 / (1 + lt) > 0 where wt_up.z > 0 and lt is finite (it is not where
         * 2z(s + z) underflows, as G1's closed form then gives 0) */
        bb_real lt = bb_ggx_lambda(wt_up, ax, ay);
        g2t = bb_select(BB_R(0.0), bb_beta_lga(BB_R(1.0) + lo, BB_R(1.0) + lt, lga_o),
                        g1o > BB_R(0.0) && wt_up.z > BB_R(0.0) && lt < BB_R(1e30));
    } else {
        bb_real g1t = bb_ggx_g1(wt_up, ax, ay);
        g2t = g1o * g1t;
        if (shadowing == BB_SHADOWING_CORRELATED) /* and BB_TRANSMISSION_SHADOWING_CYCLES */
            g2t = bb_select(BB_R(0.0), bb_g2_correlated_from_g1(g1o, g1t), g1o > BB_R(0.0) && g1t > BB_R(0.0));
    }
    out.t = bb_select(BB_R(0.0), (BB_R(1.0) - f) * g2t, wt.z < BB_R(0.0));
    return out;
}

/* One sample of the reflected and transmitted fractions from the disk point d of the visible-
 * normal warp (bb_disk_polar(u1, u2); cell-independent: the vector kernel tabulates it).
 * Branch-free: the vector kernel evaluates it on float16/double8 lanes. */
BB_FN bb_rt bb_rough_dielectric_sample_disk(bb_vec3 wo, bb_real ax, bb_real ay, bb_real eta, int shadowing,
                                            int transmission_shadowing, bb_vec2 d) {
    bb_vec3 wh = bb_ggx_sample_vndf_disk(wo, ax, ay, d);
    bb_real g1o = bb_ggx_g1(wo, ax, ay);
    bb_real inv_g1o = BB_R(1.0) / bb_select(BB_R(1.0), g1o, g1o > BB_R(0.0));
    bb_real lo = bb_ggx_lambda(wo, ax, ay);
    bb_rt out = bb_rough_dielectric_split(wo, wh, ax, ay, eta, shadowing, transmission_shadowing, g1o, lo,
                                          bb_dielectric_beta_transmission(shadowing, transmission_shadowing)
                                              ? bb_lgamma(BB_R(1.0) + lo)
                                              : BB_R(0.0));
    out.r = bb_select(BB_R(0.0), out.r * inv_g1o, g1o > BB_R(0.0));
    out.t = bb_select(BB_R(0.0), out.t * inv_g1o, g1o > BB_R(0.0));
    return out;
}

/* One sample of the reflected and transmitted fractions; u1, u2 in [0, 1). */
BB_FN bb_rt bb_rough_dielectric_sample(bb_vec3 wo, bb_real ax, bb_real ay, bb_real eta, int shadowing,
                                       int transmission_shadowing, bb_real u1, bb_real u2) {
    return bb_rough_dielectric_sample_disk(wo, ax, ay, eta, shadowing, transmission_shadowing, bb_disk_polar(u1, u2));
}

#endif /* BRDFBAKE_BRDF_ROUGH_DIELECTRIC_H */

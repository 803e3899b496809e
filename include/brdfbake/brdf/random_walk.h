/* Multiple scattering on the Smith microsurface by random walk, conductor case:
 * [HHdD16] Heitz, Hanika, d'Eon, Dachsbacher, "Multiple-Scattering Microfacet BSDFs with the
 * Smith Model", ACM TOG 35(4) (SIGGRAPH 2016).
 *
 * The Smith microsurface is a volume-like medium of microfacets: heights h with the uniform
 * height distribution P1(h) = 1/2 on [-1, 1] (CDF C1(h) = (h + 1)/2, the paper's choice; the
 * BSDF does not depend on it), normals with the distribution D of the model (GGX or Beckmann,
 * isotropic or anisotropic), and Smith's uncorrelated heights and normals. A ray leaves a point at
 * height h in direction w; then
 *   - (height sampling) the probability that it crosses height h' > h unoccluded (w upward) is
 *     (C1(h)/C1(h'))^Lambda(w), so that it escapes with probability G1(w, h) = C1(h)^Lambda(w)
 *     [HHdD16, the height-dependent masking of the microsurface; H14 sec. 5.3], and the next
 *     intersection height inverts that CDF:  C1(h') = C1(h) (1 - U)^(-1/Lambda(w)).
 *     A downward ray (w.z < 0) uses the same inversion with Lambda(-w) = -1 - Lambda(w) [HHdD16,
 *     the Smith Lambda of a downward direction]: C1(h') = C1(h) (1 - U)^(1/(1 + Lambda(|w|))) < C1(h),
 *     and never escapes.
 *   - (direction sampling) at the intersection the microfacet normal m is one visible from -w:
 *     density D_{-w}(m) = <-w, m> D(m) / integral of <-w, m'> D(m') dm' (the distribution of
 *     visible normals of a direction of either hemisphere [HHdD16, the microflake-like phase
 *     function of a conductor]); the ray reflects, w' = reflect(-w, m), and the walk's weight is
 *     multiplied by F(<-w, m>) (the Fresnel term of --fresnel, fresnel.h).
 * The walk enters from above the surface (C1 = 1) along -wo; the weight it carries out after k
 * scatterings is its order-k contribution to the directional albedo E(wo) = integral of
 * f cos(theta_i) over the hemisphere; k = 1 is the height-correlated Smith microfacet BRDF's
 * albedo (G2 of [H14 eq. 99]). After `bounces` scatterings a walk still inside is cut off: its
 * weight is returned as `cutoff`, never dropped.
 *
 * The heights are tracked as lc = log C1(h) <= 0 (no underflow of C1 however deep a walk goes):
 * escape iff log(1 - U) <= Lambda(w) lc, else lc' = lc - log(1 - U)/Lambda(w).
 *
 * Visible normals of a direction below the horizon: GGX's sampler [H18] covers the whole sphere
 * of view directions (its projected-area parameterisation with s = (1 + vh.z)/2 < 1/2 keeps the
 * lifted normal at or above the horizon); Beckmann's slope sampler [HD14 sec. 4, J14] is written
 * for theta in [0, pi], and is called here with the signed cosine, down to a limit
 * (BB_WALK_BECKMANN_MIN_COS, where its erf-domain inversion loses its digits).
 *
 * The random numbers: Philox4x32-10 (Random123, Salmon et al. 2011), one call per scattering,
 * counter (walk, replica, cell stream, BB_WALK_TAG | scattering), so that a walk's numbers depend
 * on its cell's identity and its index only, never on which cells share a launch.
 *
 * [H14], [HD14], [J14], [H18]: see microfacet.h. */
#ifndef BRDFBAKE_BRDF_RANDOM_WALK_H
#define BRDFBAKE_BRDF_RANDOM_WALK_H

#include "brdfbake/brdf/rough_dielectric.h"
#include "brdfbake/brdf/smith.h"

/* Random123's Philox (a kernel that includes this header is built with -D BB_PHILOX and its -I). */
#include <Random123/philox.h>

/* Parameter slots of a Smith lobe used by the walk (beside smith.h's 0-2 and ggx.h's 3; smith.h
 * names slot 4, BB_SMITH_SCATTERING, and BB_SCATTERING_SINGLE/MULTIPLE). */
#define BB_SMITH_BOUNCES 5    /* the walk's bounce limit (scatterings per walk) */
#define BB_SMITH_WALK_ETA 6   /* 0: a conductor walk; > 0: the dielectric walk's relative index eta */
#define BB_SMITH_WALK_ETA_M1 7 /* eta - 1, from the host in double (its digits near eta = 1) */
#define BB_WALK_DEFAULT_BOUNCES 100
#define BB_WALK_MAX_BOUNCES 100000

/* The fourth counter word of a walk's Philox stream: "w" in the top byte, the scattering below. */
#define BB_WALK_TAG 0x77000000u

/* The steepest downward view (stretched cosine) whose visible normals Beckmann's sampler draws
 * (bb_walk_sample_vndf). */
#define BB_WALK_BECKMANN_MIN_COS BB_R(-0.9)

/* Signed Smith Lambda of a ray direction w (either hemisphere): Lambda(w) for w.z > 0 [H14 eq. 86
 * (GGX), eq. 72 (Beckmann), with eq. 80 for the anisotropic projected roughness], and
 * Lambda(w) = -1 - Lambda(-w) for w.z <= 0 [HHdD16]. +-inf at the horizon, 0 and -1 at the poles. */
BB_FN bb_real bb_walk_lambda(int dist, bb_vec3 w, bb_real ax, bb_real ay) {
    bb_real l = dist == BB_SMITH_BECKMANN ? bb_beckmann_lambda(w, ax, ay) : bb_ggx_lambda(w, ax, ay);
    return bb_select(BB_R(-1.0) - l, l, w.z > BB_R(0.0));
}

/* A visible normal of the direction v of either hemisphere (v points away from the surface, to
 * where the ray came from): density <v, m> D(m) / (its integral) over m with <v, m> > 0, m.z >= 0. */
BB_FN bb_vec3 bb_walk_sample_vndf(int dist, bb_vec3 v, bb_real ax, bb_real ay, bb_real u1, bb_real u2) {
    if (dist == BB_SMITH_BECKMANN) {
        /* [HD14 sec. 4] as bb_beckmann_sample_vndf, with the signed cosine of the stretched v.
         * Its CDF, in the erf domain, is (1 + b + tan/sqrt(pi) exp(-x^2)) / (1 + erf(cot) + ...):
         * as the view turns straight down, 1 + erf(cot) cancels (at stretched cos = -0.95 the
         * float inversion is off by 4e-2 in the CDF, at -0.9 by 5e-5). Views steeper than
         * BB_WALK_BECKMANN_MIN_COS are sampled as from that cone's edge, the same azimuth: a
         * ray that steep upward hits a microfacet rarely (Beckmann's Lambda < 2e-4 there). Exactly
         * horizontal views (a reflection can round to one) are taken 1e-6 off the horizon: the
         * sampler's tan = sin/cos needs cos != 0. */
        bb_vec3 s11 = bb_normalize(bb_v3(ax * v.x, ay * v.y, v.z));
        bb_real z = bb_max(s11.z, BB_WALK_BECKMANN_MIN_COS);
        z = bb_select(z, bb_select(BB_R(-1e-6), BB_R(1e-6), z >= BB_R(0.0)), bb_fabs(z) < BB_R(1e-6));
        bb_real r = bb_sqrt(s11.x * s11.x + s11.y * s11.y);
        bb_real k = bb_safe_sqrt(BB_R(1.0) - z * z) / bb_select(r, BB_R(1.0), r <= BB_R(0.0));
        s11 = bb_v3(bb_select(s11.x * k, k, r <= BB_R(0.0)), s11.y * k, z);
        return bb_beckmann_sample_vndf_stretched(s11, z, ax, ay, u1, u2);
    }
    return bb_ggx_sample_vndf(v, ax, ay, u1, u2);
}

/* What one walk carries out of the microsurface. */
typedef struct {
    bb_real energy; /* the weight that escaped (every order up to the limit) */
    bb_real single; /* the part of it that escaped after one scattering */
    bb_real cutoff; /* the weight still inside after `bounces` scatterings */
    bb_real transmitted; /* dielectric: the weight that escaped below the surface (0 for a conductor) */
    bb_real single_t;    /* dielectric: the part of it transmitted after one scattering */
    bb_real f_cos;        /* next-event estimate of f(wo, target) target.z (every order; 0 without a target) */
    bb_real f_cos_single; /* its first order */
    int bad;        /* 1 if the walk met a non-finite number (its weights are then 0) */
} bb_walk_result;

/* A walk's result before it ends: nothing escaped, nothing cut off. */
BB_FN bb_walk_result bb_walk_result_zero(void) {
    bb_walk_result r;
    r.energy = r.single = r.cutoff = r.transmitted = r.single_t = r.f_cos = r.f_cos_single = BB_R(0.0);
    r.bad = 0;
    return r;
}

/* The evaluation of f by the walk [HHdD16 sec. 4.2 and its eval(): next-event estimation]: at each
 * intersection (height lc = log C1(h), the ray's direction w, v = -w) the walk adds its weight times
 * the phase function towards the target t (t.z > 0) times the probability that t leaves the
 * microsurface from that height unoccluded, C1(h)^Lambda(t) = exp(Lambda(t) lc) (the height sampling
 * above). The sum's expectation is the density of the directions the walks leave by, per solid
 * angle: f(wo, t) t.z (light from wo, its flux leaving towards t). Its first term alone is the
 * height-correlated Smith lobe's f t.z (the first intersection's height has density
 * (1 + Lambda(wo)) C1^Lambda(wo) in C1, so that E[C1^Lambda(t)] = (1 + Lambda(wo)) / (1 + Lambda(wo) + Lambda(t))).
 *
 * The projected area of the microsurface seen from v (either hemisphere) [HHdD16 eq. 3 and the
 * Lambda of a downward direction]: sigma(v) = integral of <v, m>+ D(m) dm = v.z (1 + Lambda(v)),
 * Lambda signed (bb_walk_lambda); the visible normals' density is D_v(m) = <v, m>+ D(m) / sigma(v). */
BB_FN bb_real bb_walk_sigma(int dist, bb_vec3 v, bb_real ax, bb_real ay) {
    return v.z * (BB_R(1.0) + bb_walk_lambda(dist, v, ax, ay));
}

/* The reflection phase function without its Fresnel factor, from v towards t [HHdD16 eq. 16 (the
 * conductor's microflake phase function)]: D_v(h) / (4 <v, h>) = D(h) / (4 sigma(v)), h the half
 * vector of v and t, 0 unless h lies above the mean surface; with <v, h>, which the caller's Fresnel
 * term takes, in *vh. */
BB_FN bb_real bb_walk_reflect_phase(int dist, bb_vec3 v, bb_vec3 t, bb_real ax, bb_real ay, bb_real* vh) {
    bb_vec3 s = bb_add(v, t);
    bb_real n2 = bb_dot(s, s);
    bb_vec3 h = bb_scale(s, BB_R(1.0) / bb_sqrt(bb_select(BB_R(1.0), n2, n2 > BB_R(0.0))));
    *vh = bb_dot(v, h);
    bb_real sigma = bb_walk_sigma(dist, v, ax, ay);
    bb_real ph = bb_smith_d(dist, h, ax, ay) / (BB_R(4.0) * bb_select(BB_R(1.0), sigma, sigma > BB_R(0.0)));
    return bb_select(BB_R(0.0), ph, n2 > BB_R(0.0) && h.z > BB_R(0.0) && *vh > BB_R(0.0) && sigma > BB_R(0.0));
}

/* The refraction phase function without its (1 - F) factor, from v (the near side) to o (the far
 * side, o.z < 0) through an interface of relative index e (far over near) [HHdD16 sec. 5;
 * WMLT07 eq. 16 and 17]: D_v(h) times the Jacobian e^2 |<o, h>| / (<v, h> + e <o, h>)^2, h the
 * generalized half vector +-(v + e o) turned above the mean surface, 0 unless <v, h> > 0 > <o, h>;
 * <v, h> in *vh. */
BB_FN bb_real bb_walk_refract_phase(int dist, bb_vec3 v, bb_vec3 o, bb_real e, bb_real ax, bb_real ay, bb_real* vh) {
    bb_vec3 s = bb_add(v, bb_scale(o, e));
    bb_real n2 = bb_dot(s, s);
    bb_vec3 h = bb_scale(s, bb_select(BB_R(1.0), BB_R(-1.0), s.z < BB_R(0.0)) /
                                bb_sqrt(bb_select(BB_R(1.0), n2, n2 > BB_R(0.0))));
    *vh = bb_dot(v, h);
    bb_real oh = bb_dot(o, h), den = *vh + e * oh;
    bb_real sigma = bb_walk_sigma(dist, v, ax, ay);
    bb_real ph = bb_smith_d(dist, h, ax, ay) * *vh / bb_select(BB_R(1.0), sigma, sigma > BB_R(0.0)) * e * e *
                 bb_fabs(oh) / bb_select(BB_R(1.0), den * den, den != BB_R(0.0));
    return bb_select(BB_R(0.0), ph,
                     n2 > BB_R(0.0) && h.z > BB_R(0.0) && *vh > BB_R(0.0) && oh < BB_R(0.0) && sigma > BB_R(0.0) &&
                         den != BB_R(0.0));
}

/* The fourth counter word of the second Philox call per scattering of an evaluation walk (the
 * direction drawn from the target's side, bb_walk_conductor). */
#define BB_WALK_NEE_TAG 0x65000000u
/* The dielectric evaluation walk's Russian roulette (bb_walk_dielectric): its counter word's tag,
 * and the weight below which a walk survives with probability weight / BB_WALK_ROULETTE_WEIGHT. */
#define BB_WALK_ROULETTE_TAG 0x72000000u
#define BB_WALK_ROULETTE_WEIGHT BB_R(0.05)

/* The bracket of bb_walk_next_nee below: the probability that a ray leaving height lc = log C1(h)
 * in direction w (signed Lambda l) meets the microsurface, weighted by the masking C1(h')^lt of the
 * target from the intersection, over exp(-lt x), x = -lc (see there). */
BB_FN bb_real bb_walk_hit_average(bb_real l, bb_real x, bb_real lt) {
    bb_real d = l - lt;
    bb_real down = BB_R(1.0) / (BB_R(1.0) + lt / bb_fabs(l)); /* |L| / (|L| + lt), 1 at the horizon */
    bb_real dx = d * x;
    bb_real up = bb_select(-l * bb_expm1(-dx) / bb_select(d, BB_R(1.0), d == BB_R(0.0)),
                           l * x * (BB_R(1.0) - BB_R(0.5) * dx), bb_fabs(dx) < BB_R(1e-6));
    return bb_select(down, up, l > BB_R(0.0));
}

/* The next-event estimate at the next intersection of a ray leaving height lc = log C1(h) in
 * direction w, averaged over where that intersection lies (the height sampling above, in closed
 * form): the reflection phase function from v = -w towards t, its Fresnel term, and the masking of t
 * from the intersection, C1(h')^Lambda(t), times the probability of the intersection; 0 for the part
 * of the rays that escape. With lc' = lc + E / L (E exponential, L = bb_walk_lambda(w) signed, lt =
 * Lambda(t), x = -lc >= 0):
 *   L < 0 (downward, never escapes): E[C1(h')^lt] = exp(-lt x) |L| / (|L| + lt);
 *   L > 0 (upward, escapes when E > L x): E[C1(h')^lt; hit] = exp(-lt x) (1 - exp(-(L - lt) x)) / (1 - lt / L).
 * For an upward w the phase function's 1/sigma(v) = 1/(|w.z| L) cancels against the factor L of the
 * hit probability: the average is bounded where the sampled intersection's estimate is not. For
 * Beckmann, whose Lambda of a steep upward ray is exponentially small (sigma(v) ~ exp(-cot^2/alpha^2)),
 * the sampled estimate has infinite variance: rare walks that reach such a height carry most of
 * f (walk4: 85% of the second order in 1e-4 of the walks at theta 7.5 / 67.5 deg, alpha 0.4), and
 * the replicas' error hides it. Without the bracket's expected factor this is [HHdD16]'s eval(). */
BB_FN bb_real bb_walk_next_nee(int dist, bb_vec3 w, bb_real lc, bb_vec3 t, bb_real lt, int fkind, bb_params fp,
                               bb_real ax, bb_real ay) {
    bb_real vh;
    bb_real ph = bb_walk_reflect_phase(dist, bb_scale(w, BB_R(-1.0)), t, ax, ay, &vh);
    bb_real l = bb_walk_lambda(dist, w, ax, ay), x = -lc;
    bb_real nee = ph * bb_fresnel_eval(fkind, fp, bb_clamp_cos(vh)) * bb_exp(-lt * x) * bb_walk_hit_average(l, x, lt);
    return bb_select(BB_R(0.0), nee, ph > BB_R(0.0));
}

/* One random walk from the view wo (wo.z > 0) on the microsurface of the Smith lobe `dist` with
 * parameters p (alpha in BB_SMITH_ALPHA_X/Y), the Fresnel term (fkind, fp) at every scattering and
 * at most `bounces` scatterings; its random numbers from Philox with `key` and the counter words
 * (walk, rep, stream). With target.z > 0 it also estimates f(wo, target) target.z (r.f_cos, the
 * next-event estimation above, each intersection's estimate averaged over its height,
 * bb_walk_next_nee): the first intersection's in closed form (the height-correlated lobe's f exactly,
 * r.f_cos_single), each later one at the intersection before it, over the direction towards it by
 * multiple importance sampling [Veach 1997, the balance heuristic] of two directions: the walk's own
 * (the phase function from v) and one drawn from the target's side (a visible normal of the target,
 * its reflection reversed: density the phase function from the target towards -w). The second
 * catches the paths the walk's own directions rarely take but the target's phase function favours
 * (from near-normal wo to a grazing target: the first scattering must turn the ray to grazing). */
BB_FN bb_walk_result bb_walk_conductor(int dist, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 target,
                                       int bounces, philox4x32_key_t key, unsigned int walk, unsigned int rep,
                                       unsigned int stream) {
    bb_real ax = p.v[BB_SMITH_ALPHA_X], ay = p.v[BB_SMITH_ALPHA_Y];
    bb_walk_result r = bb_walk_result_zero();
    bb_vec3 w = bb_scale(wo, BB_R(-1.0)); /* the ray's direction */
    bb_real lc = BB_R(0.0);               /* log C1(h): above the surface */
    bb_real weight = BB_R(1.0);
    const int eval = target.z > BB_R(0.0);
    bb_real lt = bb_walk_lambda(dist, target, ax, ay);
    if (eval && bounces > 0) { /* the first intersection's next event, in closed form */
        r.f_cos_single = bb_walk_next_nee(dist, w, lc, target, lt, fkind, fp, ax, ay);
        r.f_cos = r.f_cos_single;
    }
    for (int k = 0;; ++k) {
        philox4x32_ctr_t ctr = {{walk, rep, stream, BB_WALK_TAG | (unsigned int)k}};
        philox4x32_ctr_t u = philox4x32(ctr, key);
        /* height sampling: escape, or the next intersection */
        bb_real l = bb_log1p(-bb_unit_from_bits(u.v[0])); /* log(1 - U) <= 0 */
        bb_real lambda = bb_walk_lambda(dist, w, ax, ay);
        if (w.z > BB_R(0.0) && l <= lambda * lc) {
            r.energy = weight;
            r.single = k == 1 ? weight : BB_R(0.0);
            break;
        }
        if (k == bounces) {
            r.cutoff = weight;
            break;
        }
        lc = lc - l / lambda;
        bb_vec3 v = bb_scale(w, BB_R(-1.0));
        /* direction sampling: a visible normal of -w, reflection, the Fresnel term */
        bb_vec3 m = bb_walk_sample_vndf(dist, v, ax, ay, bb_unit_from_bits(u.v[1]), bb_unit_from_bits(u.v[2]));
        bb_real c = bb_dot(v, m);
        bb_vec3 wa = bb_reflect(v, m);
        if (eval && k + 1 < bounces) { /* the next intersection's next event, two directions (above) */
            philox4x32_ctr_t ctr2 = {{walk, rep, stream, BB_WALK_NEE_TAG | (unsigned int)k}};
            philox4x32_ctr_t u2 = philox4x32(ctr2, key);
            bb_vec3 mb = bb_walk_sample_vndf(dist, target, ax, ay, bb_unit_from_bits(u2.v[0]),
                                             bb_unit_from_bits(u2.v[1]));
            bb_vec3 wb = bb_scale(bb_reflect(target, mb), BB_R(-1.0));
            bb_real vha, vhb, ignored;
            bb_real paa = bb_walk_reflect_phase(dist, v, wa, ax, ay, &vha);
            bb_real pba = bb_walk_reflect_phase(dist, target, bb_scale(wa, BB_R(-1.0)), ax, ay, &ignored);
            bb_real pab = bb_walk_reflect_phase(dist, v, wb, ax, ay, &vhb);
            bb_real pbb = bb_walk_reflect_phase(dist, target, bb_scale(wb, BB_R(-1.0)), ax, ay, &ignored);
            bb_real ea = bb_fresnel_eval(fkind, fp, bb_clamp_cos(vha)) * paa *
                         bb_walk_next_nee(dist, wa, lc, target, lt, fkind, fp, ax, ay);
            bb_real eb = bb_fresnel_eval(fkind, fp, bb_clamp_cos(vhb)) * pab *
                         bb_walk_next_nee(dist, wb, lc, target, lt, fkind, fp, ax, ay);
            bb_real nee = bb_select(BB_R(0.0), ea / (paa + pba), paa + pba > BB_R(0.0)) +
                          bb_select(BB_R(0.0), eb / (pab + pbb), pab + pbb > BB_R(0.0));
            r.f_cos += weight * nee;
        }
        weight = weight * bb_fresnel_eval(fkind, fp, bb_clamp_cos(c));
        w = wa;
        if (!(bb_isfinite(lc) || lc < BB_R(0.0)) || !bb_isfinite(w.z) || !bb_isfinite(weight)) {
            r.bad = 1;
            break;
        }
    }
    return r;
}

/* The half step of bb_unit_from_bits's grid (2^-24 in float, 2^-32 in double): the height a draw
 * u = 0 stands for (bb_walk_flip_height). */
#ifdef BB_REAL_IS_FLOAT
#define BB_WALK_HALF_STEP BB_R(2.98023223876953125e-8)
#else
#define BB_WALK_HALF_STEP BB_R(1.16415321826934814e-10)
#endif

/* log C1(-h) = log(1 - C1(h)) from lc = log C1(h) < 0: the height seen from the other side of the
 * microsurface (heights mirrored, C1 uniform). log(-expm1(lc)) near the top, log1p(-exp(lc)) below.
 * The top itself, lc = 0 (the first intersection of a walk whose height draw is u = 0 exactly: the
 * uniform grid's first point, probability 2^-24 in float), has no mirror: C1 = 0, lc = -inf, a height
 * from which every later height average, hit probability and Lambda(w) lc is inf - inf or 0 * inf
 * (walk6: a NaN in `check` of Beckmann alpha 0.3, eta 1.5 in float, where the steep upward ray's Lambda
 * underflows to 0). That draw stands for the grid cell [0, 2 BB_WALK_HALF_STEP): it is taken at the
 * cell's middle, lc = -BB_WALK_HALF_STEP (at most; the height's density there is bounded). */
BB_FN bb_real bb_walk_flip_height(bb_real lc) {
    lc = bb_min(lc, -BB_WALK_HALF_STEP);
    return bb_select(bb_log1p(-bb_exp(lc)), bb_log(-bb_expm1(lc)), lc > BB_R(-0.6931471805599453));
}

/* The rough dielectric's relative indices: the upper (outside) side's eta, the lower's 1/eta, each
 * with its e - 1 exact (1/eta - 1 = -(eta - 1)/eta). The next-event functions below take [1] as the
 * target's side: for a target below the surface (the transmitted f_t) the two are swapped and
 * flip = 1 (bb_walk_dielectric), their `up` then meaning "on the target's side"; flip tells them
 * the physical upper side, where an evaluation walk's first direction has its mixture
 * (bb_walk_mix_pdf). */
typedef struct {
    bb_real e[2], em1[2]; /* [1]: the upper side (the target's), [0]: the lower */
    int flip;             /* 1: [1] is the physical lower side (the target below) */
} bb_walk_etas;

/* The unpolarised dielectric Fresnel term at cos c for relative index e (em1 = e - 1). */
BB_FN bb_real bb_walk_fresnel_dielectric(bb_real c, bb_real e, bb_real em1) {
    bb_fresnel_sp fr = bb_fresnel_dielectric_sp_m1(bb_clamp_cos(c), e, em1);
    return BB_R(0.5) * (fr.rs + fr.rp);
}

/* The next event at the next intersection of a ray on the dielectric microsurface (in the frame of
 * the side it travels in, `up` that side: direction w, height lc), towards the target t (above the
 * surface, Lambda lt), averaged over where that intersection lies. On the upper side: the
 * reflection phase function towards t times F, the height average in closed form
 * (bb_walk_hit_average). On the lower side: the refraction phase function out towards t (-t in that
 * frame) times 1 - F, and t masked from the height seen from above, (1 - C1(h'))^lt, which has no
 * closed-form average: the intersection is drawn (u) given that the ray meets the microsurface and
 * the estimate multiplied by that probability, 1 - C1(h)^L for an upward ray (L > 0), 1 downward,
 * which cancels the phase function's 1/sigma(v) = 1/(w.z L) as the closed form does above. */
BB_FN bb_real bb_walk_dielectric_next_nee(int dist, bb_vec3 w, bb_real lc, int up, bb_vec3 t, bb_real lt,
                                          bb_walk_etas et, bb_real ax, bb_real ay, bb_real u) {
    bb_real vh;
    bb_vec3 v = bb_scale(w, BB_R(-1.0));
    bb_real l = bb_walk_lambda(dist, w, ax, ay);
    if (up) {
        bb_real ph = bb_walk_reflect_phase(dist, v, t, ax, ay, &vh);
        bb_real nee = ph * bb_walk_fresnel_dielectric(vh, et.e[1], et.em1[1]) * bb_exp(lt * lc) *
                      bb_walk_hit_average(l, -lc, lt);
        return bb_select(BB_R(0.0), nee, ph > BB_R(0.0));
    }
    bb_real ph = bb_walk_refract_phase(dist, v, bb_scale(t, BB_R(-1.0)), et.e[0], ax, ay, &vh);
    bb_real p_hit = bb_select(BB_R(1.0), -bb_expm1(l * lc), l > BB_R(0.0));
    bb_real lc_hit = lc - bb_log1p(-p_hit * u) / l;
    bb_real mask = bb_select(BB_R(1.0), bb_exp(lt * bb_walk_flip_height(lc_hit)), lt > BB_R(0.0));
    bb_real nee = ph * (BB_R(1.0) - bb_walk_fresnel_dielectric(vh, et.e[0], et.em1[0])) * p_hit * mask;
    return bb_select(BB_R(0.0), nee, ph > BB_R(0.0));
}

/* The density of a direction w leaving an intersection of the dielectric microsurface, in the frame
 * of the side `up` the intersection lies on, seen from v there: w crossing to the other side
 * (`cross`) by refraction, (1 - F) times the refraction phase function, else by reflection, F times
 * the reflection phase function (the walk samples exactly this: the weight stays 1). */
BB_FN bb_real bb_walk_dielectric_pdf(int dist, bb_vec3 v, bb_vec3 w, int up, int cross, bb_walk_etas et, bb_real ax,
                                     bb_real ay) {
    bb_real vh;
    if (cross) {
        bb_real ph = bb_walk_refract_phase(dist, v, w, et.e[up], ax, ay, &vh);
        return bb_select(BB_R(0.0), ph * (BB_R(1.0) - bb_walk_fresnel_dielectric(vh, et.e[up], et.em1[up])),
                         ph > BB_R(0.0));
    }
    bb_real ph = bb_walk_reflect_phase(dist, v, w, ax, ay, &vh);
    return bb_select(BB_R(0.0), ph * bb_walk_fresnel_dielectric(vh, et.e[up], et.em1[up]), ph > BB_R(0.0));
}

/* Whether bb_walk_sample_vndf draws exactly the visible normals of the view v (its density is
 * D_v): always for GGX; for Beckmann down to BB_WALK_BECKMANN_MIN_COS (the stretched cosine). */
BB_FN int bb_walk_vndf_exact(int dist, bb_vec3 v, bb_real ax, bb_real ay) {
    bb_vec3 s11 = bb_normalize(bb_v3(ax * v.x, ay * v.y, v.z));
    return dist != BB_SMITH_BECKMANN || s11.z >= BB_WALK_BECKMANN_MIN_COS;
}

/* The density of the direction an evaluation walk draws at its first intersection (a defensive
 * mixture [Hesterberg 1995]): with probability mix uniform over the upper hemisphere (a reflection,
 * reflect_up), else by the phase function (density p); mix = 0 at every later intersection. */
BB_FN bb_real bb_walk_mix_pdf(bb_real p, bb_real mix, bb_vec3 w, int reflect_up) {
    bb_real g = bb_select(BB_R(0.0), BB_R(0.5) / BB_PI, reflect_up && w.z > BB_R(0.0));
    return (BB_R(1.0) - mix) * p + mix * g;
}

/* The density with which the entry strategy (bb_walk_dielectric_entry) draws a path's two segments
 * around an intersection x1 on the upper side: the ray arrives from x0 along a (upper frame) and
 * refracts into the glass along w (upper frame) towards x2, from which the next event leaves
 * towards t. It draws w reversed from t (t's visible normal, always refracted: density pt, the
 * refraction phase function from t without its 1 - F), then a reversed from x1 (a visible normal of
 * the view w seen from below, -w, always refracted out: density q, the refraction phase function
 * from -w to -a through 1/eta); 0 where the samplers are not exact (bb_walk_vndf_exact). */
BB_FN bb_real bb_walk_entry_pdf(int dist, bb_vec3 a, bb_vec3 w, bb_vec3 t, bb_walk_etas et, bb_real ax, bb_real ay) {
    bb_real vh;
    bb_vec3 d = bb_scale(w, BB_R(-1.0)); /* t's refraction into the glass */
    bb_real pt = bb_walk_refract_phase(dist, t, d, et.e[1], ax, ay, &vh);
    bb_real q = bb_walk_refract_phase(dist, d, a, et.e[0], ax, ay, &vh);
    return bb_select(BB_R(0.0), pt * q, bb_walk_vndf_exact(dist, d, ax, ay));
}

/* The next intersection's next event of a dielectric walk at an intersection (side `up`, height lc,
 * v towards where the ray came from, in that side's frame), over the direction towards the next
 * intersection by multiple importance sampling [Veach 1997, the balance heuristic] of two
 * directions: the walk's own wa (crossing to the other side if cross_a) and one drawn from the
 * target's side: a visible normal of t, then reflection (F) or refraction into the lower side
 * (1 - F), reversed, the path's last segment towards the target sampled backwards. The second
 * catches the paths the walk's own directions rarely take but the target's scattering favours: from
 * a near-normal view to a grazing target, reflected or refracted out. A direction from the upper
 * side into the glass is also drawn by the entry strategy at the intersection before this one
 * (bb_walk_dielectric_entry, with the direction the walk arrived by): there the balance heuristic
 * has three terms, the walk having drawn that direction with density pin (0 at the first
 * intersection: no entry strategy). The walk's density of wa in *pout. mb: the target's visible
 * normal (drawn with u.v[0], u.v[1]); u.v[2] its Fresnel choice, u.v[3] the intersection height
 * below the surface (BB_WALK_NEE_TAG). */
BB_FN bb_real bb_walk_dielectric_mis(int dist, bb_vec3 v, bb_real lc, int up, bb_vec3 wa, int cross_a, bb_vec3 t,
                                     bb_real lt, bb_walk_etas et, bb_real ax, bb_real ay, bb_vec3 mb,
                                     philox4x32_ctr_t u, bb_real pin, bb_real mix, bb_real* pout) {
    const bb_real s = up ? BB_R(1.0) : BB_R(-1.0); /* this side's frame from the world's */
    bb_real cb = bb_clamp_cos(bb_dot(t, mb));
    int refract_b = bb_unit_from_bits(u.v[2]) >= bb_walk_fresnel_dielectric(cb, et.e[1], et.em1[1]);
    bb_vec3 d = refract_b ? bb_refract(t, mb, cb, et.e[1]) : bb_reflect(t, mb); /* from t, world */
    bb_vec3 wb = bb_scale(d, -s); /* the reversed segment, in this side's frame */
    int cross_b = refract_b == up; /* lands below from above, or above from below */
    bb_real sum = BB_R(0.0);
    for (int j = 0; j < 2; ++j) {
        bb_vec3 w = j == 0 ? wa : wb;
        int cross = j == 0 ? cross_a : cross_b;
        int up_next = cross ? !up : up;
        bb_real pa = bb_walk_dielectric_pdf(dist, v, w, up, cross, et, ax, ay);
        bb_real pb = bb_walk_dielectric_pdf(dist, t, bb_scale(w, -s), 1, !up_next, et, ax, ay);
        bb_real pw = bb_walk_mix_pdf(pa, mix, w, up != et.flip && !cross);
        if (j == 0) *pout = pw;
        if (up && cross && pin > BB_R(0.0)) /* the entry strategy's term, over the walk's density of v */
            pb += bb_walk_entry_pdf(dist, bb_scale(v, BB_R(-1.0)), w, t, et, ax, ay) / pin;
        bb_vec3 wn = cross ? bb_scale(w, BB_R(-1.0)) : w; /* in the next side's frame */
        bb_real lcn = cross ? bb_walk_flip_height(lc) : lc;
        bb_real nee = bb_walk_dielectric_next_nee(dist, wn, lcn, up_next, t, lt, et, ax, ay, bb_unit_from_bits(u.v[3]));
        sum += bb_select(BB_R(0.0), pa * nee / (pw + pb), pw + pb > BB_R(0.0) && bb_dot(w, w) > BB_R(0.5));
    }
    return sum;
}

/* The fourth counter word of the entry strategy's Philox call (bb_walk_dielectric_entry). */
#define BB_WALK_ENTRY_TAG 0x69000000u
/* The first intersection's share of uniform directions in an evaluation walk (bb_walk_mix_pdf). */
#define BB_WALK_MIX BB_R(0.2)

/* The entry strategy (walk8): at an intersection x0 (side `up`, height lc, v towards where the ray
 * came from, in that side's frame), the next event two intersections on, through the glass: the
 * ray from x0 goes through the upper side to x1, refracts into the glass there towards x2, and from
 * x2 refracts out towards t. Both segments are drawn from the target's side (bb_walk_entry_pdf):
 * t's visible normal mt (the one bb_walk_dielectric_mis draws) refracted into the glass
 * and reversed (x1 -> x2), then at x1 a visible normal of that direction seen from below (ue[0],
 * ue[1]) refracted out, reversed (x0 -> x1). x1 lies where the ray from x0 meets the microsurface
 * (drawn given that it does, ue[2], times that probability, as the walk's forced intersections), x2
 * where the ray from x1 does (ue[3], bb_walk_dielectric_next_nee). The walk's own directions reach
 * these paths with density f0 (x0's scattering towards x1) times pa or pb at x1
 * (bb_walk_dielectric_mis); the three by the balance heuristic [Veach 1997]: the estimate is
 * f0 f1 nee / (f0 f1 + f0 pb + pt q), f1 x1's refraction into the glass. Why (walk8, measured on
 * the host in double, GGX alpha 0.6, eta 1.5, 2^20 walks from 22.5 deg towards 82.5 deg): these paths
 * carried 90% of the estimate's variance from the near-normal end: the walk reaches x1 by a
 * reflection at x0 into a grazing upward direction (density ~0.0025 per sr from a near-normal
 * view), and from there the next event through the glass is ~0.5 of f cos where f cos is 9e-4:
 * 3077 walks in 1e6 carried 54% of the orders >= 2. From the grazing end the same paths are the
 * walk's own (its first intersection near the top, refracted in). */
BB_FN bb_real bb_walk_dielectric_entry(int dist, bb_vec3 v, bb_real lc, int up, bb_vec3 t, bb_real lt,
                                       bb_walk_etas et, bb_real ax, bb_real ay, bb_vec3 mt, philox4x32_ctr_t ue,
                                       bb_real mix) {
    bb_vec3 d = bb_refract(t, mt, bb_clamp_cos(bb_dot(t, mt)), et.e[1]); /* world: x2 -> x1, into the glass */
    if (!(bb_dot(d, d) > BB_R(0.5)) || !bb_walk_vndf_exact(dist, d, ax, ay)) return BB_R(0.0); /* no sample */
    bb_vec3 m1 = bb_walk_sample_vndf(dist, d, ax, ay, bb_unit_from_bits(ue.v[0]), bb_unit_from_bits(ue.v[1]));
    bb_real c1 = bb_dot(d, m1);
    bb_vec3 a = bb_refract(d, m1, bb_clamp_cos(c1), et.e[0]); /* x0 -> x1 in the world (d's frame is the lower) */
    int ok = c1 > BB_R(0.0) && bb_dot(a, a) > BB_R(0.5);
    bb_vec3 w = bb_scale(d, BB_R(-1.0)); /* x1 -> x2, upper frame */
    bb_real vh;
    bb_real pt = bb_walk_refract_phase(dist, t, d, et.e[1], ax, ay, &vh);
    bb_real pb = pt * (BB_R(1.0) - bb_walk_fresnel_dielectric(vh, et.e[1], et.em1[1]));
    bb_real q = bb_walk_refract_phase(dist, d, a, et.e[0], ax, ay, &vh);
    bb_real f0 = bb_walk_dielectric_pdf(dist, v, up ? a : bb_scale(a, BB_R(-1.0)), up, !up, et, ax, ay);
    bb_real f1 = bb_walk_dielectric_pdf(dist, bb_scale(a, BB_R(-1.0)), w, 1, 1, et, ax, ay);
    bb_real lca = up ? lc : bb_walk_flip_height(lc); /* x0's height seen from above */
    bb_real l = bb_walk_lambda(dist, a, ax, ay);
    bb_real p_hit = bb_select(BB_R(1.0), -bb_expm1(l * lca), a.z > BB_R(0.0));
    bb_real lc1 = lca - bb_log1p(-p_hit * bb_unit_from_bits(ue.v[2])) / l;
    bb_real nee = bb_walk_dielectric_next_nee(dist, d, bb_walk_flip_height(lc1), 0, t, lt, et, ax, ay,
                                              bb_unit_from_bits(ue.v[3]));
    bb_real fw = bb_walk_mix_pdf(f0, mix, a, up && !et.flip);
    bb_real den = fw * f1 + fw * pb + pt * q;
    return bb_select(BB_R(0.0), p_hit * f0 * f1 * nee / den, ok && den > BB_R(0.0) && f0 * f1 * nee > BB_R(0.0));
}

/* The first intersection's next event towards a target t below the surface (t.z < 0), averaged over
 * its height in closed form: the ray from above along -wo meets the microsurface at C1 = c with
 * density (1 + Lambda(wo)) c^Lambda(wo) (the height sampling above), refracts towards t with the
 * refraction phase function from wo times 1 - F(eta), and t, seen from below (-t, Lambda lt), leaves
 * unoccluded with probability (1 - c)^lt: E = (1 + Lambda(wo)) B(1 + Lambda(wo), 1 + lt). With the
 * phase function's 1/sigma(wo) this is the height-correlated rough dielectric's transmission f_t |t.z|
 * [WMLT07 eq. 21, with G2 = B(1 + Lambda(wo), 1 + Lambda(t)), H14 eq. 100]. */
BB_FN bb_real bb_walk_first_transmit(int dist, bb_vec3 wo, bb_vec3 t, bb_real lt, bb_walk_etas et, bb_real ax,
                                     bb_real ay) {
    bb_real vh;
    bb_real ph = bb_walk_refract_phase(dist, wo, t, et.e[1], ax, ay, &vh);
    bb_real a = BB_R(1.0) + bb_walk_lambda(dist, wo, ax, ay);
    bb_real nee = ph * (BB_R(1.0) - bb_walk_fresnel_dielectric(vh, et.e[1], et.em1[1])) * a *
                  bb_beta(a, BB_R(1.0) + lt);
    return bb_select(BB_R(0.0), nee, ph > BB_R(0.0));
}

/* One random walk on the rough dielectric microsurface [HHdD16 sec. 5 (dielectric), the
 * microsurface seen from either side]: the interface of relative index eta (far side over near
 * side, eta_m1 = eta - 1 exact) lit from above along -wo. At each intersection the microfacet
 * normal is a visible one of -w on the side the ray travels in, and the exact unpolarised
 * dielectric Fresnel term F(<-w, m>) of that side's relative index (eta outside, 1/eta inside
 * [WMLT07 eq. 22]) chooses the event: reflection with probability F, refraction [WMLT07 eq. 40]
 * (into the other side of the microsurface) with 1 - F, so that the weight stays 1 (total internal
 * reflection has F = 1). Below the surface the microsurface is the same one seen upside down:
 * the walk keeps its state in the frame of the side it travels in (directions and heights
 * negated below), so that the height sampling and the visible normals are the conductor's, and a
 * refraction turns the frame over: w -> -w_t, C1(h) -> 1 - C1(h) (bb_walk_flip_height). A walk
 * that escapes upward from the upper side is reflected (r.energy), from the lower side
 * transmitted (r.transmitted). Four Philox words per scattering: height, two for the normal and
 * the Fresnel choice. With target.z > 0 it also estimates the reflection f(wo, target) target.z
 * (r.f_cos) by next-event estimation as the conductor's walk does: the first intersection's in
 * closed form (the height-correlated lobe's reflection exactly, r.f_cos_single), each later one at
 * the intersection before it, averaged over its height (bb_walk_dielectric_next_nee: from the upper
 * side the reflection phase function times F, from the lower side the refraction phase function out
 * towards the target times 1 - F, masked at the height seen from above) and over the direction
 * towards it by MIS of the walk's own and one from the target's side (bb_walk_dielectric_mis; a
 * second Philox call per scattering), and two intersections on through the glass by the entry
 * strategy (bb_walk_dielectric_entry; a third). At its first intersection an evaluation walk
 * draws its direction from a defensive mixture (bb_walk_mix_pdf: 20% uniform over the upper
 * hemisphere, its weight times phase / mixture <= 1.25), the mixture's density in that
 * intersection's MIS weights and the next one's: above alpha 1 the rare walks that carried the
 * tail from a near-normal wo reflected there into a grazing upward direction (walk8: density
 * 7e-4 per sr at alpha 3) and crossed the glass near the top of the microsurface several times
 * before leaving towards a grazing target. An evaluation walk (target.z > 0) also forces its
 * intersections: an upward ray always meets the microsurface, at a height drawn given that it does,
 * and the walk's weight is multiplied by the probability 1 - C1(h)^Lambda(w) that it does; below a
 * weight of BB_WALK_ROULETTE_WEIGHT it survives with probability weight / that (Russian roulette,
 * a third Philox call) at that weight. Rare walks whose steep ray meets the microsurface again
 * (from a near-normal wo, the paths through the glass towards a grazing target) carried f's glass
 * part and the replicas' error hid them (walk5: check failed GGX alpha 0.4 on 7 of 16 seeds; 0 with
 * this). Without a target the walk, and so R and T, draws the same numbers as before.
 * With target.z < 0 (walk9) the same fields estimate the transmitted f_t(wo, target) |target.z| by the
 * same scheme mirrored: the next-event functions see the lower side as the target's (bb_walk_etas'
 * swap: at an upper-side intersection the refraction phase function into the glass towards the
 * target times 1 - F and its masking from that height seen from below; at a lower-side one the
 * reflection phase function times F(1/eta) in the lower frame, in closed form over the height), the
 * MIS directions drawn from -target in the lower frame, the entry strategy's mirror (two segments
 * through the air above); the first order in closed form (bb_walk_first_transmit). */
BB_FN bb_walk_result bb_walk_dielectric(int dist, bb_params p, bb_vec3 wo, bb_vec3 target, int bounces,
                                        philox4x32_key_t key, unsigned int walk, unsigned int rep, unsigned int stream) {
    bb_real ax = p.v[BB_SMITH_ALPHA_X], ay = p.v[BB_SMITH_ALPHA_Y];
    bb_walk_etas et;
    et.e[1] = p.v[BB_SMITH_WALK_ETA];
    et.em1[1] = p.v[BB_SMITH_WALK_ETA_M1];
    et.e[0] = BB_R(1.0) / et.e[1];
    et.em1[0] = -et.em1[1] / et.e[1]; /* 1/eta - 1 = -(eta - 1)/eta */
    et.flip = 0;
    const int eval = target.z != BB_R(0.0);
    const int below = target.z < BB_R(0.0); /* f_t: the next events see the lower side as the target's */
    bb_walk_etas ev = et;                    /* the next events' indices, [1] the target's side */
    if (below) {
        ev.e[0] = et.e[1], ev.e[1] = et.e[0], ev.em1[0] = et.em1[1], ev.em1[1] = et.em1[0];
        ev.flip = 1;
    }
    const bb_vec3 tt = below ? bb_scale(target, BB_R(-1.0)) : target; /* the target in its side's frame */
    bb_walk_result r = bb_walk_result_zero();
    bb_vec3 w = bb_scale(wo, BB_R(-1.0)); /* the ray's direction, in the frame of its side */
    bb_real lc = BB_R(0.0);               /* log C1(h), h in the frame of its side */
    int outside = 1;
    bb_real lt = bb_walk_lambda(dist, tt, ax, ay);
    if (eval && bounces > 0) { /* the first intersection's next event, in closed form */
        r.f_cos_single = below ? bb_walk_first_transmit(dist, wo, target, lt, et, ax, ay)
                               : bb_walk_dielectric_next_nee(dist, w, lc, 1, target, lt, et, ax, ay, BB_R(0.0));
        r.f_cos = r.f_cos_single;
    }
    bb_real weight = BB_R(1.0); /* an evaluation walk's weight (forced intersections, above) */
    bb_real pin = BB_R(0.0);    /* the density the walk drew its direction with (0: -wo, not drawn) */
    for (int k = 0;; ++k) {
        philox4x32_ctr_t ctr = {{walk, rep, stream, BB_WALK_TAG | (unsigned int)k}};
        philox4x32_ctr_t u = philox4x32(ctr, key);
        bb_real u0 = bb_unit_from_bits(u.v[0]);
        bb_real lambda = bb_walk_lambda(dist, w, ax, ay);
        if (eval && w.z > BB_R(0.0)) { /* a forced intersection and roulette (above) */
            bb_real p_hit = -bb_expm1(lambda * lc);
            u0 = p_hit * u0;
            weight = weight * p_hit;
            if (weight < BB_WALK_ROULETTE_WEIGHT) {
                philox4x32_ctr_t ctr3 = {{walk, rep, stream, BB_WALK_ROULETTE_TAG | (unsigned int)k}};
                if (!(bb_unit_from_bits(philox4x32(ctr3, key).v[0]) * BB_WALK_ROULETTE_WEIGHT < weight)) break;
                weight = BB_WALK_ROULETTE_WEIGHT;
            }
        }
        bb_real l = bb_log1p(-u0);
        if (w.z > BB_R(0.0) && l <= lambda * lc) {
            bb_real one_if_first = k == 1 ? BB_R(1.0) : BB_R(0.0);
            r.energy = outside ? BB_R(1.0) : BB_R(0.0);
            r.single = outside ? one_if_first : BB_R(0.0);
            r.transmitted = outside ? BB_R(0.0) : BB_R(1.0);
            r.single_t = outside ? BB_R(0.0) : one_if_first;
            break;
        }
        if (k == bounces) {
            r.cutoff = BB_R(1.0);
            break;
        }
        lc = lc - l / lambda;
        bb_vec3 v = bb_scale(w, BB_R(-1.0));
        bb_real e = et.e[outside], em1 = et.em1[outside];
        bb_vec3 m = bb_walk_sample_vndf(dist, v, ax, ay, bb_unit_from_bits(u.v[1]), bb_unit_from_bits(u.v[2]));
        /* <v, m> >= 0 but for Beckmann's views below BB_WALK_BECKMANN_MIN_COS (drawn from that cone's
         * edge, bb_walk_sample_vndf), whose normal can face away (11 in 1.7e7 walks at alpha 0.3, mu
         * 0.29): taken at grazing incidence, F = 1, a reflection (a refraction there has no direction). */
        bb_real c = bb_max(bb_clamp_cos(bb_dot(v, m)), BB_R(0.0));
        bb_fresnel_sp f = bb_fresnel_dielectric_sp_m1(c, e, em1);
        int cross = !(bb_unit_from_bits(u.v[3]) < BB_R(0.5) * (f.rs + f.rp));
        bb_vec3 wa = cross ? bb_refract(v, m, c, e) : bb_reflect(v, m); /* in this side's frame */
        bb_real mix = eval && k == 0 ? BB_WALK_MIX : BB_R(0.0); /* the first direction's mixture (above) */
        if (mix > BB_R(0.0)) { /* at k = 0 the roulette's counter word is free (a downward ray) */
            philox4x32_ctr_t ctr5 = {{walk, rep, stream, BB_WALK_ROULETTE_TAG | (unsigned int)k}};
            philox4x32_ctr_t um = philox4x32(ctr5, key);
            if (bb_unit_from_bits(um.v[0]) < mix) {
                bb_real z = bb_unit_from_bits(um.v[1]), ph = BB_R(2.0) * BB_PI * bb_unit_from_bits(um.v[2]);
                bb_real sr = bb_safe_sqrt(BB_R(1.0) - z * z);
                wa = bb_v3(sr * bb_cos(ph), sr * bb_sin(ph), z);
                cross = 0;
            }
        }
        if (eval && k + 1 < bounces) { /* the next intersection's next event, two directions (above) */
            philox4x32_ctr_t ctr2 = {{walk, rep, stream, BB_WALK_NEE_TAG | (unsigned int)k}};
            philox4x32_ctr_t un = philox4x32(ctr2, key);
            bb_vec3 mt = bb_walk_sample_vndf(dist, tt, ax, ay, bb_unit_from_bits(un.v[0]),
                                             bb_unit_from_bits(un.v[1])); /* the target's visible normal */
            const int side = outside != below; /* on the target's side */
            r.f_cos += weight * bb_walk_dielectric_mis(dist, v, lc, side, wa, cross, tt, lt, ev, ax, ay, mt, un, pin,
                                                       mix, &pin);
            if (k + 2 < bounces) { /* two intersections on through the glass, drawn from the target */
                philox4x32_ctr_t ctr4 = {{walk, rep, stream, BB_WALK_ENTRY_TAG | (unsigned int)k}};
                r.f_cos += weight * bb_walk_dielectric_entry(dist, v, lc, side, tt, lt, ev, ax, ay, mt,
                                                             philox4x32(ctr4, key), mix);
            }
        }
        if (mix > BB_R(0.0)) { /* the mixture's weight f0 / p_mix (bounded by 1 / (1 - mix)) */
            bb_real f0 = bb_walk_dielectric_pdf(dist, v, wa, outside, cross, et, ax, ay);
            bb_real pm = bb_walk_mix_pdf(f0, mix, wa, !cross);
            weight = weight * bb_select(BB_R(0.0), f0 / pm, pm > BB_R(0.0));
        }
        if (cross) {
            w = bb_scale(wa, BB_R(-1.0));
            lc = bb_walk_flip_height(lc);
            outside = !outside;
        } else {
            w = wa;
        }
        if (!(bb_isfinite(lc) || lc < BB_R(0.0)) || !bb_isfinite(w.z) || bb_dot(w, w) < BB_R(0.5)) {
            r.bad = 1;
            break;
        }
    }
    return r;
}

#endif /* BRDFBAKE_BRDF_RANDOM_WALK_H */

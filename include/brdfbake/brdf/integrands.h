/* The integrands of the albedo methods other than a model's own importance sampler
 * (kernels/albedo.cl, host/integrate/albedo.cpp). Shared by host and kernels like the models.
 *
 * E(wo) = integral over the upper hemisphere of f(wo, wi) cos(theta_i) dwi is computed as
 *
 *   mc, qmc      uniform hemisphere sampling, the model-agnostic estimator: wi with
 *                cos(theta_i) = u1, phi_i = 2 pi u2, pdf = 1/(2 pi), weight 2 pi f cos(theta_i);
 *                u from Philox (mc) or from randomised Hammersley points (qmc).
 *
 *   quadrature   a Gauss-Legendre product rule, in one of two coordinate systems:
 *
 *     half-vector space, for the models whose lobe is a distribution of normals D (ggx,
 *     beckmann, torrance-sparrow, blinn-phong). The half vector h has azimuth phi_o + delta and
 *     radial coordinate u = the CDF of D(h) cos(theta_h) along that azimuth, which flattens
 *     the peak of D however narrow it is. wi = reflect(wo, h) is above the horizon exactly for
 *       theta_h < theta_max(delta),  tan(theta_max) = (R + B)/A = A/(R - B),
 *       A = cos(theta_o), B = sin(theta_o) cos(delta), R = sqrt(A^2 + B^2)
 *     (from 2 (wo.h) h_z >= cos(theta_o), i.e. A cos 2theta + B sin 2theta >= 0), and there
 *     wo.h > 0 too. So for each delta the rule integrates u over [0, u_max(delta)] only: the
 *     integrand is smooth on the whole domain, with no horizon cut inside it. delta runs
 *     over four quarters [k pi/2, (k+1) pi/2], split where u_max changes fastest at grazing
 *     wo. With p(h) the density of the map (u, delta/2pi) -> h,
 *       E = 1/(2 pi) int d(delta) int_0^u_max du  f cos(theta_i) 4 (wo.h) / p(h).
 *     For an anisotropic D the map along azimuth phi uses the isotropic radial CDF with the
 *     azimuth's roughness a(phi) = 1/sqrt(cos^2 phi/ax^2 + sin^2 phi/ay^2) [H14 eq. 80]; then
 *     D(h)/p(h) = a^2/(ax ay cos(theta_h)) exactly.
 *
 *     sampler space, for the others (lambert, oren-nayar, phong, phong-original): the
 *     model's own importance warp (u1, u2) -> wi on the unit square, u2 split into four
 *     quarters (phi_i - phi_o = +-pi/2 for phi_o = 0 is where Oren-Nayar's max(0, cos) bends);
 *     the integrand is the sample weight.
 *
 * References: [H14] Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based
 * BRDFs", JCGT 3(2), 2014; [WMLT07] Walter et al., "Microfacet Models for Refraction through
 * Rough Surfaces", EGSR 2007 (the D cos(theta_h) sampling densities). */
#ifndef BRDFBAKE_BRDF_INTEGRANDS_H
#define BRDFBAKE_BRDF_INTEGRANDS_H

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/brdf/quad_dist.h"

/* ------------------------------------------------------- uniform hemisphere */

/* The weight 2 pi f cos(theta_i) of the uniform hemisphere sample (u1, u2). */
BB_FN bb_real bb_uniform_hemisphere_weight(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1,
                                        bb_real u2) {
    bb_real mu = u1;
    bb_real s = bb_safe_sqrt(bb_sin2_from_cos(mu));
    bb_real phi = BB_2PI * u2;
    bb_vec3 wi = bb_v3(s * bb_cos(phi), s * bb_sin(phi), mu);
    return BB_2PI * mu * bb_model_eval(model, p, fkind, fp, wo, wi);
}

/* The sampling methods' estimator at the point (u1, u2) of a replica (the sum over its points,
 * divided by their number, is the replica's estimate of E(wo)): the model's importance-sample
 * weight f cos / pdf for BB_METHOD_IMPORTANCE, the uniform hemisphere weight for BB_METHOD_QMC
 * and BB_METHOD_MC (kernel_abi.h), which differ only in where (u1, u2) come from. */
BB_FN bb_real bb_albedo_point_weight(int method, int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1,
                                  bb_real u2) {
    if (method == BB_METHOD_IMPORTANCE) return bb_model_sample(model, p, fkind, fp, wo, u1, u2).weight;
    return bb_uniform_hemisphere_weight(model, p, fkind, fp, wo, u1, u2);
}

/* ------------------------------------------------------ half-vector space */

/* The coordinate system of the quadrature for a model, and its distribution's parameters
 * (quad_dist.h): each half-vector model's own bb_<name>_quad_dist, the sampler's square for the
 * others (the QUAD column of model_registry.h). */
#define BB_QUAD_DIST_CASE_SAMPLER(NAME, name)
#define BB_QUAD_DIST_CASE_HALFVECTOR(NAME, name) \
    case BB_MODEL_##NAME:                        \
        return bb_##name##_quad_dist(p);
#define BB_QUAD_DIST_CASE(NAME, name, SPEC, ARGS, QUAD, ...) \
    BB_IF_COMPILED(NAME)(BB_PP_CAT(BB_QUAD_DIST_CASE_, QUAD)(NAME, name))

BB_FN bb_quad_dist bb_model_quad_dist(int model, bb_params p) {
    switch (model) {
        BB_MODEL_REGISTRY(BB_QUAD_DIST_CASE)
    default:
        return bb_make_quad_dist(BB_QUAD_SAMPLER, BB_R(1.0), BB_R(1.0), BB_R(0.0));
    }
}

/* Mirror symmetry of the rule: for an isotropic lobe the integrand at azimuth offset -delta
 * equals that at delta (half-vector space; in the sampler's square phi_i -> -phi_i needs
 * phi_o = 0 too, and every sampler-space model is isotropic). Then two quarters suffice.
 * A measured table (merl) is mirror-symmetric only where the host found it so
 * (bb_merl_mirror_symmetric): the mirror image of a pair takes phi_d to pi - phi_d (brdf/merl.h),
 * which a measured file need not hold equal; otherwise its rule covers the whole azimuth.
 * In a vector build d and phi_o are one cell's, equal in every lane. */
BB_FN int bb_quad_mirrored(int model, bb_params p, bb_quad_dist d, bb_real phi_o) {
#if BB_HAS_MODEL(BB_MODEL_MERL) /* merl.h is included only where the model may be merl */
    if (model == BB_MODEL_MERL && !bb_merl_mirror_symmetric(p))
        return 0;
#endif
    return d.kind == BB_QUAD_SAMPLER ? bb_all(phi_o == BB_R(0.0)) : bb_all(d.ax == d.ay);
}

/* Azimuth pieces of the half-vector rule. The rule runs over 8 pieces: each quarter k of the
 * azimuth offset delta = phi_h - phi_o is cut in two (h = 0, 1) where it crosses an axis of an
 * anisotropic D (phi_h a multiple of pi/2), so that every piece lies in one quadrant j of phi_h.
 * There the azimuth follows the marginal of D's slopes, which for roughness a(phi) along the
 * azimuth is proportional to a(phi)^2 (see the head of this file):
 *   psi = phi_h - j pi/2 = atan(rho tan(theta)),  rho = ay/ax (j even) or ax/ay (j odd),
 * with theta linear in the node x; dpsi/dtheta = rho / (cos^2 theta + rho^2 sin^2 theta) then
 * cancels the factor a^2 of the integrand, however elongated the lobe (alpha_x = 1 with
 * alpha_y = 1e-3 puts the lobe in 1e-3 rad of azimuth, which a rule in delta cannot see).
 * For isotropic D (rho = 1) the map is the identity and the h = 1 pieces are empty, as they
 * are when phi_o is on an axis. */
typedef struct {
    bb_real delta;  /* the node's azimuth offset */
    bb_real ddelta; /* d(delta)/dx */
} bb_quad_azimuth;

/* Where the axis crossing cuts each quarter of delta: pi/2 - (phi_o mod pi/2), or pi/2 (no
 * cut) for isotropic lobes and phi_o within 1e-6 rad of an axis. */
BB_FN bb_real bb_quad_piece_split(bb_quad_dist d, bb_real phi_o) {
    const bb_real q = BB_R(0.5) * BB_PI;
    bb_real phi0 = phi_o - bb_floor(phi_o / q) * q;
    bb_mask aligned = d.ax == d.ay || phi0 < BB_R(1e-6) || phi0 > q - BB_R(1e-6);
    return bb_select(q - phi0, q, aligned);
}


/* The azimuth of node x in [0, 1] of piece (k, h) (piece = 2k + h); ddelta = 0 for an empty
 * piece. In a vector build (one row per lane, kernels/albedo.cl) only x may differ between
 * lanes: d and phi_o are one cell's, so the branches below are taken by every lane alike. */
/* kink_delta (bb_quad_kink_delta): for an isotropic lobe, the offset in quarter 0 where the rows
 * stop crossing the Fresnel kink; each quarter is cut there (mirrored, at q - kink_delta in the
 * odd quarters), pi/2 for none. */
BB_FN bb_quad_azimuth bb_quad_azimuth_node(bb_quad_dist d, bb_real phi_o, unsigned int piece, bb_real x,
                                           bb_real kink_delta) {
    const bb_real q = BB_R(0.5) * BB_PI;
    const int odd = (int)((piece >> 1) & 1u);
    bb_real kink_split = bb_select(kink_delta, q - kink_delta, odd);
    bb_real split = bb_select(bb_quad_piece_split(d, phi_o), kink_split, d.ax == d.ay && kink_delta < q);
    bb_real k = (bb_real)(piece >> 1);
    int h = (int)(piece & 1u);
    bb_real lo = k * q + bb_select(BB_R(0.0), split, h);
    bb_real hi = bb_select(k * q + split, (k + BB_R(1.0)) * q, h);
    bb_quad_azimuth a;
    if (bb_all(!(hi > lo))) {
        a.delta = lo;
        a.ddelta = BB_R(0.0);
        return a;
    }
    if (bb_all(d.ax == d.ay)) { /* rho = 1: the identity */
        a.delta = lo + (hi - lo) * x;
        a.ddelta = hi - lo;
        return a;
    }
    bb_real j = bb_floor((phi_o + BB_R(0.5) * (lo + hi)) / q);
    bb_real rho = bb_select(d.ax / d.ay, d.ay / d.ax, bb_floor(BB_R(0.5) * j) == BB_R(0.5) * j); /* j even */
    bb_real psi_lo = bb_clamp(phi_o + lo - j * q, BB_R(0.0), q), psi_hi = bb_clamp(phi_o + hi - j * q, BB_R(0.0), q);
    bb_real th_lo = bb_atan2(bb_sin(psi_lo), rho * bb_cos(psi_lo));
    bb_real th_hi = bb_atan2(bb_sin(psi_hi), rho * bb_cos(psi_hi));
    bb_real th = th_lo + (th_hi - th_lo) * x;
    bb_real c = bb_cos(th), s = bb_sin(th);
    a.delta = j * q + bb_atan2(rho * s, c) - phi_o;
    a.ddelta = (th_hi - th_lo) * rho / (c * c + rho * rho * s * s);
    return a;
}

/* Whether piece (0..BB_QUAD_PIECES - 1) of a cell's rule is empty: with mirror symmetry
 * (bb_quad_mirrored) quarters 2 and 3 (quarters 0 and 1 count twice); the halves h = 1 in the
 * sampler's square, and where bb_quad_azimuth_node gives no width (no axis crossing, no kink
 * cut: kink_delta as bb_quad_kink_delta gives it, pi/2 for none). The kernels skip these; the
 * host counts the others (bb_quad_piece_count). */
BB_FN int bb_quad_piece_empty(int model, bb_params p, bb_quad_dist d, bb_real phi_o, unsigned int piece,
                              bb_real kink_delta) {
    if (bb_quad_mirrored(model, p, d, phi_o) && (piece >> 1) >= 2u) return 1;
    return (piece & 1u) && (d.kind == BB_QUAD_SAMPLER ||
                            bb_all(bb_quad_azimuth_node(d, phi_o, piece, BB_R(0.5), kink_delta).ddelta == BB_R(0.0)));
}

/* The number of non-empty pieces of a cell's rule (its node count per rule of n nodes is this
 * times n^2 times the parts of a row): 2 for an isotropic lobe, 4 where a kink cuts its quarters
 * (bb_quad_kink_delta), 4 or 8 for an anisotropic one. */
BB_FN int bb_quad_piece_count(int model, bb_params p, bb_quad_dist d, bb_real phi_o, bb_real kink_delta) {
    int count = 0;
    for (unsigned int piece = 0; piece < 8u; ++piece)
        count += bb_quad_piece_empty(model, p, d, phi_o, piece, kink_delta) ? 0 : 1;
    return count;
}

/* Sampler space for the cosine samplers (Lambert, Oren-Nayar: sin^2(theta_i) = u1; the
 * COSINE column of model_registry.h, bb_quad_sampler_is_cosine): the rule runs over
 * c = cos(theta_i) instead, u1 = 1 - c^2 with Jacobian 2c, which removes the 1/c of
 * Oren-Nayar's tan(theta_i), and in two pieces, [0, cos(theta_o)] and [cos(theta_o), 1], where
 * its max(theta_i, theta_o) and min(...) switch. */

/* The roughness of an anisotropic distribution along azimuth phi, squared:
 * a^2 = ax^2 ay^2 / (ay^2 cos^2 phi + ax^2 sin^2 phi). */
BB_FN bb_real bb_quad_alpha2(bb_quad_dist d, bb_real cos_phi, bb_real sin_phi) {
    bb_real ax2 = d.ax * d.ax, ay2 = d.ay * d.ay;
    return ax2 * ay2 / (ay2 * cos_phi * cos_phi + ax2 * sin_phi * sin_phi);
}

/* D(h) cos^4(theta_h) at slope radius r = tan(theta_h) along an azimuth of roughness^2 a2. */
BB_FN bb_real bb_quad_slope_density(bb_quad_dist d, bb_real a2, bb_real r) {
    bb_real r2 = r * r;
    switch (d.kind) {
    case BB_QUAD_GGX: {
        bb_real q = BB_R(1.0) + r2 / a2;
        return BB_R(1.0) / (BB_PI * d.ax * d.ay * q * q);
    }
    case BB_QUAD_BECKMANN:
        return bb_exp(-r2 / a2) / (BB_PI * d.ax * d.ay);
    default: /* normalised Blinn: (N + 2)/(2 pi) cos^(N+4) */
        return (d.n + BB_R(2.0)) * (BB_R(0.5) * BB_INV_PI) * bb_exp(BB_R(-0.5) * (d.n + BB_R(4.0)) * bb_log1p(r2));
    }
}

/* tan of the largest theta_h at azimuth offset delta whose mirror direction is above the
 * horizon (see the head of this file): (R + B)/A, or A/(R - B) for B < 0. */
BB_FN bb_real bb_quad_tan_max(bb_real mu_o, bb_real sin_o, bb_real cos_delta) {
    bb_real a = mu_o, b = sin_o * cos_delta;
    bb_real r = bb_sqrt(a * a + b * b);
    return bb_select((r + b) / a, a / (r - b), b < BB_R(0.0));
}

/* One row of the half-vector rule: the half vectors at azimuth phi_h = phi_o + delta, with
 * radial coordinate t in [0, t_max]: tan(theta_h) = a sinh(t), a the azimuth's roughness
 * (sqrt(2/(N + 2)) for Blinn, the Beckmann width of the same lobe [WMLT07 sec. 5.2]). The map
 * is linear in the slope inside the lobe and logarithmic outside it, so that the three scales
 * of the integrand (the lobe's width a, the 45-degree bend, the horizon cut near
 * tan(theta_max) ~ 2/cos(theta_o) at grazing) are each smooth in t; the Jacobian
 * a r cosh(t) cos^4 meets D cos^4, the slope density, and the visible-normal factor
 * (wo.h)/cos(theta_h) grows only linearly in r = a sinh(t). */
typedef struct {
    bb_real cos_phi, sin_phi; /* of phi_h */
    bb_real a2, a;            /* the azimuth's roughness, squared and not */
    bb_real t_max;
} bb_quad_row;

BB_FN bb_quad_row bb_make_quad_row(bb_quad_dist d, bb_vec3 wo, bb_real phi_o, bb_real delta) {
    bb_quad_row r;
    bb_real phi = phi_o + delta;
    r.cos_phi = bb_cos(phi);
    r.sin_phi = bb_sin(phi);
    r.a2 = bb_select(bb_quad_alpha2(d, r.cos_phi, r.sin_phi), BB_R(2.0) / (d.n + BB_R(2.0)), d.kind == BB_QUAD_BLINN);
    r.a = bb_sqrt(r.a2);
    bb_real sin_o = bb_safe_sqrt(bb_sin2_from_cos(wo.z));
    /* Beyond r = tan(theta_h) = r_cap the Gaussian-like lobes are below 1e-18 of their peak:
     * no nodes are spent there. */
    bb_real r_cap = bb_select(BB_R(6.5) * r.a, bb_sqrt(bb_expm1(BB_R(84.0) / (d.n + BB_R(4.0)))), d.kind == BB_QUAD_BLINN);
    bb_real r_max = bb_quad_tan_max(wo.z, sin_o, bb_cos(delta));
    r_max = bb_select(r_max, bb_min(r_max, r_cap), d.kind != BB_QUAD_GGX);
    bb_real x = r_max / r.a;
    r.t_max = bb_log(x + bb_sqrt(x * x + BB_R(1.0))); /* asinh */
    return r;
}

/* The integrand f cos(theta_i) 4 (wo.h) times the map's Jacobian at t in [0, t_max): the
 * models' closed forms bb_<name>_halfvector_weight, written so that the narrow D enters only
 * through the slope density (djc = D J cos(theta_h)). */
#define BB_HALFVECTOR_CASE_SAMPLER(NAME, name)
#define BB_HALFVECTOR_CASE_HALFVECTOR(NAME, name)                        \
    case BB_MODEL_##NAME:                                                \
        w = bb_##name##_halfvector_weight(p, f, wo, wi, oh, co, ch, djc); \
        break;
#define BB_HALFVECTOR_CASE(NAME, name, SPEC, ARGS, QUAD, ...) \
    BB_IF_COMPILED(NAME)(BB_PP_CAT(BB_HALFVECTOR_CASE_, QUAD)(NAME, name))

BB_FN bb_real bb_quad_halfvector_point(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_quad_dist d,
                                    bb_quad_row row, bb_real t) {
    bb_real em1 = bb_expm1(t);
    bb_real sinh_t = BB_R(0.5) * em1 * (em1 + BB_R(2.0)) / (em1 + BB_R(1.0));
    bb_real cosh_t = sinh_t + BB_R(1.0) / (em1 + BB_R(1.0));
    bb_real r = row.a * sinh_t;
    bb_real ch = BB_R(1.0) / bb_sqrt(BB_R(1.0) + r * r);
    bb_real sh = r * ch;
    bb_vec3 h = bb_v3(sh * row.cos_phi, sh * row.sin_phi, ch);
    /* D J cos(theta_h) */
    bb_real djc = row.a * r * cosh_t * bb_quad_slope_density(d, row.a2, r);

    bb_real oh = bb_clamp_cos(bb_dot(wo, h));
    bb_vec3 wi = bb_reflect(wo, h);
    bb_mask ok = wi.z > BB_R(0.0) && oh > BB_R(0.0) && wo.z > BB_R(0.0);
    bb_real co = bb_select(BB_R(1.0), wo.z, ok);
    bb_real f = bb_fresnel_eval(fkind, fp, oh);
    bb_real w = BB_R(0.0);
    switch (model) {
        BB_MODEL_REGISTRY(BB_HALFVECTOR_CASE)
    default:
        break;
    }
    return bb_select(BB_R(0.0), w, ok);
}

/* ------------------------------------------------------------- kinks the rules split at
 * A Gauss rule converges geometrically only where its integrand is smooth; where the derivative
 * jumps inside a row (a cone, a cusp) it converges algebraically, and the three rules of the
 * error estimate can agree on a value far off (issue 37: sheen with ashikhmin visibility at
 * alpha 0.9375, 54x its estimate). The rules therefore split each row at such a point. */

/* The mirror cone (BB_TRAIT_MIRROR_CONE): the sampler's u1 whose cos(theta_i) is cos(theta_o),
 * the polar angle of the mirror direction, by bisection on the model's own sampler (its
 * cos(theta_i) rises with u1 and does not depend on u2); 1 - u1 is the second part's length. */
BB_FN bb_real bb_quad_sampler_cone_u1(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo) {
    bb_real lo = BB_R(0.0), hi = BB_R(1.0);
    for (int i = 0; i < 64; ++i) {
        bb_real mid = BB_R(0.5) * (lo + hi);
        bb_mask below = bb_model_sample(model, p, fkind, fp, wo, mid, BB_R(0.5)).wi.z < wo.z;
        lo = bb_select(lo, mid, below);
        hi = bb_select(mid, hi, below);
    }
    return BB_R(0.5) * (lo + hi);
}

/* Whether the Fresnel term has a cusp at wo.h = 1 (h along wo): generalized Schlick's
 * (1 - cos)^exponent with a non-integer exponent (Cycles' z = 0.99 is exponent 0.05, whose
 * weight drops from 1 to 0 within a few 1e-3 of cos = 1). Constant over a launch. */
BB_FN int bb_quad_fresnel_cusp(int fkind, bb_params fp) {
    if (fkind != BB_FRESNEL_GEN_SCHLICK) return 0;
    bb_real e = fp.v[BB_GEN_SCHLICK_EXPONENT];
    return !bb_all(e == bb_floor(e));
}

/* The cosine wo.h below which the Fresnel term's weight leaves 0 with a kink, or -1 for none:
 * Cycles' remapped dielectric clamp((F - F0) / (1 - F0), 0, 1) (gen-schlick-ior) is 0 where a
 * high index's F dips below F0 (from cos = 1 down to past Brewster's angle; eta = 4.56, Cycles'
 * z = 0.8, puts the kink at cos 0.09, in the tail of a narrow lobe seen at grazing). Found from
 * a 64-step scan of the weight down from cos = 1 and bisection. Constant over a launch. */
BB_FN bb_real bb_quad_fresnel_kink_cos(int fkind, bb_params fp) {
    if (fkind != BB_FRESNEL_GEN_SCHLICK_IOR) return BB_R(-1.0);
    bb_real hi = BB_R(1.0), lo = BB_R(-1.0);
    for (int j = 63; j >= 0 && bb_all(lo < BB_R(0.0)); --j) {
        bb_real c = (bb_real)j / BB_R(64.0);
        if (bb_all(bb_fresnel_eval(fkind, fp, c) > BB_R(0.0))) lo = c;
        else hi = c;
    }
    if (bb_all(lo < BB_R(0.0)) || bb_all(hi == BB_R(1.0))) return BB_R(-1.0); /* 0 nowhere below 1, or nowhere */
    for (int i = 0; i < 60; ++i) {
        bb_real mid = BB_R(0.5) * (lo + hi);
        bb_mask pos = bb_fresnel_eval(fkind, fp, mid) > BB_R(0.0);
        lo = bb_select(lo, mid, pos);
        hi = bb_select(mid, hi, pos);
    }
    return BB_R(0.5) * (lo + hi);
}

/* A cell's kink cosine: bb_quad_fresnel_kink_cos in half-vector space, -1 (none) in the sampler's. */
BB_FN bb_real bb_quad_cell_kink_cos(bb_quad_dist d, int fkind, bb_params fp) {
    return d.kind != BB_QUAD_SAMPLER ? bb_quad_fresnel_kink_cos(fkind, fp) : BB_R(-1.0);
}

/* The azimuth offset delta in [0, pi/2] at which half-vector rows stop crossing the kink
 * wo.h = kink_cos, or pi/2 for none: a row's largest wo.h is R(delta) = sqrt(mu_o^2 +
 * sin^2(theta_o) cos^2(delta)) (bb_quad_row_cuts), which falls to kink_cos at
 * cos(delta) = sqrt(kink_cos^2 - mu_o^2) / sin(theta_o) when mu_o < kink_cos (grazing views: the
 * preset's mu = 1e-4 at eta 4.56, kink_cos 0.09). Across it the row integral's derivative has a
 * square-root singularity in delta, where the outer Gauss rule converges only algebraically.
 * pi/2 for kink_cos <= mu_o (none: kink_cos -1). */
BB_FN bb_real bb_quad_kink_delta(bb_vec3 wo, bb_real kink_cos) {
    const bb_real q = BB_R(0.5) * BB_PI;
    bb_real sin_o = bb_safe_sqrt(bb_sin2_from_cos(wo.z));
    bb_mask has = kink_cos > wo.z && sin_o > BB_R(0.0);
    bb_real c = bb_clamp(bb_safe_sqrt(kink_cos * kink_cos - wo.z * wo.z) / bb_select(BB_R(1.0), sin_o, has), BB_R(0.0), BB_R(1.0));
    bb_real delta = bb_atan2(bb_safe_sqrt(BB_R(1.0) - c * c), c); /* acos(c) */
    return bb_select(q, delta, has && delta > BB_R(0.0) && delta < q);
}

/* The radial coordinate t = asinh(tan(theta_h) / a) of polar angle theta_h on a row (bb_make_quad_row's
 * map), clamped to [0, t_max]. */
BB_FN bb_real bb_quad_row_t(bb_quad_row r, bb_real theta) {
    bb_real th = bb_clamp(theta, BB_R(0.0), BB_R(0.5) * BB_PI);
    bb_real x = bb_sin(th) / (bb_cos(th) * r.a); /* +inf at pi/2: t_max */
    bb_real t = bb_log(x + bb_sqrt(x * x + BB_R(1.0))); /* asinh */
    return bb_clamp(t, BB_R(0.0), r.t_max);
}

/* Where a half-vector row at azimuth offset delta is cut (sorted into cut[0..2], unused ones
 * t_max): along it wo.h = R cos(theta_h - theta*), R = sqrt(cos^2(theta_o) + sin^2(theta_o)
 * cos^2(delta)), tan(theta*) = tan(theta_o) cos(delta). `cusp`: at theta*, where the row comes
 * closest to wo (at delta = 0 the Fresnel cusp at wo.h = 1 sits there); `kink_cos` > 0: at
 * theta* -+ acos(kink_cos / R), where wo.h crosses that cosine. */
BB_FN void bb_quad_row_cuts(bb_quad_row r, bb_vec3 wo, bb_real delta, int cusp, bb_real kink_cos, bb_real* cut) {
    bb_real sin_o = bb_safe_sqrt(bb_sin2_from_cos(wo.z));
    bb_real b = sin_o * bb_cos(delta);
    bb_real big_r = bb_sqrt(wo.z * wo.z + b * b);
    bb_real th = bb_atan2(b, wo.z);
    bb_real c0 = cusp ? bb_quad_row_t(r, th) : r.t_max, c1 = r.t_max, c2 = r.t_max;
    if (bb_all(kink_cos > BB_R(0.0))) {
        bb_mask crosses = kink_cos < big_r;
        bb_real q = bb_clamp(kink_cos / big_r, BB_R(-1.0), BB_R(1.0));
    bb_real spread = bb_atan2(bb_safe_sqrt(BB_R(1.0) - q * q), q); /* acos(q) */
        c1 = bb_select(r.t_max, bb_quad_row_t(r, th - spread), crosses);
        c2 = bb_select(r.t_max, bb_quad_row_t(r, th + spread), crosses);
    }
    /* sort the three */
    bb_real lo = bb_min(c0, bb_min(c1, c2)), hi = bb_max(c0, bb_max(c1, c2));
    cut[0] = lo;
    cut[1] = c0 + c1 + c2 - lo - hi;
    cut[2] = hi;
}

/* Part `part` of a row [0, t_max] cut into n_parts at the first n_parts - 1 of cut[]: its start
 * and length (the kernels' rules run n nodes over each). */
typedef struct {
    bb_real lo, len;
} bb_quad_part;

BB_FN bb_quad_part bb_quad_row_part(const bb_real* cut, int n_parts, int part, bb_real t_max) {
    bb_quad_part q;
    q.lo = part == 0 ? BB_R(0.0) : cut[part - 1];
    q.len = (part == n_parts - 1 ? t_max : cut[part]) - q.lo;
    return q;
}

#endif /* BRDFBAKE_BRDF_INTEGRANDS_H */

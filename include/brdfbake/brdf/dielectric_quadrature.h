/* Quadrature of the rough dielectric's reflected and transmitted energy fractions (R, T of
 * rough_dielectric.h) in half-vector space, shared by the host and kernels/dielectric.cl.
 *
 * Both fractions are integrals over the microfacet normal m of the visible-normal measure
 * D(m) (wo.m) / wo.z [H14 eq. 38; WMLT07 eq. 22], split at each microfacet as the importance
 * sampler splits it (bb_rough_dielectric_split):
 *   R = int D(m) (wo.m)/wo.z  F(wo.m) G2_R(wo, wr)        dm  over wr = reflect(wo, m) above,
 *   T = int D(m) (wo.m)/wo.z  (1 - F(wo.m)) G2_T(wo, wt)  dm  over wt = refract(wo, m) below,
 * with no Jacobian of the reflection or refraction map (the integral runs over m, not over the
 * outgoing direction). The sampler's estimator is this integrand divided by the visible-normal
 * density G1(wo) D (wo.m)/wo.z, so both methods integrate the same function.
 *
 * m is parameterised as the albedo's half-vector rule does (integrands.h): azimuth delta of m
 * (phi_o = 0; the lobe is isotropic, so delta runs over [0, pi] and counts twice), slope
 * tan(theta_m) = a sinh(t) along the row. Each row is cut where the integrand has a kink or a
 * square-root edge, so that it is smooth on every segment:
 *   t_R  where wr reaches the horizon (bb_quad_tan_max, as for the albedo);
 *   t_V  where wo.m = 0 (tan = wo.z / -B for B = sin_o cos(delta) < 0; none for B >= 0);
 *   t_a, t_b  for eta < 1, where wo.m = c_crit = sqrt(1 - eta^2), the edge of total internal
 *        reflection: wo.m = A cos(theta) + B sin(theta) = rho cos(theta - phi0) gives
 *        theta = phi0 -+ acos(c_crit / rho) in closed form; 1 - F grows like sqrt(wo.m - c_crit)
 *        there [Born and Wolf 1.5.4];
 *   t_w, t_x  for eta < 1, where the refracted direction reaches the horizon (wt.z = 0): up to
 *        two crossings per row, in closed form (bb_dielectric_t_horizon); with the Cycles form
 *        G2_T falls linearly to 0 there, a kink the rule must not straddle.
 * Each segment [t0, t1] is integrated through the smoothstep map t = t0 + (t1 - t0) S(x) (on the
 * row's last segment followed by an exponential stretch, bb_dielectric_segment_node),
 * S(x) = x^2 (3 - 2x), whose Jacobian 6x(1 - x) vanishes at both ends: a square-root edge
 * becomes sqrt(S(x)) ~ x, smooth for the Gauss-Legendre rule. The azimuth is cut the same way,
 * where the rows' structure changes: [0, delta_h], [delta_h, delta*], [delta*, pi/2], [pi/2, pi],
 * delta_h where the edge of total internal reflection meets the horizon (sin_o cos(delta_h) =
 * c_crit: beyond it the far end of the row is no longer transmitting; 0 if it never does),
 * delta* where the whole row falls under total internal reflection (rho(delta*) = c_crit; pi/2
 * if no row does), pi/2 where rows change from unbounded (B >= 0) to ending at wo.m = 0.
 *
 * GGX has no slope beyond which D vanishes: rows with B >= 0 end at slope r_cap. The part of the
 * visible-normal measure beyond slope r is at most a^2/r^2 + 2 a^2 tan(theta_o)/r (the GGX slope
 * density a^2/(pi (a^2 + r^2)^2) times 1 + r tan(theta_o) >= (wo.m)/(wo.z cos(theta_m))), so
 * r_cap = a^2 (1 + 2 tan(theta_o)) / eps + a leaves out less than eps = BB_EPS_REAL / 16 of R + T.
 *
 * References: [H14] Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based
 * BRDFs", JCGT 3(2), 2014; [WMLT07] Walter et al., "Microfacet Models for Refraction through
 * Rough Surfaces", EGSR 2007. */
#ifndef BRDFBAKE_BRDF_DIELECTRIC_QUADRATURE_H
#define BRDFBAKE_BRDF_DIELECTRIC_QUADRATURE_H

#include "brdfbake/brdf/integrands.h"
#include "brdfbake/brdf/rough_dielectric.h"

/* Azimuth pieces per cell and rule, and segments per row (the kernel's output layout is per cell
 * BB_QUAD_RULES x BB_DIELECTRIC_QUAD_PIECES sums of R and of T, rule-major). */
#define BB_DIELECTRIC_QUAD_PIECES 4
#define BB_DIELECTRIC_QUAD_SEGMENTS 6

/* The smoothstep map of a segment: S(x) = x^2 (3 - 2x) and its derivative 6x(1 - x). */
BB_FN bb_real bb_smoothstep(bb_real x) { return x * x * (BB_R(3.0) - BB_R(2.0) * x); }
BB_FN bb_real bb_smoothstep_d(bb_real x) { return BB_R(6.0) * x * (BB_R(1.0) - x); }

/* The node of a row segment [t0, t0 + len] at x in [0, 1]: t and dt/dx. Through the smoothstep
 * u = S(x); on the row's last segment (`tail`) t - t0 is then distributed exponentially,
 * t = t0 - log(1 - u q), q = 1 - e^-len, because the visible-normal measure falls like e^-t
 * far out along a row (the GGX slope density times its Jacobian, ~ e^-2t, times wo.m / cos(theta_m)
 * ~ e^t), so that the integrand is about constant in u there: spread evenly in t over rows that run
 * out to slope r_cap (t ~ 38 in double), the 15-node Gauss rule misjudged the tail by 4e-4.
 * 1 - u q is formed as (1 - x)^2 (1 + 2x) + u e^-len, which loses nothing as u -> 1. */
typedef struct {
    bb_real t, dt;
} bb_segment_node;

BB_FN bb_segment_node bb_dielectric_segment_node(bb_real t0, bb_real len, bb_mask tail, bb_real x) {
    bb_real u = bb_smoothstep(x), du = bb_smoothstep_d(x);
    bb_real e = bb_exp(-len);
    bb_real rest = (BB_R(1.0) - x) * (BB_R(1.0) - x) * (BB_R(1.0) + BB_R(2.0) * x) + u * e; /* 1 - u q */
    bb_segment_node n;
    n.t = t0 + bb_select(len * u, -bb_log(rest), tail);
    n.dt = du * bb_select(len, (BB_R(1.0) - e) / rest, tail);
    return n;
}

/* The slope where every row ends (see the head of this file). */
BB_FN bb_real bb_dielectric_r_cap(bb_vec3 wo, bb_real a) {
    bb_real tan_o = wo.x / wo.z; /* phi_o = 0: wo.x = sin(theta_o) */
    return a * a * (BB_R(1.0) + BB_R(2.0) * tan_o) / (BB_EPS_REAL / BB_R(16.0)) + a;
}

/* The row coordinate t = asinh(r/a) of slope r. */
BB_FN bb_real bb_dielectric_t_of_r(bb_real r, bb_real a) {
    bb_real x = r / a;
    return bb_log(x + bb_sqrt(x * x + BB_R(1.0)));
}

/* The slope tan(theta) of polar angle theta, 0 below 0 and r_cap from pi/2 on. */
BB_FN bb_real bb_dielectric_r_of_theta(bb_real theta, bb_real r_cap) {
    bb_real c = bb_cos(theta), s = bb_sin(theta);
    bb_real r = bb_select(r_cap, bb_min(r_cap, s / c), c > BB_R(0.0));
    return bb_select(r, BB_R(0.0), theta <= BB_R(0.0));
}

/* The cosine of the critical angle of total internal reflection, sqrt(1 - eta^2) for eta < 1,
 * and 0 for eta >= 1 (no such angle). */
BB_FN bb_real bb_dielectric_c_crit(bb_real eta) { return bb_safe_sqrt((BB_R(1.0) - eta) * (BB_R(1.0) + eta)); }

/* The azimuth interval [lo, hi] of piece 0 to 3 (see the head of this file). */
typedef struct {
    bb_real lo, hi;
} bb_interval;

BB_FN bb_interval bb_dielectric_piece(bb_vec3 wo, bb_real eta, unsigned int piece) {
    const bb_real q = BB_R(0.5) * BB_PI;
    bb_real cc = bb_dielectric_c_crit(eta), sin_o = wo.x;
    bb_real inv_sin_o = BB_R(1.0) / bb_select(BB_R(1.0), sin_o, sin_o > BB_R(0.0));
    /* rho(delta)^2 = wo.z^2 + sin_o^2 cos^2(delta) = c_crit^2 */
    bb_real cos_star = bb_safe_sqrt((cc - wo.z) * (cc + wo.z)) * inv_sin_o;
    bb_real star = bb_select(q, bb_atan2(bb_safe_sqrt(BB_R(1.0) - cos_star * cos_star), cos_star),
                          eta < BB_R(1.0) && wo.z < cc && sin_o > BB_R(0.0) && cos_star <= BB_R(1.0));
    /* sin_o cos(delta) = c_crit: the edge of total internal reflection meets the horizon */
    bb_real cos_h = cc * inv_sin_o;
    bb_real edge = bb_select(BB_R(0.0), bb_min(star, bb_atan2(bb_safe_sqrt(BB_R(1.0) - cos_h * cos_h), cos_h)),
                          eta < BB_R(1.0) && sin_o > BB_R(0.0) && cos_h <= BB_R(1.0));
    bb_interval out;
    out.lo = piece == 0u ? BB_R(0.0) : (piece == 1u ? edge : (piece == 2u ? star : q));
    out.hi = piece == 0u ? edge : (piece == 1u ? star : (piece == 2u ? q : BB_R(2.0) * q));
    return out;
}

/* One row: the half vectors at azimuth delta, its segments [t[k], t[k + 1]] ascending. */
typedef struct {
    bb_real cos_phi, sin_phi;
    bb_real t[BB_DIELECTRIC_QUAD_SEGMENTS + 1];
} bb_dielectric_row;

/* The half vector at row coordinate t, and D J there (J = dm / (dt d delta)), from D J cos(theta_m)
 * as the albedo's rule forms it (bb_quad_halfvector_point). */
typedef struct {
    bb_vec3 h;
    bb_real dj;
} bb_dielectric_node;

BB_FN bb_dielectric_node bb_dielectric_node_at(bb_real cos_phi, bb_real sin_phi, bb_real a, bb_real t) {
    bb_real em1 = bb_expm1(t);
    bb_real inv_et = BB_R(1.0) / (em1 + BB_R(1.0)); /* e^-t */
    bb_real sinh_t = BB_R(0.5) * em1 * (em1 + BB_R(2.0)) * inv_et;
    bb_real cosh_t = sinh_t + inv_et;
    bb_real r = a * sinh_t;
    bb_real sec = bb_sqrt(BB_R(1.0) + r * r); /* 1 / cos(theta_m) */
    bb_real ch = BB_R(1.0) / sec;
    bb_real sh = r * ch;
    bb_dielectric_node n;
    n.h = bb_v3(sh * cos_phi, sh * sin_phi, ch);
    /* D J cos(theta_m) = a r cosh(t) times the GGX slope density 1/(pi a^2 (1 + r^2/a^2)^2)
     * (bb_quad_slope_density), with 1 + r^2/a^2 = cosh^2(t): sinh(t) / (pi cosh^3(t)) */
    bb_real inv_cosh = BB_R(1.0) / cosh_t;
    n.dj = BB_INV_PI * sinh_t * inv_cosh * inv_cosh * inv_cosh * sec;
    return n;
}

/* Where the refracted direction reaches the horizon along the row at azimuth delta (eta < 1):
 * the row coordinate of one of the two crossings, or t_none where that one does not exist.
 * A microfacet m that refracts wo into a horizontal wt = (cos psi, sin psi, 0) is
 * m = (wo + eta wt) / |wo + eta wt| [WMLT07 eq. 16, the generalized half vector], valid where
 * wt lies on the far side of m, wt.m < 0, i.e. sin_o cos(psi) < -eta (no such m for eta >= 1:
 * its z would be negative). m lies on the row (azimuth delta) where
 * eta sin(psi - delta) = sin_o sin(delta): with s = sin_o sin(delta) / eta and k = +-sqrt(1 - s^2)
 * (the two crossings, `branch` +1 or -1), cos(psi - delta) = k, and the slope of m along the row
 * is (sin_o cos(delta) + eta k) / wo.z, counted only where positive (m on the row's side). */
BB_FN bb_real bb_dielectric_t_horizon(bb_vec3 wo, bb_real a, bb_real eta, bb_real r_cap, bb_real cos_d, bb_real sin_d, bb_real branch,
                                   bb_real t_none) {
    bb_real sin_o = wo.x;
    bb_real s = sin_o * sin_d / eta;
    bb_real k = branch * bb_safe_sqrt((BB_R(1.0) - s) * (BB_R(1.0) + s));
    bb_real cos_psi = cos_d * k - sin_d * s;
    bb_real r = (sin_o * cos_d + eta * k) / wo.z;
    bb_mask ok = eta < BB_R(1.0) && bb_fabs(s) <= BB_R(1.0) && sin_o * cos_psi < -eta && r > BB_R(0.0) && r < r_cap;
    return bb_select(t_none, bb_dielectric_t_of_r(bb_select(BB_R(1.0), r, ok), a), ok);
}

/* Swaps a and b into ascending order (a sorting-network comparator). */
#define BB_SORT2(a, b)                   \
    do {                                 \
        const bb_real lo_ = bb_min((a), (b)); \
        (b) = bb_max((a), (b));          \
        (a) = lo_;                       \
    } while (0)

BB_FN bb_dielectric_row bb_make_dielectric_row(bb_vec3 wo, bb_real a, bb_real eta, bb_real r_cap, bb_real delta) {
    bb_dielectric_row row;
    row.cos_phi = bb_cos(delta);
    row.sin_phi = bb_sin(delta);
    bb_real A = wo.z, sin_o = wo.x, B = sin_o * row.cos_phi;
    /* wo.m = 0 and wr.z = 0 */
    bb_real r_v = bb_select(r_cap, bb_min(r_cap, A / -B), B < BB_R(0.0));
    bb_real r_r = bb_min(bb_quad_tan_max(A, sin_o, row.cos_phi), r_v);
    /* the edges of total internal reflection, wo.m = c_crit */
    bb_real cc = bb_dielectric_c_crit(eta);
    bb_real rho = bb_sqrt(A * A + B * B), phi0 = bb_atan2(B, A);
    bb_real psi = bb_atan2(bb_safe_sqrt((rho - cc) * (rho + cc)), cc);
    bb_mask crit = eta < BB_R(1.0) && rho > cc;
    bb_real r_a = bb_select(BB_R(0.0), bb_min(bb_dielectric_r_of_theta(phi0 - psi, r_cap), r_v), crit);
    bb_real r_b = bb_select(BB_R(0.0), bb_min(bb_dielectric_r_of_theta(phi0 + psi, r_cap), r_v), crit);
    bb_real t_v = bb_dielectric_t_of_r(r_v, a);
    bb_real t_a = bb_dielectric_t_of_r(r_a, a), t_b = bb_dielectric_t_of_r(r_b, a);
    bb_real t_r = bb_dielectric_t_of_r(r_r, a);
    /* where wt reaches the horizon: up to two crossings, in closed form */
    bb_real t_w = bb_min(t_v, bb_dielectric_t_horizon(wo, a, eta, r_cap, row.cos_phi, row.sin_phi, BB_R(1.0), t_v));
    bb_real t_x = bb_min(t_v, bb_dielectric_t_horizon(wo, a, eta, r_cap, row.cos_phi, row.sin_phi, BB_R(-1.0), t_v));
    /* sort t_a, t_b, t_w, t_x, t_r: an optimal 9-comparator network for 5 values [Knuth, TAOCP 3,
     * 5.3.4] */
    BB_SORT2(t_a, t_b);
    BB_SORT2(t_x, t_r);
    BB_SORT2(t_w, t_r);
    BB_SORT2(t_w, t_x);
    BB_SORT2(t_a, t_x);
    BB_SORT2(t_a, t_w);
    BB_SORT2(t_b, t_r);
    BB_SORT2(t_b, t_x);
    BB_SORT2(t_b, t_w);
    row.t[0] = BB_R(0.0);
    row.t[1] = t_a;
    row.t[2] = t_b;
    row.t[3] = t_w;
    row.t[4] = t_x;
    row.t[5] = t_r;
    row.t[6] = t_v;
    return row;
}

/* The integrand at row coordinate t: D J (wo.m)/wo.z times the microfacet's split, so that
 * R = sum over pieces, rows and segments of (weights) x .r, and T likewise with .t. */
BB_FN bb_rt bb_dielectric_quad_point(bb_vec3 wo, bb_real a, bb_real eta, int shadowing, int transmission_shadowing,
                                     bb_real g1o, bb_real lo, bb_real lga_o, bb_real cos_phi, bb_real sin_phi, bb_real t) {
    bb_dielectric_node n = bb_dielectric_node_at(cos_phi, sin_phi, a, t);
    bb_real c = bb_dot(wo, n.h);
    bb_real w = n.dj * c * (BB_R(1.0) / wo.z); /* 1/wo.z: the same for every node of a cell */
    bb_rt s = bb_rough_dielectric_split(wo, n.h, a, a, eta, shadowing, transmission_shadowing, g1o, lo, lga_o);
    bb_mask ok = c > BB_R(0.0);
    s.r = bb_select(BB_R(0.0), w * s.r, ok);
    s.t = bb_select(BB_R(0.0), w * s.t, ok);
    return s;
}

#endif /* BRDFBAKE_BRDF_DIELECTRIC_QUADRATURE_H */

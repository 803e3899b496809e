/* The volumetric sheen layer of [ZBC22] Zeltner, Burley and Chiang, "Practical Multiple-Scattering
 * Sheen Using Linearly Transformed Cosines", SIGGRAPH 2022 Talks: a slab of unit thickness and
 * density 1 filled with fiber-like specular SGGX microflakes [HDCD15] (Heitz, Dupuy, Crassin and
 * Dachsbacher, "The SGGX Microflake Distribution", SIGGRAPH 2015), fibers along the normal z,
 * single-scattering albedo 1, fiber cross-section sigma = alpha^2 ([ZBC22] sec. 3; alpha the
 * artist's roughness). Light enters through the top; what leaves through the top is the sheen's
 * reflectance R (the magnitude of its LTC), what leaves through the bottom is transmitted (the
 * layer below; [ZBC22] counts it as not reflected).
 *
 * The medium, with S = diag(1, 1, s^2), s = sigma [HDCD15 sec. 3, a fiber of direction z]:
 *   projected area   sigma(w) = sqrt(w^T S w) = sqrt(w.x^2 + w.y^2 + s^2 w.z^2)     [HDCD15 eq. 9]
 *   normals          D(m) = 1 / (pi sqrt|S| (m^T S^-1 m)^2)
 *                         = 1 / (pi s (m.x^2 + m.y^2 + m.z^2 / s^2)^2)                [HDCD15 eq. 8]
 *   extinction       sigma_t(w) = density sigma(w), density 1                          [HDCD15 eq. 2]
 *   phase function   p(wi -> wo) = D(wh) / (4 sigma(wi)), wh = (wi + wo)/|wi + wo|   [HDCD15 eq. 13,
 *                    the specular microflake; wi points back along the ray]
 * The SGGX normals are those of the ellipsoid x^T S x = 1, the image of the unit sphere under
 * A = S^-1/2 = diag(1, 1, 1/s). A linear map keeps ratios of projected areas, so a visible normal
 * of wi [HDCD15 sec. 5] is drawn as on a sphere seen from wi' = A^-1 wi / |A^-1 wi|: a point p'
 * uniform on the disk across wi' lifted onto the sphere's visible half; the ellipsoid's normal at
 * A p' is A^-T p' = (p'.x, p'.y, s p'.z), normalised (the construction of [H18 sec. 4] for GGX).
 *
 * The walk: from the top (depth t = 0; t grows downwards to 1 at the bottom) along -wo. A free
 * flight of length l ~ Exp(sigma_t(w)) moves the depth by -l w.z; t < 0 escapes through the top
 * (reflection, direction w), t > 1 through the bottom (transmission); otherwise the ray scatters:
 * a visible normal m of -w, w' = reflect(-w, m). With albedo 1 every walk ends in exactly one of
 * reflection, transmission, or the bounce limit (its `cutoff`, reported, never dropped).
 *
 * The paper's precomputation (Zeltner et al.'s public fitting code, which made the table Blender
 * Cycles ships, table_sheen_ltc) walks at most 16 scatterings and stops a walk right after its 16th:
 * one still inside then counts as reflected when its direction points up (its weight is 1 whatever
 * the exit), as transmitted otherwise. A negative `bounces` = -L asks for that rule with L
 * scatterings (`truncated` marks those walks; the kernel reports their share as the cut-off). At
 * low roughness it is most of the lobe's shape: rows r = 0.13-0.23 of Cycles' table are fits to it
 * (benchmarks/results/sheen-ltc-amd-epyc-2c.md, session 5).
 *
 * The reflected lobe's higher orders (what the LTC is fitted to beside the closed-form first order)
 * are tallied by next flights, not by the walks' actual exits (bb_sheen_next_flight below): after
 * each scattering n >= 2 a walk heading up adds its probability of leaving the top before it
 * scatters again to the bin of its direction; the same expectation as the analog count of the exits
 * (which the kernel still offers), but every walk that turns up contributes, not only the few that
 * get out (tests/test_sheen_next_flight.cpp compares the two). R, T and their orders stay the
 * walks' counts (R + T + cut-off = 1 per replica).
 *
 * Closed forms the walk must meet (tests): transmission without scattering T0 = exp(-sigma(wo)/mu_o)
 * (Beer-Lambert along the view), and the first order
 *   R1(wo) = integral over the upper hemisphere of p(wo -> w) k_o (1 - exp(-(k_o + k))) / (k_o + k) dw,
 *   k_o = sigma(wo)/mu_o, k = sigma(w)/mu
 * (the depth of the first collision has density k_o exp(-k_o t), the way out attenuates by exp(-k t)).
 *
 * Random numbers: Philox4x32-10 as random_walk.h, one call per flight, counter
 * (walk, replica, cell stream, BB_SHEEN_TAG | flight).
 * [H18] Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018. */
#ifndef BRDFBAKE_BRDF_SHEEN_VOLUME_H
#define BRDFBAKE_BRDF_SHEEN_VOLUME_H

#include "brdfbake/brdf/compat.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/brdf/sampling.h"

#ifdef BB_PHILOX
#include <Random123/philox.h>
#endif

/* Parameter slots of the sheen-volume model. */
#define BB_SHEEN_VOLUME_ROUGHNESS 0 /* alpha; sigma = alpha^2 */
#define BB_SHEEN_VOLUME_BOUNCES 1   /* the walk's scattering limit */
#define BB_SHEEN_VOLUME_DEFAULT_BOUNCES 1000
#define BB_SHEEN_VOLUME_MAX_BOUNCES 1000000
/* The paper's precomputation's limit, with its rule for the walks it stops (bounces = -16). */
#define BB_SHEEN_VOLUME_PAPER_BOUNCES 16

/* The fourth counter word of a sheen walk's Philox stream: "s" in the top byte. */
#define BB_SHEEN_TAG 0x73000000u

/* The fiber cross-section of a roughness: sigma = alpha^2 [ZBC22 sec. 3]. */
BB_FN bb_real bb_sheen_volume_sigma(bb_real alpha) { return alpha * alpha; }

/* Projected area sigma(w) of the fiber SGGX [HDCD15 eq. 9], s the fiber cross-section. */
BB_FN bb_real bb_sggx_fiber_area(bb_vec3 w, bb_real s) {
    return bb_sqrt(w.x * w.x + w.y * w.y + s * s * w.z * w.z);
}

/* A visible normal of wi (density <wi, m>+ D(m) / sigma(wi)) from two uniform numbers: the
 * sphere seen from A^-1 wi, mapped back by A^-T (see the header's comment). */
BB_FN bb_vec3 bb_sggx_fiber_sample_vndf(bb_vec3 wi, bb_real s, bb_real u1, bb_real u2) {
    const bb_vec3 v = bb_normalize(bb_v3(wi.x, wi.y, s * wi.z));
    /* an orthonormal basis (t1, t2, v) (Duff et al. 2017, "Building an Orthonormal Basis, Revisited") */
    const bb_real sg = bb_select(BB_R(-1.0), BB_R(1.0), v.z >= BB_R(0.0));
    const bb_real a = BB_R(-1.0) / (sg + v.z), b = v.x * v.y * a;
    const bb_vec3 t1 = bb_v3(BB_R(1.0) + sg * v.x * v.x * a, sg * b, -sg * v.x);
    const bb_vec3 t2 = bb_v3(b, sg + v.y * v.y * a, -v.y);
    const bb_real r = bb_sqrt(u1), phi = BB_R(2.0) * BB_PI * u2;
    const bb_real d1 = r * bb_cos(phi), d2 = r * bb_sin(phi);
    const bb_real lift = bb_safe_sqrt(BB_R(1.0) - d1 * d1 - d2 * d2);
    const bb_vec3 p = bb_add(bb_add(bb_scale(t1, d1), bb_scale(t2, d2)), bb_scale(v, lift));
    return bb_normalize(bb_v3(p.x, p.y, s * p.z));
}

/* How a walk ended. */
#define BB_SHEEN_EXIT_TOP 0
#define BB_SHEEN_EXIT_BOTTOM 1
#define BB_SHEEN_EXIT_CUTOFF 2
#define BB_SHEEN_EXIT_BAD 3

typedef struct {
    int exit;        /* BB_SHEEN_EXIT_*, valid once `done` */
    int scatterings; /* the scatterings so far */
    int truncated;   /* 1: stopped by the paper's rule (bounces < 0), its exit read from its direction */
    int done;        /* 1: the walk has ended */
    int flights;     /* the free flights so far (the Philox counter) */
    int bounces;     /* the scattering limit (positive) */
    int paper_limit; /* L of bounces = -L, else 0 */
    bb_real t;       /* the depth, 0 at the top, 1 at the bottom */
    bb_vec3 w;       /* the direction of flight (after `done`: the one it left in) */
} bb_sheen_walk;

/* A walk about to enter the layer from the view wo (wo.z > 0): at most `bounces` scatterings;
 * bounces = -L: the paper's rule, stopped right after the L-th scattering. */
BB_FN bb_sheen_walk bb_sheen_walk_start(bb_vec3 wo, int bounces) {
    bb_sheen_walk r;
    r.exit = BB_SHEEN_EXIT_BAD;
    r.w = bb_scale(wo, BB_R(-1.0));
    r.scatterings = 0;
    r.truncated = 0;
    r.done = 0;
    r.flights = 0;
    r.paper_limit = bounces < 0 ? -bounces : 0;
    r.bounces = bounces < 0 ? BB_SHEEN_VOLUME_MAX_BOUNCES : bounces;
    r.t = BB_R(0.0);
    return r;
}

/* The next-flight tally of a walk that has just scattered (r->scatterings = n >= 1) into r->w at
 * depth r->t: the probability that its next free flight leaves through the top, so that the walk
 * exits after exactly n scatterings in the direction r->w. Given the walk up to its n-th scattering
 * the flight l ~ Exp(sigma_t(w)) leaves through the top iff w.z > 0 and l > t / w.z, probability
 *   exp(-sigma(w) t / w.z)                                    (Beer-Lambert, density 1),
 * the expectation of the analog tally 1{exit through the top after n scatterings, in w} given that
 * history: summed over n, the same mean as the analog count of the exits, per exit direction (the
 * expected-value, or next-flight, estimator of neutron transport: Spanier and Gelbard, "Monte Carlo
 * Principles and Neutron Transport Problems", 1969, sec. 5.3; Lux and Koblinger, "Monte Carlo
 * Particle Transport Methods", 1991, ch. 6), and every walk that scatters up adds to it, not only
 * the few that get out. The walk then flies on as before (its actual exit is no longer tallied:
 * nothing counts twice). Under the paper's rule (bounces = -L) a walk just stopped after its L-th
 * scattering counts as reflected by its direction [ZBC22's precomputation]: its tally is 1 for
 * w.z > 0 (the expectation of that rule's exit given the history is the rule itself). Under the
 * bounce limit a walk's tally after its last allowed scattering is still the transmittance: its
 * actual next flight decides between an exit and the cut-off, whose share is reported as before. */
BB_FN bb_real bb_sheen_next_flight(bb_sheen_walk r, bb_real s) {
    if (!(r.w.z > BB_R(0.0))) return BB_R(0.0);
    if (r.truncated) return BB_R(1.0);
    return bb_exp(-bb_sggx_fiber_area(r.w, s) * r.t / r.w.z);
}

#ifdef BB_PHILOX
/* One free flight of the walk r through the layer of fiber cross-section s and, when it stays
 * inside, one scattering. Returns 1 when the walk scattered (r->w its new direction; r->done when the
 * paper's rule stopped it there), 0 when it ended without scattering (an exit, the cut-off, or a
 * non-finite number). One Philox call per flight: counter (walk, replica, stream, BB_SHEEN_TAG | flight). */
BB_FN int bb_sheen_walk_step(bb_sheen_walk* r, bb_real s, philox4x32_key_t key, unsigned int walk,
                             unsigned int rep, unsigned int stream) {
    const int k = r->flights++;
    philox4x32_ctr_t ctr = {{walk, rep, stream, BB_SHEEN_TAG | (unsigned int)k}};
    philox4x32_ctr_t u = philox4x32(ctr, key);
    /* free flight: l = -log(1 - U) / sigma_t(w) */
    const bb_real l = -bb_log1p(-bb_unit_from_bits(u.v[0])) / bb_sggx_fiber_area(r->w, s);
    r->t = r->t - l * r->w.z;
    if (r->t < BB_R(0.0) || r->t > BB_R(1.0)) {
        r->exit = r->t < BB_R(0.0) ? BB_SHEEN_EXIT_TOP : BB_SHEEN_EXIT_BOTTOM;
        r->done = 1;
        return 0;
    }
    if (k == r->bounces) {
        r->exit = BB_SHEEN_EXIT_CUTOFF;
        r->done = 1;
        return 0;
    }
    /* scattering: a visible normal of -w, specular reflection */
    const bb_vec3 v = bb_scale(r->w, BB_R(-1.0));
    const bb_vec3 m = bb_sggx_fiber_sample_vndf(v, s, bb_unit_from_bits(u.v[1]), bb_unit_from_bits(u.v[2]));
    r->w = bb_normalize(bb_reflect(v, m));
    r->scatterings = k + 1;
    if (!bb_isfinite(r->w.z) || !bb_isfinite(r->t)) {
        r->exit = BB_SHEEN_EXIT_BAD;
        r->done = 1;
        return 0;
    }
    if (r->scatterings == r->paper_limit) {
        r->truncated = 1;
        r->exit = r->w.z > BB_R(0.0) ? BB_SHEEN_EXIT_TOP : BB_SHEEN_EXIT_BOTTOM;
        r->done = 1;
    }
    return 1;
}
#endif

#endif /* BRDFBAKE_BRDF_SHEEN_VOLUME_H */

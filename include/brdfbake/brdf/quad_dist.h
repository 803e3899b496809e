/* The coordinate system of a model's albedo quadrature (integrands.h), shared by host and
 * kernels: the sampler's unit square, or half-vector space with the radial CDF of one of three
 * distributions of normals. The half-vector models (model_registry.h, quadrature space
 * HALFVECTOR) each give theirs with bb_<name>_quad_dist(p). */
#ifndef BRDFBAKE_BRDF_QUAD_DIST_H
#define BRDFBAKE_BRDF_QUAD_DIST_H

#include "brdfbake/brdf/compat.h"

#define BB_QUAD_SAMPLER 0 /* sampler space */
#define BB_QUAD_GGX 1     /* half-vector space, radial CDF of GGX D cos */
#define BB_QUAD_BECKMANN 2
#define BB_QUAD_BLINN 3   /* cos^(N+1) density */

/* The coordinate system of the quadrature for a model, and its distribution's parameters. */
typedef struct {
    int kind;
    bb_real ax, ay, n;
} bb_quad_dist;

BB_FN bb_quad_dist bb_make_quad_dist(int kind, bb_real ax, bb_real ay, bb_real n) {
    bb_quad_dist d;
    d.kind = kind;
    d.ax = ax;
    d.ay = ay;
    d.n = n;
    return d;
}

#endif /* BRDFBAKE_BRDF_QUAD_DIST_H */

/* The GGX (Trowbridge-Reitz) microfacet BRDF with Smith masking-shadowing:
 *   f = D(wh) G2(wo, wi) F(wo.wh) / (4 cos_theta_o cos_theta_i)      [WMLT07 eq. 20]
 * with D, G1, G2 from microfacet.h; G2 separable, height-correlated or masking only (smith.h). */
#ifndef BRDFBAKE_BRDF_GGX_H
#define BRDFBAKE_BRDF_GGX_H

#include "brdfbake/brdf/smith.h"

/* Parameter slots: those of every Smith lobe (smith.h). */
#define BB_GGX_ALPHA_X BB_SMITH_ALPHA_X
#define BB_GGX_ALPHA_Y BB_SMITH_ALPHA_Y
#define BB_GGX_SHADOWING BB_SMITH_SHADOWING /* BB_SHADOWING_SEPARABLE, _CORRELATED or _MASKING */
/* The rough dielectric's transmitted G2 under shadowing=correlated (the spec's
 * transmission_shadowing=beta|cycles): BB_TRANSMISSION_SHADOWING_* of rough_dielectric.h. No
 * reflection reads it. */
#define BB_GGX_TRANSMISSION_SHADOWING 3

/* The Smith lobe (smith.h) with the GGX distribution. Its importance sample takes the visible
 * normal [H18] of the disk point bb_disk_polar(u1, u2), which the fast kernels tabulate
 * (bb_ggx_disk_* below). */
BB_SMITH_LOBE(ggx, BB_SMITH_GGX)

/* The same estimator weight, F(wo.wh) G2(wo, wi) / G1(wo), in the two halves the vector kernel
 * uses (kernels/albedo.cl, albedo_replicas_disk): what depends on the cell alone, once per cell
 * (bb_ggx_disk_cell_make), and the weight of one disk point (bb_ggx_disk_weight), in a closed
 * form on the unnormalised visible normal. With Nh the normal of the hemisphere configuration
 * [H18 sec. 4.3], n = (ax Nh.x, ay Nh.y, max(0, Nh.z)), L = n.n and W = L wi = 2 (wo.n) n - L wo
 * (the reflection of wo about n/|n|, scaled by L): Lambda(wi) = (q / W.z - 1) / 2 with
 * q = sqrt(W.z^2 + (ax W.x)^2 + (ay W.y)^2) [H14 eq. 86, 80], and
 *   G2/G1(wo) = c0 / (c0 + Lambda(wi)) = 2 c0 W.z / ((2 c0 - 1) W.z + kq q),
 * c0 = 1/G1(wo) = 1 + Lambda(wo) for height-correlated G2 [H14 eq. 99], c0 = 1 for separable
 * G2 (the weight is then G1(wi)), kq = 1; masking-only G2 = G1(wo) (smith.h) has the weight 1:
 * there k2 = k1 = 1 and kq = 0 give W.z / W.z (W.z > 0 where the weight is kept). Every term of the denominator is >= 0 (c0 >= 1 or
 * kq = 0): no cancellation, however small alpha. Per sample: two square roots and one division, where
 * bb_ggx_sample's normalise, reflect, G1(wi), G2 and / G1(wo) take four of each; a Fresnel
 * term adds F((wo.n) / sqrt(L)). Algebraically bb_ggx_sample's weight (tests/test_microfacet.cpp
 * compares them). */
typedef struct {
    bb_vec3 wo;             /* the view; (sin, 0, cos) when isotropic */
    bb_vec3 vh, t1, t2;     /* the stretched view and its basis [H18 sec. 3.2, 4.1], */
    bb_vec3 a_t1, a_t2, a_vh; /* ... and the same scaled by (ax, ay, 1) */
    bb_real ax, ay, s;         /* s = (1 + vh.z) / 2 [H18 sec. 4.2] */
    bb_real ax2, ay2, b2;      /* ax^2, ay^2 and 1 - ax^2 */
    bb_real k2, k1, kq;        /* 2 c0, 2 c0 - 1 and q's factor */
    bb_real live;              /* 1 where G1(wo) > 0, else 0: every weight 0 */
} bb_ggx_disk_cell;

/* isotropic (a constant: the kernels pass -D BB_ISOTROPIC when every cell has ax = ay) rotates
 * wo about the normal into the x-z plane, which changes no albedo of an isotropic BRDF, and lets
 * bb_ggx_disk_weight drop the terms that are then 0 (wo.y, vh.y, t1.x, t2.y; ax = ay). */
BB_FN bb_ggx_disk_cell bb_ggx_disk_cell_make(bb_params p, bb_vec3 wo, int isotropic) {
    bb_ggx_disk_cell c;
    c.ax = p.v[BB_GGX_ALPHA_X];
    c.ay = isotropic ? c.ax : p.v[BB_GGX_ALPHA_Y];
    c.wo = isotropic ? bb_v3(bb_sqrt(wo.x * wo.x + wo.y * wo.y), BB_R(0.0), wo.z) : wo;
    c.vh = bb_normalize(bb_v3(c.ax * c.wo.x, c.ay * c.wo.y, c.wo.z));
    bb_real lensq = c.vh.x * c.vh.x + c.vh.y * c.vh.y;
    bb_real inv_len = BB_R(1.0) / bb_sqrt(bb_select(BB_R(1.0), lensq, lensq > BB_R(0.0)));
    c.t1 = bb_v3(bb_select(BB_R(1.0), -c.vh.y * inv_len, lensq > BB_R(0.0)),
                 bb_select(BB_R(0.0), c.vh.x * inv_len, lensq > BB_R(0.0)), BB_R(0.0));
    if (isotropic) /* (0, 1, 0) also at normal incidence: the disk turned by 90 degrees there */
        c.t1 = bb_v3(BB_R(0.0), BB_R(1.0), BB_R(0.0));
    c.t2 = bb_cross(c.vh, c.t1);
    c.a_t1 = bb_v3(c.ax * c.t1.x, c.ay * c.t1.y, BB_R(0.0));
    c.a_t2 = bb_v3(c.ax * c.t2.x, c.ay * c.t2.y, c.t2.z);
    c.a_vh = bb_v3(c.ax * c.vh.x, c.ay * c.vh.y, c.vh.z);
    c.s = BB_R(0.5) * (BB_R(1.0) + c.vh.z);
    c.ax2 = c.ax * c.ax;
    c.ay2 = c.ay * c.ay;
    c.b2 = BB_R(1.0) - c.ax2;
    bb_real g1o = bb_ggx_g1(c.wo, c.ax, c.ay);
    bb_real c0 = bb_select(BB_R(1.0), BB_R(1.0) / bb_select(BB_R(1.0), g1o, g1o > BB_R(0.0)),
                        p.v[BB_GGX_SHADOWING] == BB_R(BB_SHADOWING_CORRELATED));
    c.kq = bb_select(BB_R(1.0), BB_R(0.0), p.v[BB_GGX_SHADOWING] == BB_R(BB_SHADOWING_MASKING)); /* 0: masking only */
    c.k2 = bb_select(BB_R(1.0), BB_R(2.0) * c0, c.kq > BB_R(0.5));
    c.k1 = bb_select(BB_R(1.0), c.k2 - BB_R(1.0), c.kq > BB_R(0.5));
    c.live = bb_select(BB_R(0.0), BB_R(1.0), g1o > BB_R(0.0));
    return c;
}

/* The weight of the disk point d = bb_disk_polar(u1, u2), given h = sqrt(1 - d.x^2) (both
 * cell-independent: the host tabulates them); isotropic as for bb_ggx_disk_cell_make. */
BB_FN bb_real bb_ggx_disk_weight(bb_ggx_disk_cell c, int fkind, bb_params fp, bb_vec2 d, bb_real h, int isotropic) {
    /* [H18 sec. 4.2, 4.3]: the point of the projected area, lifted onto the hemisphere */
    bb_real p1 = d.x;
    bb_real p2 = (BB_R(1.0) - c.s) * h + c.s * d.y;
    bb_real p3 = bb_safe_sqrt(BB_R(1.0) - p1 * p1 - p2 * p2);
    /* n = (ax, ay, 1) (p1 t1 + p2 t2 + p3 vh) (t1.z = 0), max(0, z) [H18 sec. 3.4], not
     * normalised; L = |n|^2 and W = L wi = 2 (wo.n) n - L wo */
    bb_real nx, ny, nz, len2, on, wz, q;
    nz = bb_max(BB_R(0.0), p2 * c.t2.z + p3 * c.vh.z);
    if (isotropic) { /* t1 = (0, 1, 0), t2.y = vh.y = wo.y = 0, ax = ay */
        nx = p2 * c.a_t2.x + p3 * c.a_vh.x;
        ny = c.ax * p1;
        len2 = nx * nx + ny * ny + nz * nz;
        on = c.wo.x * nx + c.wo.z * nz;
        wz = BB_R(2.0) * on * nz - len2 * c.wo.z;
        /* W.x^2 + W.y^2 = L^2 - W.z^2 (|wi| = 1) */
        q = bb_sqrt(c.ax2 * len2 * len2 + c.b2 * wz * wz);
    } else {
        nx = p1 * c.a_t1.x + p2 * c.a_t2.x + p3 * c.a_vh.x;
        ny = p1 * c.a_t1.y + p2 * c.a_t2.y + p3 * c.a_vh.y;
        len2 = nx * nx + ny * ny + nz * nz;
        on = c.wo.x * nx + c.wo.y * ny + c.wo.z * nz;
        bb_real wx = BB_R(2.0) * on * nx - len2 * c.wo.x;
        bb_real wy = BB_R(2.0) * on * ny - len2 * c.wo.y;
        wz = BB_R(2.0) * on * nz - len2 * c.wo.z;
        q = bb_sqrt(wz * wz + c.ax2 * wx * wx + c.ay2 * wy * wy);
    }
    bb_real w = c.k2 * wz / (c.k1 * wz + c.kq * q);
    if (fkind != BB_FRESNEL_NONE)
        w = w * bb_fresnel_eval(fkind, fp, bb_clamp_cos(on / bb_sqrt(len2)));
    return bb_select(BB_R(0.0), w, wz > BB_R(0.0) && c.live > BB_R(0.0));
}

#endif /* BRDFBAKE_BRDF_GGX_H */

/* A measured isotropic BRDF in the MERL format of
 *   [M03] Matusik, Pfister, Brand, McMillan, "A Data-Driven Reflectance Model", ACM TOG 22(3)
 *         (SIGGRAPH 2003), and the MERL BRDF database's reader BRDFRead.cpp,
 * tabulated in the half/difference angles of
 *   [R98] Rusinkiewicz, "A New Change of Variables for Efficient BRDF Representation",
 *         Eurographics Workshop on Rendering 1998:
 *
 *   h = (wo + wi) / |wo + wi|,  theta_h = angle(h, n),  phi_h = azimuth of h         [R98 sec. 3]
 *   d = R_y(-theta_h) R_z(-phi_h) wi,  theta_d = angle(d, n),  phi_d = azimuth of d   [R98 eq. 1]
 *
 * and in [M03]'s bins (90 x 90 x 180, the file's three dimensions), the bin of a direction pair
 *
 *   i_h = floor(90 sqrt(theta_h / (pi/2))),  i_d = floor(90 theta_d / (pi/2)),
 *   i_p = floor(180 phi_d / pi),  phi_d folded into [0, pi) by phi_d + pi (reciprocity)
 *
 * each clamped to its last bin, the value at index i_p + 180 (i_d + 90 i_h). The bins' nodes
 * (where a bin's value belongs) are their lower edges, theta_h = (i_h/90)^2 pi/2,
 * theta_d = i_d pi/180, phi_d = i_p pi/180, the inverse of the index map that MERL's reader
 * applies (bb_merl_node_dirs).
 *
 * Lookup (slot BB_MERL_INTERP):
 *   nearest  the bin's value, as BRDFRead.cpp's lookup_brdf_val (the default: a measured file's
 *            values are what was measured, and the albedo of a nearest lookup is the file's own
 *            piecewise-constant function, which any reader of the database reproduces);
 *   linear   trilinear between the 8 nodes about the point in (90 sqrt(theta_h/(pi/2)),
 *            90 theta_d/(pi/2), 180 phi_d/pi), phi_d periodic with period pi, theta clamped at the
 *            last node; unmeasured nodes take no weight and the others are renormalised.
 * A negative value marks an unmeasured bin: it reads as 0 here (a nearest lookup, or a linear
 * one with no measured node) and the host counts such bins and the share of the integrand that
 * reads them (host/models/merl_file.h), so that they are reported, never silently used.
 *
 * The model's data is one channel (r, g, b or Rec. 709 luminance y, already scaled by [M03]'s
 * 1/1500, 1.15/1500, 1.66/1500) of BB_MERL_BINS values per table, the tables of a process one
 * after the other in the model data buffer (BB_MODEL_DATA_ARG); slot BB_MERL_TABLE is the
 * table's index there. On the host the same tables are read through bb_merl_host_table.
 *
 * Sampling: the cosine warp (the measured lobe has no closed-form sampler): weight pi f.
 * Edge cases: 0 at or below either horizon; h from wo + wi, which is never 0 when both are
 * above the horizon. */
#ifndef BRDFBAKE_BRDF_MERL_H
#define BRDFBAKE_BRDF_MERL_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Parameter slots. */
#define BB_MERL_TABLE 0  /* the table's index in the model data */
#define BB_MERL_INTERP 1 /* BB_MERL_NEAREST or BB_MERL_LINEAR */
#define BB_MERL_MIRROR 2 /* 1: the lookup is mirror-symmetric (bb_merl_mirror_symmetric) */

#define BB_MERL_NEAREST 0
#define BB_MERL_LINEAR 1

/* [M03]'s resolution. */
#define BB_MERL_THETA_H 90
#define BB_MERL_THETA_D 90
#define BB_MERL_PHI_D 180
#define BB_MERL_BINS (BB_MERL_THETA_H * BB_MERL_THETA_D * BB_MERL_PHI_D)

#ifdef __OPENCL_C_VERSION__
#define BB_MERL_DATA(p) ((p).data + (size_t)(p).v[BB_MERL_TABLE] * BB_MERL_BINS)
#else
/* The host's copy of table `index` (host/models/merl_file.cpp). */
const double* bb_merl_host_table(int index);
#define BB_MERL_DATA(p) bb_merl_host_table((int)(p).v[BB_MERL_TABLE])
#endif

/* The continuous bin coordinates (x_h, x_d, x_p) of the pair [R98 sec. 3], for wo.z, wi.z > 0:
 * node k of an axis at x = k. */
BB_FN bb_vec3 bb_merl_coords(bb_vec3 wo, bb_vec3 wi) {
    bb_real sx = wo.x + wi.x, sy = wo.y + wi.y, sz = wo.z + wi.z;
    bb_real len = bb_sqrt(sx * sx + sy * sy + sz * sz);
    bb_real hx = sx / len, hy = sy / len, hz = sz / len;
    bb_real sin_h = bb_sqrt(hx * hx + hy * hy);
    /* The angles by the half-angle identity theta = 2 atan(sin / (1 + cos)) (unit vector), and
     * atan(y/x) picked per half-plane so that no sum cancels: one atan and one division each,
     * where atan2 spent 12.6% of a merl albedo's run in its branches (issue 34 item 7). */
    bb_real theta_h = BB_R(2.0) * bb_atan(sin_h / (BB_R(1.0) + hz)); /* hz > 0 */
    /* R_z(-phi_h): (a, b) = (x cos phi_h + y sin phi_h, -x sin phi_h + y cos phi_h) */
    bb_real cp = BB_R(1.0), sp = BB_R(0.0);
    if (sin_h > BB_R(0.0)) {
        cp = hx / sin_h;
        sp = hy / sin_h;
    }
    /* d of either vector: wo's and wi's differ by pi in phi_d, the same bin after the fold; the
     * one taken is chosen by an order that does not depend on the order of the arguments (the
     * lower z, then x, then y), so that rounding at the fold cannot break f(wo, wi) = f(wi, wo). */
    bb_vec3 v = wi;
    if (wo.z < wi.z || (wo.z == wi.z && (wo.x < wi.x || (wo.x == wi.x && wo.y < wi.y)))) v = wo;
    bb_real a = v.x * cp + v.y * sp, b = -v.x * sp + v.y * cp;
    /* R_y(-theta_h): (a cos theta_h - z sin theta_h, b, a sin theta_h + z cos theta_h) */
    bb_real dx = a * hz - v.z * sin_h, dz = a * sin_h + v.z * hz;
    /* |d| = 1 and dz = d.h >= 0: theta_d = 2 atan(sin / (1 + cos)) */
    bb_real sin_d = bb_sqrt(dx * dx + b * b);
    bb_real theta_d = BB_R(2.0) * bb_atan(sin_d / (BB_R(1.0) + bb_max(dz, BB_R(0.0))));
    /* phi_d folded into [0, pi] (reciprocity: phi_d and phi_d + pi are one bin): (dx, b) taken
     * with b >= 0, then phi = 2 atan(b / (r + dx)) for dx >= 0 and pi - 2 atan(b / (r - dx))
     * for dx < 0, r = sin_d (0 when d is the normal: phi_d = 0). On the axis b = 0, dx < 0 the
     * fold keeps atan2's signed zero: +0 gives pi, -0 gives 0. */
    if (b < BB_R(0.0) || (b == BB_R(0.0) && dx < BB_R(0.0) && bb_signbit(b))) {
        b = -b;
        dx = -dx;
    }
    bb_real phi_d = BB_R(0.0);
    if (sin_d > BB_R(0.0))
        phi_d = dx >= BB_R(0.0) ? BB_R(2.0) * bb_atan(b / (sin_d + dx)) : BB_PI - BB_R(2.0) * bb_atan(b / (sin_d - dx));
    return bb_v3(BB_R(BB_MERL_THETA_H) * bb_sqrt(bb_max(theta_h, BB_R(0.0)) * BB_R(2.0) * BB_INV_PI),
                 BB_R(BB_MERL_THETA_D) * theta_d * BB_R(2.0) * BB_INV_PI, BB_R(BB_MERL_PHI_D) * phi_d * BB_INV_PI);
}

/* The index of bins (ih, id, ip) in a table. */
BB_FN int bb_merl_index(int ih, int id, int ip) { return ip + BB_MERL_PHI_D * (id + BB_MERL_THETA_D * ih); }

/* floor(x) clamped to [0, n - 1]. */
BB_FN int bb_merl_bin(bb_real x, int n) {
    int i = (int)bb_floor(x);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

/* The nearest lookup of [M03]'s reader, bins as the head of this file; -1 where unmeasured. */
#ifdef __OPENCL_C_VERSION__
BB_FN bb_real bb_merl_nearest(__global const bb_scalar* t, bb_vec3 x) {
#else
BB_FN bb_real bb_merl_nearest(const double* t, bb_vec3 x) {
#endif
    return t[bb_merl_index(bb_merl_bin(x.x, BB_MERL_THETA_H), bb_merl_bin(x.y, BB_MERL_THETA_D),
                           bb_merl_bin(x.z, BB_MERL_PHI_D))];
}

/* Trilinear between the 8 nodes about x (the head of this file); -1 where none is measured. */
#ifdef __OPENCL_C_VERSION__
BB_FN bb_real bb_merl_linear(__global const bb_scalar* t, bb_vec3 x) {
#else
BB_FN bb_real bb_merl_linear(const double* t, bb_vec3 x) {
#endif
    bb_real xh = bb_clamp(x.x, BB_R(0.0), BB_R(BB_MERL_THETA_H - 1));
    bb_real xd = bb_clamp(x.y, BB_R(0.0), BB_R(BB_MERL_THETA_D - 1));
    int ih = bb_merl_bin(xh, BB_MERL_THETA_H - 1), id = bb_merl_bin(xd, BB_MERL_THETA_D - 1);
    int ip = bb_merl_bin(x.z, BB_MERL_PHI_D);
    bb_real fh = xh - (bb_real)ih, fd = xd - (bb_real)id;
    bb_real fp = bb_clamp(x.z - (bb_real)ip, BB_R(0.0), BB_R(1.0));
    bb_real sum = BB_R(0.0), weight = BB_R(0.0);
    for (int k = 0; k < 8; ++k) {
        int dh = k & 1, dd = (k >> 1) & 1, dp = (k >> 2) & 1;
        int jp = ip + dp == BB_MERL_PHI_D ? 0 : ip + dp; /* phi_d = pi is node 0 again */
        bb_real v = t[bb_merl_index(ih + dh, id + dd, jp)];
        bb_real w = (dh ? fh : BB_R(1.0) - fh) * (dd ? fd : BB_R(1.0) - fd) * (dp ? fp : BB_R(1.0) - fp);
        if (v >= BB_R(0.0)) {
            sum += w * v;
            weight += w;
        }
    }
    return weight > BB_R(0.0) ? sum / weight : BB_R(-1.0);
}

/* Whether the lookup is symmetric under the mirror image of a pair (y -> -y, which takes phi_d to
 * pi - phi_d after the fold), so that a quadrature may integrate half the azimuth about a viewer
 * in the mirror plane and double it (integrands.h, bb_quad_mirrored). The host sets the slot:
 * 1 for interp=linear on a table whose nodes k and 180 - k of phi_d hold the same values (within
 * 1e-9 relative; the nodes map onto each other, and so does the trilinear interpolant); 0 for a
 * table that is not (a measured file need not be) and for interp=nearest, whose bins
 * [k, k + 1) mirror onto [179 - k, 180 - k), not onto a bin. */
BB_FN int bb_merl_mirror_symmetric(bb_params p) { return bb_all(p.v[BB_MERL_MIRROR] != BB_R(0.0)); }

BB_FN bb_real bb_merl_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    if (!(wo.z > BB_R(0.0) && wi.z > BB_R(0.0))) return BB_R(0.0);
    bb_vec3 x = bb_merl_coords(wo, wi);
    bb_real v = p.v[BB_MERL_INTERP] == BB_R(BB_MERL_LINEAR) ? bb_merl_linear(BB_MERL_DATA(p), x)
                                                            : bb_merl_nearest(BB_MERL_DATA(p), x);
    return bb_max(v, BB_R(0.0)); /* unmeasured: 0, counted by the host */
}

/* The cosine warp (pdf cos(theta_i)/pi): weight pi f. */
BB_FN bb_sample bb_merl_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_vec3 wi = bb_cosine_hemisphere(u1, u2);
    return bb_make_sample(wi, BB_PI * bb_merl_eval(p, wo, wi));
}

#endif /* BRDFBAKE_BRDF_MERL_H */

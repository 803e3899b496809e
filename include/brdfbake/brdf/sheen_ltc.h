/* The LTC sheen of
 *   [ZBC22] Zeltner, Burley and Chiang, "Practical Multiple-Scattering Sheen Using Linearly
 *           Transformed Cosines", SIGGRAPH 2022 Talks (OpenPBR's fuzz, Blender's Sheen BSDF),
 * the fitted lobe of the volumetric sheen layer (brdf/sheen_volume.h) as renderers evaluate it:
 *
 *   f(wo, wi) cos(theta_i) = R(mu, r) D_ltc(wi),                                     [ZBC22 eq. 1]
 *   D_ltc(w) = D_o(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3,  D_o(w) = max(0, z)/pi
 *                                          [Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-
 *                                           Light Shading with Linearly Transformed Cosines", eq. 1]
 *   M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]] in the frame where wo = (sin theta_o, 0, cos theta_o),
 *
 * with (a, b, R) read from a table that brdfbake baked (`lut sheen-ltc`: data/sheen_ltc/, or a
 * table=FILE) bilinearly in (mu = cos theta_o, r = roughness), each channel on its own, as Blender
 * Cycles' bsdf_sheen_setup reads table_sheen_ltc through lookup_table_read_2D
 * (intern/cycles/kernel/closure/bsdf_sheen.h, kernel/util/lookup_table.h): r clamped to the
 * table's nodes, as Cycles clamps roughness to [1e-3, 1]. M^-1 keeps z, so it maps the upper
 * hemisphere onto itself and D_ltc integrates to 1 over it: the albedo is R(mu, r) exactly.
 *
 * Sampling: the LTC's own ([Heitz et al. 2016] sec. 3.1): a cosine sample w' mapped to
 * M w' / |M w'|, pdf D_ltc, weight R.
 *
 * The model data (BB_MODEL_DATA_ARG) holds every table of the process one after the other; a table
 * at offset BB_SHEEN_LTC_OFFSET is nx mu nodes, ny roughness nodes (both increasing), then the
 * planes a, b, R of nx * ny values each, texel (i, j) at j * nx + i. */
#ifndef BRDFBAKE_BRDF_SHEEN_LTC_H
#define BRDFBAKE_BRDF_SHEEN_LTC_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Parameter slots. */
#define BB_SHEEN_LTC_ALPHA 0  /* alpha = roughness^2 (the layer's sigma), as the sheen model's */
#define BB_SHEEN_LTC_OFFSET 1 /* the table's offset in the model data */
#define BB_SHEEN_LTC_NX 2     /* its mu nodes */
#define BB_SHEEN_LTC_NY 3     /* its roughness nodes */

#ifdef __OPENCL_C_VERSION__
#define BB_SHEEN_LTC_PTR __global const bb_scalar*
#define BB_SHEEN_LTC_DATA(p) ((p).data + (size_t)(p).v[BB_SHEEN_LTC_OFFSET])
#else
#define BB_SHEEN_LTC_PTR const double*
/* The host's copy of the process's tables (host/models/sheen_ltc_table.cpp). */
const double* bb_sheen_ltc_host_data(void);
#define BB_SHEEN_LTC_DATA(p) (bb_sheen_ltc_host_data() + (size_t)(p).v[BB_SHEEN_LTC_OFFSET])
#endif

/* The node interval of x among n increasing nodes: its lower index in [0, n - 2] and the weight
 * of the upper node, x clamped to the nodes (lookup_table_read's clamp). */
BB_FN int bb_sheen_ltc_interval(BB_SHEEN_LTC_PTR nodes, int n, bb_real x, bb_real* t) {
    bb_real xc = bb_clamp(x, (bb_real)nodes[0], (bb_real)nodes[n - 1]);
    int i = 0;
    while (i < n - 2 && xc >= (bb_real)nodes[i + 1]) ++i;
    bb_real lo = (bb_real)nodes[i], hi = (bb_real)nodes[i + 1];
    *t = hi > lo ? bb_clamp((xc - lo) / (hi - lo), BB_R(0.0), BB_R(1.0)) : BB_R(0.0);
    return i;
}

/* (a, b, R) at (mu, r), bilinear between the four texels about it. */
BB_FN bb_vec3 bb_sheen_ltc_lookup(bb_params p, bb_real mu) {
    BB_SHEEN_LTC_PTR d = BB_SHEEN_LTC_DATA(p);
    int nx = (int)p.v[BB_SHEEN_LTC_NX], ny = (int)p.v[BB_SHEEN_LTC_NY];
    bb_real tx, ty;
    int i = bb_sheen_ltc_interval(d, nx, mu, &tx);
    int j = bb_sheen_ltc_interval(d + nx, ny, bb_sqrt(p.v[BB_SHEEN_LTC_ALPHA]), &ty);
    BB_SHEEN_LTC_PTR plane = d + nx + ny;
    bb_real out[3];
    for (int k = 0; k < 3; ++k) {
        BB_SHEEN_LTC_PTR c = plane + k * nx * ny + j * nx + i;
        bb_real lo = (BB_R(1.0) - tx) * (bb_real)c[0] + tx * (bb_real)c[1];
        bb_real hi = (BB_R(1.0) - tx) * (bb_real)c[nx] + tx * (bb_real)c[nx + 1];
        out[k] = (BB_R(1.0) - ty) * lo + ty * hi;
    }
    return bb_v3(out[0], out[1], out[2]);
}

/* cos and sin of wo's azimuth (1, 0 at the normal). */
BB_FN bb_real bb_sheen_ltc_azimuth(bb_vec3 wo, bb_real* s) {
    bb_real len = bb_sqrt(wo.x * wo.x + wo.y * wo.y);
    *s = len > BB_R(0.0) ? wo.y / len : BB_R(0.0);
    return len > BB_R(0.0) ? wo.x / len : BB_R(1.0);
}

/* D_ltc of M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]] at the unit w of wo's frame (the head of this file). */
BB_FN bb_real bb_sheen_ltc_density(bb_real a, bb_real b, bb_vec3 w) {
    bb_real u = a * w.x + b * w.z, v = a * w.y;
    bb_real n2 = u * u + v * v + w.z * w.z; /* |M^-1 w|^2; D_o(M^-1 w / n) a^2 / n^3 = z a^2 / (pi n^4) */
    return bb_max(w.z, BB_R(0.0)) * BB_INV_PI * a * a / (n2 * n2);
}

BB_FN bb_real bb_sheen_ltc_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    if (!(wo.z > BB_R(0.0) && wi.z > BB_R(0.0))) return BB_R(0.0);
    bb_vec3 abr = bb_sheen_ltc_lookup(p, wo.z);
    if (!(abr.x > BB_R(0.0))) return BB_R(0.0);
    bb_real s, c = bb_sheen_ltc_azimuth(wo, &s);
    bb_vec3 w = bb_v3(c * wi.x + s * wi.y, -s * wi.x + c * wi.y, wi.z);
    return abr.z * bb_sheen_ltc_density(abr.x, abr.y, w) / wi.z;
}

/* The LTC's sampler: w = M w' / |M w'| for a cosine sample w', M = [[1/a, 0, -b/a], [0, 1/a, 0],
 * [0, 0, 1]]; pdf D_ltc(w), so the weight f cos / pdf is R. */
BB_FN bb_sample bb_sheen_ltc_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    bb_vec3 abr = bb_sheen_ltc_lookup(p, wo.z);
    bb_vec3 c = bb_cosine_hemisphere(u1, u2);
    bb_real a = bb_select(BB_R(1.0), abr.x, abr.x > BB_R(0.0));
    bb_real x = (c.x - abr.y * c.z) / a, y = c.y / a, z = c.z;
    bb_real len = bb_sqrt(x * x + y * y + z * z);
    x /= len;
    y /= len;
    z /= len;
    bb_real s, co = bb_sheen_ltc_azimuth(wo, &s);
    bb_vec3 wi = bb_v3(co * x - s * y, s * x + co * y, z);
    bb_real weight = bb_select(BB_R(0.0), abr.z, wo.z > BB_R(0.0) && wi.z > BB_R(0.0) && abr.x > BB_R(0.0));
    return bb_make_sample(wi, weight);
}

#endif /* BRDFBAKE_BRDF_SHEEN_LTC_H */

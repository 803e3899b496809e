/* The volumetric sheen layer of [ZBC22] (Zeltner, Burley and Chiang 2022; brdf/sheen_volume.h) as
 * a model spec, `sheen-volume:roughness=R[,bounces=N]`: a random walk through a slab of fiber SGGX
 * microflakes, whose f has no pointwise value. The registry marks it BB_TRAIT_STOCHASTIC and
 * BB_TRAIT_LAYER_WALK: albedo, check, lobe and lut albedo run the layer's walks
 * (host/integrate/sheen_volume.h), every pointwise use (evaluate, the Python module's f, a
 * quadrature, the importance sampler) is refused on the host before any kernel is built.
 *
 * The functions below exist only because every registry row compiles into the generic kernels;
 * they return 0 (no value, no sample) and nothing calls them. */
#ifndef BRDFBAKE_BRDF_SHEEN_VOLUME_MODEL_H
#define BRDFBAKE_BRDF_SHEEN_VOLUME_MODEL_H

#include "brdfbake/brdf/params.h"
#include "brdfbake/brdf/sampling.h"

/* Parameter slots of the model (the spec's, not the kernel's: the walk takes the roughness r). */
#define BB_SHEEN_VOLUME_MODEL_ALPHA 0   /* alpha = r^2, the fibers' cross-section sigma, as sheen-ltc's */
#define BB_SHEEN_VOLUME_MODEL_BOUNCES 1 /* the walk's scattering limit */

BB_FN bb_real bb_sheen_volume_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    (void)p;
    (void)wo;
    (void)wi;
    return BB_R(0.0);
}

BB_FN bb_sample bb_sheen_volume_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    (void)p;
    (void)wo;
    (void)u1;
    (void)u2;
    return bb_make_sample(bb_v3(BB_R(0.0), BB_R(0.0), BB_R(1.0)), BB_R(0.0));
}

#endif /* BRDFBAKE_BRDF_SHEEN_VOLUME_MODEL_H */

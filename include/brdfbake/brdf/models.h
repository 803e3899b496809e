/* The BRDF models brdfbake knows (model_registry.h), and one dispatch for each operation,
 * generated from the registry's table.
 *
 * Each model lives in its own header as stateless functions (eval, sample). The dispatch
 * functions switch on a model id; the host calls them with any id, a kernel is built with
 * -D BB_MODEL=<id> and only that model's code is compiled in (BB_HAS_MODEL, BB_IF_COMPILED).
 * docs/models.md lists the steps of adding a model. */
#ifndef BRDFBAKE_BRDF_MODELS_H
#define BRDFBAKE_BRDF_MODELS_H

#include "brdfbake/brdf/model_registry.h"

#define BB_EVAL_CASE(NAME, name, SPEC, ARGS, ...) \
    BB_IF_COMPILED(NAME)(case BB_MODEL_##NAME: return bb_##name##_eval BB_PP_CAT(BB_EVAL_ARGS_, ARGS);)
#define BB_SAMPLE_CASE(NAME, name, SPEC, ARGS, ...) \
    BB_IF_COMPILED(NAME)(case BB_MODEL_##NAME: return bb_##name##_sample BB_PP_CAT(BB_SAMPLE_ARGS_, ARGS);)

/* f(wo, wi) without the cosine. */
BB_FN bb_real bb_model_eval(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    switch (model) {
        BB_MODEL_REGISTRY(BB_EVAL_CASE)
    default:
        return BB_R(0.0);
    }
}

/* The model's importance sample for wo and the uniform pair (u1, u2). */
BB_FN bb_sample bb_model_sample(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1,
                                bb_real u2) {
    switch (model) {
        BB_MODEL_REGISTRY(BB_SAMPLE_CASE)
    default:
        return bb_make_sample(bb_v3(BB_R(0.0), BB_R(0.0), BB_R(1.0)), BB_R(0.0));
    }
}

#if BB_HAS_MODEL(BB_MODEL_GGX)
/* The vector path's estimator, in two halves: the constants of a cell, once per cell, and the
 * weight of one disk point d with h = sqrt(1 - d.x^2), both tabulated by the host (GGX's closed
 * form, ggx.h). Only GGX's sample is a function of the disk point (bb_model_samples_disk).
 * isotropic: a constant, 1 when every cell of the launch is isotropic (-D BB_ISOTROPIC). */
typedef bb_ggx_disk_cell bb_disk_cell;

#ifndef BB_VECTOR_WIDTH
/* Whether the disk path may treat a cell as isotropic (then wo is rotated into the x-z plane and
 * the terms that vanish are dropped): the host asks for every cell of a launch. */
BB_FN int bb_model_disk_isotropic(int model, bb_params p) {
    return model == BB_MODEL_GGX && p.v[BB_GGX_ALPHA_X] == p.v[BB_GGX_ALPHA_Y];
}
#endif

BB_FN bb_disk_cell bb_model_disk_cell(int model, bb_params p, bb_vec3 wo, int isotropic) {
    (void)model;
    return bb_ggx_disk_cell_make(p, wo, isotropic);
}

BB_FN bb_real bb_model_disk_weight(int model, bb_disk_cell c, int fkind, bb_params fp, bb_vec2 d, bb_real h, int isotropic) {
    (void)model;
    return bb_ggx_disk_weight(c, fkind, fp, d, h, isotropic);
}
#endif

#endif /* BRDFBAKE_BRDF_MODELS_H */

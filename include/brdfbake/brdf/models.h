/* The BRDF models brdfbake knows, and one dispatch for each operation.
 *
 * Each model lives in its own header as stateless functions (eval, sample). The dispatch
 * functions switch on a model id; the host calls them with any id, a kernel is built with
 * -D BB_MODEL=<id> and only that model's code is compiled in (BB_HAS_MODEL).
 *
 * Adding a model: write its header, give it an id below, add a case to each dispatch function,
 * and register its spec (name, keys, ranges) in host/model_spec.cpp. */
#ifndef BRDFBAKE_BRDF_MODELS_H
#define BRDFBAKE_BRDF_MODELS_H

#include "brdfbake/brdf/fresnel.h"

#define BB_MODEL_LAMBERT 1
#define BB_MODEL_GGX 2

#if defined(__OPENCL_C_VERSION__) && defined(BB_MODEL)
#define BB_HAS_MODEL(id) ((id) == BB_MODEL)
#else
#define BB_HAS_MODEL(id) 1
#endif

#if BB_HAS_MODEL(BB_MODEL_LAMBERT)
#include "brdfbake/brdf/lambert.h"
#endif
#if BB_HAS_MODEL(BB_MODEL_GGX)
#include "brdfbake/brdf/ggx.h"
#endif

/* f(wo, wi) without the cosine. */
BB_FN real bb_model_eval(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    switch (model) {
#if BB_HAS_MODEL(BB_MODEL_LAMBERT)
    case BB_MODEL_LAMBERT:
        return bb_lambert_eval(p, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_GGX)
    case BB_MODEL_GGX:
        return bb_ggx_eval(p, fkind, fp, wo, wi);
#endif
    default:
        return BB_R(0.0);
    }
}

/* The model's importance sample for wo and the uniform pair (u1, u2). */
BB_FN bb_sample bb_model_sample(int model, bb_params p, int fkind, bb_params fp, bb_vec3 wo, real u1,
                                real u2) {
    switch (model) {
#if BB_HAS_MODEL(BB_MODEL_LAMBERT)
    case BB_MODEL_LAMBERT:
        return bb_lambert_sample(p, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_GGX)
    case BB_MODEL_GGX:
        return bb_ggx_sample(p, fkind, fp, wo, u1, u2);
#endif
    default:
        return bb_make_sample(bb_v3(BB_R(0.0), BB_R(0.0), BB_R(1.0)), BB_R(0.0));
    }
}

#endif /* BRDFBAKE_BRDF_MODELS_H */

/* The BRDF models brdfbake knows, and one dispatch for each operation.
 *
 * Each model lives in its own header as stateless functions (eval, sample). The dispatch
 * functions switch on a model id; the host calls them with any id, a kernel is built with
 * -D BB_MODEL=<id> and only that model's code is compiled in (BB_HAS_MODEL).
 *
 * Adding a model (docs/models.md has the full checklist): write its header, give it an id
 * below, include the header under BB_HAS_MODEL, add a case to each dispatch function, and
 * register its spec (name, keys, ranges, defaults) in host/spec.cpp. */
#ifndef BRDFBAKE_BRDF_MODELS_H
#define BRDFBAKE_BRDF_MODELS_H

#include "brdfbake/brdf/fresnel.h"

#define BB_MODEL_LAMBERT 1
#define BB_MODEL_GGX 2
#define BB_MODEL_OREN_NAYAR 3
#define BB_MODEL_PHONG 4
#define BB_MODEL_PHONG_ORIGINAL 5
#define BB_MODEL_BLINN_PHONG 6
#define BB_MODEL_TORRANCE_SPARROW 7
#define BB_MODEL_BECKMANN 8
#define BB_MODEL_MIRROR 9
#define BB_MODEL_DIELECTRIC_SPECULAR 10

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
#if BB_HAS_MODEL(BB_MODEL_OREN_NAYAR)
#include "brdfbake/brdf/oren_nayar.h"
#endif
#if BB_HAS_MODEL(BB_MODEL_PHONG) || BB_HAS_MODEL(BB_MODEL_PHONG_ORIGINAL)
#include "brdfbake/brdf/phong.h"
#endif
#if BB_HAS_MODEL(BB_MODEL_BLINN_PHONG)
#include "brdfbake/brdf/blinn_phong.h"
#endif
#if BB_HAS_MODEL(BB_MODEL_TORRANCE_SPARROW)
#include "brdfbake/brdf/torrance_sparrow.h"
#endif
#if BB_HAS_MODEL(BB_MODEL_BECKMANN)
#include "brdfbake/brdf/beckmann.h"
#endif
#if BB_HAS_MODEL(BB_MODEL_MIRROR) || BB_HAS_MODEL(BB_MODEL_DIELECTRIC_SPECULAR)
#include "brdfbake/brdf/specular.h"
#endif

/* True for the delta lobes (mirror, dielectric-specular): eval is 0, the albedo is analytic. */
BB_FN int bb_model_is_delta(int model) {
    return model == BB_MODEL_MIRROR || model == BB_MODEL_DIELECTRIC_SPECULAR;
}

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
#if BB_HAS_MODEL(BB_MODEL_OREN_NAYAR)
    case BB_MODEL_OREN_NAYAR:
        return bb_oren_nayar_eval(p, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_PHONG)
    case BB_MODEL_PHONG:
        return bb_phong_eval(p, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_PHONG_ORIGINAL)
    case BB_MODEL_PHONG_ORIGINAL:
        return bb_phong_original_eval(p, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_BLINN_PHONG)
    case BB_MODEL_BLINN_PHONG:
        return bb_blinn_phong_eval(p, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_TORRANCE_SPARROW)
    case BB_MODEL_TORRANCE_SPARROW:
        return bb_torrance_sparrow_eval(p, fkind, fp, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_BECKMANN)
    case BB_MODEL_BECKMANN:
        return bb_beckmann_eval(p, fkind, fp, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_MIRROR)
    case BB_MODEL_MIRROR:
        return bb_mirror_eval(p, fkind, fp, wo, wi);
#endif
#if BB_HAS_MODEL(BB_MODEL_DIELECTRIC_SPECULAR)
    case BB_MODEL_DIELECTRIC_SPECULAR:
        return bb_dielectric_specular_eval(p, wo, wi);
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
#if BB_HAS_MODEL(BB_MODEL_OREN_NAYAR)
    case BB_MODEL_OREN_NAYAR:
        return bb_oren_nayar_sample(p, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_PHONG)
    case BB_MODEL_PHONG:
        return bb_phong_sample(p, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_PHONG_ORIGINAL)
    case BB_MODEL_PHONG_ORIGINAL:
        return bb_phong_original_sample(p, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_BLINN_PHONG)
    case BB_MODEL_BLINN_PHONG:
        return bb_blinn_phong_sample(p, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_TORRANCE_SPARROW)
    case BB_MODEL_TORRANCE_SPARROW:
        return bb_torrance_sparrow_sample(p, fkind, fp, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_BECKMANN)
    case BB_MODEL_BECKMANN:
        return bb_beckmann_sample(p, fkind, fp, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_MIRROR)
    case BB_MODEL_MIRROR:
        return bb_mirror_sample(p, fkind, fp, wo, u1, u2);
#endif
#if BB_HAS_MODEL(BB_MODEL_DIELECTRIC_SPECULAR)
    case BB_MODEL_DIELECTRIC_SPECULAR:
        return bb_dielectric_specular_sample(p, wo, u1, u2);
#endif
    default:
        return bb_make_sample(bb_v3(BB_R(0.0), BB_R(0.0), BB_R(1.0)), BB_R(0.0));
    }
}

/* Models whose importance sample is a function of the disk point bb_disk_polar(u1, u2) alone
 * (no other use of u1, u2), so that a kernel can tabulate that point once for all cells: the
 * vector path of kernels/albedo.cl. The host asks before choosing that path. */
BB_FN int bb_model_samples_disk(int model) { return model == BB_MODEL_GGX; }

/* Models whose importance sampler (bb_model_sample) is branch-free, so that the generic vector
 * path of kernels/albedo.cl (albedo_replicas_points, -D BB_VECTOR_POINTS) evaluates it on W
 * lanes; the others run the scalar kernel. tests/test_albedo_vector.cpp holds each to the scalar
 * kernel's answer. */
BB_FN int bb_model_samples_vector(int model) {
    return model == BB_MODEL_BECKMANN || model == BB_MODEL_LAMBERT || model == BB_MODEL_OREN_NAYAR ||
           model == BB_MODEL_PHONG || model == BB_MODEL_PHONG_ORIGINAL || model == BB_MODEL_BLINN_PHONG ||
           model == BB_MODEL_TORRANCE_SPARROW;
}

/* Models whose evaluation (bb_model_eval) is branch-free, so that the qmc method's uniform
 * hemisphere weights run on W lanes too (-D BB_VECTOR_UNIFORM); tests/test_albedo_vector.cpp. */
BB_FN int bb_model_evals_vector(int model) {
    return model == BB_MODEL_GGX || bb_model_samples_vector(model);
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

BB_FN real bb_model_disk_weight(int model, bb_disk_cell c, int fkind, bb_params fp, bb_vec2 d, real h, int isotropic) {
    (void)model;
    return bb_ggx_disk_weight(c, fkind, fp, d, h, isotropic);
}
#endif

#endif /* BRDFBAKE_BRDF_MODELS_H */

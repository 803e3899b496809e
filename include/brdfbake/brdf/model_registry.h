/* The registry of BRDF models: one entry per model, shared by host and kernels.
 *
 * A model is its header (stateless eval and sample functions, parameter slots) and its entry
 * here: an id, the include of its header under BB_HAS_MODEL, and one row of
 * BB_MODEL_REGISTRY. Every dispatch on a model id (models.h, integrands.h) and every trait
 * query of the host (ModelTraits in brdfbake/spec.h) is generated from the table, so that a
 * model's traits live in this one place. The host resolves a spec with the function
 * resolve_<name> registered beside the others in host/models/spec.cpp (keys, ranges, defaults).
 *
 * A kernel is built with -D BB_MODEL=<id> and compiles only that model's header; the host sees
 * every model. */
#ifndef BRDFBAKE_BRDF_MODEL_REGISTRY_H
#define BRDFBAKE_BRDF_MODEL_REGISTRY_H

#include "brdfbake/brdf/fresnel.h"

#if defined(__OPENCL_C_VERSION__) && defined(BB_MODEL)
#define BB_HAS_MODEL(id) ((id) == BB_MODEL)
#else
#define BB_HAS_MODEL(id) 1
#endif

/* ------------------------------------------------------------------ the models' headers
 * Each block gives the model's id, includes its header where the model is compiled, and marks
 * it compiled (BB_COMPILED_<NAME>, read by BB_IF_COMPILED below). */

#define BB_MODEL_LAMBERT 1
#if BB_HAS_MODEL(BB_MODEL_LAMBERT)
#include "brdfbake/brdf/lambert.h"
#define BB_COMPILED_LAMBERT ~, 1
#endif

#define BB_MODEL_GGX 2
#if BB_HAS_MODEL(BB_MODEL_GGX)
#include "brdfbake/brdf/ggx.h"
#define BB_COMPILED_GGX ~, 1
#endif

#define BB_MODEL_OREN_NAYAR 3
#if BB_HAS_MODEL(BB_MODEL_OREN_NAYAR)
#include "brdfbake/brdf/oren_nayar.h"
#define BB_COMPILED_OREN_NAYAR ~, 1
#endif

#define BB_MODEL_PHONG 4
#if BB_HAS_MODEL(BB_MODEL_PHONG)
#include "brdfbake/brdf/phong.h"
#define BB_COMPILED_PHONG ~, 1
#endif

#define BB_MODEL_PHONG_ORIGINAL 5
#if BB_HAS_MODEL(BB_MODEL_PHONG_ORIGINAL)
#include "brdfbake/brdf/phong.h"
#define BB_COMPILED_PHONG_ORIGINAL ~, 1
#endif

#define BB_MODEL_BLINN_PHONG 6
#if BB_HAS_MODEL(BB_MODEL_BLINN_PHONG)
#include "brdfbake/brdf/blinn_phong.h"
#define BB_COMPILED_BLINN_PHONG ~, 1
#endif

#define BB_MODEL_TORRANCE_SPARROW 7
#if BB_HAS_MODEL(BB_MODEL_TORRANCE_SPARROW)
#include "brdfbake/brdf/torrance_sparrow.h"
#define BB_COMPILED_TORRANCE_SPARROW ~, 1
#endif

#define BB_MODEL_BECKMANN 8
#if BB_HAS_MODEL(BB_MODEL_BECKMANN)
#include "brdfbake/brdf/beckmann.h"
#define BB_COMPILED_BECKMANN ~, 1
#endif

#define BB_MODEL_MIRROR 9
#if BB_HAS_MODEL(BB_MODEL_MIRROR)
#include "brdfbake/brdf/specular.h"
#define BB_COMPILED_MIRROR ~, 1
#endif

#define BB_MODEL_DIELECTRIC_SPECULAR 10
#if BB_HAS_MODEL(BB_MODEL_DIELECTRIC_SPECULAR)
#include "brdfbake/brdf/specular.h"
#define BB_COMPILED_DIELECTRIC_SPECULAR ~, 1
#endif

#define BB_MODEL_SHEEN 11
#if BB_HAS_MODEL(BB_MODEL_SHEEN)
#include "brdfbake/brdf/sheen.h"
#define BB_COMPILED_SHEEN ~, 1
#endif

#define BB_MODEL_MERL 12
#if BB_HAS_MODEL(BB_MODEL_MERL)
#include "brdfbake/brdf/merl.h"
#define BB_COMPILED_MERL ~, 1
#endif

#define BB_MODEL_SHEEN_LTC 13
#if BB_HAS_MODEL(BB_MODEL_SHEEN_LTC)
#include "brdfbake/brdf/sheen_ltc.h"
#define BB_COMPILED_SHEEN_LTC ~, 1
#endif

#define BB_MODEL_SHEEN_VOLUME 14
#if BB_HAS_MODEL(BB_MODEL_SHEEN_VOLUME)
#include "brdfbake/brdf/sheen_volume_model.h"
#define BB_COMPILED_SHEEN_VOLUME ~, 1
#endif

/* ---------------------------------------------------------------------------- the table
 * X(NAME, name, SPEC, ARGS, QUAD, TRAITS, ALPHA_X, ALPHA_Y, EXPONENT, EXAMPLE), one row per model:
 *   NAME, name  its id is BB_MODEL_<NAME>; its functions are bb_<name>_eval and
 *               bb_<name>_sample, and for QUAD = HALFVECTOR bb_<name>_quad_dist and
 *               bb_<name>_halfvector_weight (integrands.h); its host resolver resolve_<name>.
 *   SPEC        the spec name (`--model SPEC:key=value,...`).
 *   ARGS        FRESNEL: the model multiplies by the Fresnel term of --fresnel, and its functions
 *               take (p, fkind, fp, ...); PLAIN: they take (p, ...).
 *   QUAD        the space of its albedo quadrature: SAMPLER (the model's importance warp on
 *               the unit square) or HALFVECTOR (half-vector space, integrands.h).
 *   TRAITS      the BB_TRAIT_* flags below that hold for the model, or'ed (0: none).
 *   ALPHA_X, ALPHA_Y  the parameter slots a roughness axis sweeps (-1: no roughness axis).
 *   EXPONENT    the slot of a cosine-power exponent N whose lobe lies about the mirror
 *               direction (width sqrt(2/(N+2))) when QUAD = SAMPLER; -1 otherwise.
 *   EXAMPLE     a spec of the model for the generic tests. */

/* The TRAITS flags. */
#define BB_TRAIT_COSINE_SAMPLER 0x001 /* its sampler is the cosine warp (sin^2 theta_i = u1), which
                                       * the sampler-space rule runs in cos(theta_i) instead */
#define BB_TRAIT_DELTA 0x002          /* a delta lobe (eval is 0, the albedo is analytic;
                                       * host/integrate/analytic.cpp) */
#define BB_TRAIT_SAMPLES_DISK 0x004   /* its sample is a function of the disk point bb_disk_polar(u1,
                                       * u2) alone and it has the closed-form disk weight of the
                                       * vector path (albedo_replicas_disk) */
#define BB_TRAIT_SAMPLES_VECTOR 0x008 /* its sampler is branch-free (albedo_replicas_points) */
#define BB_TRAIT_EVALS_VECTOR 0x010   /* its evaluation is branch-free (qmc on the vector path) */
#define BB_TRAIT_RECIPROCAL 0x020     /* f(wo, wi) = f(wi, wo) (tests/test_model_battery.cpp) */
#define BB_TRAIT_KINKED 0x040         /* the quadrature's integrand has a kink everywhere (the
                                       * V-groove min()), so its error estimate never assumes
                                       * geometric convergence (host/integrate/quadrature_rules.cpp) */
#define BB_TRAIT_FURNACE 0x080        /* EXAMPLE conserves energy, albedo <= 1 (the white furnace
                                       * test claims it) */
#define BB_TRAIT_STOCHASTIC 0x100     /* its value is itself an estimate (a random-walk simulation):
                                       * only the sampling methods integrate it, never quadrature
                                       * (docs/architecture.md, "The seam for new models") */
#define BB_TRAIT_MEASURED 0x200       /* its values are a measured table (model data): no roughness
                                       * axis, its tables are E(mu_o) and Eavg of the data alone */
#define BB_TRAIT_MIRROR_CONE 0x400    /* the integrand has a cone (a kink of the derivative) at the
                                       * mirror direction, such as sheen's sin^(1/alpha)(theta_h):
                                       * the sampler-space rule splits u1 where the sampler's
                                       * cos(theta_i) equals cos(theta_o) (integrands.h,
                                       * bb_quad_sampler_cone_u1); the sampler's cos(theta_i) must
                                       * rise with u1 and not depend on u2 */

#define BB_TRAIT_DIFFUSE_KEY 0x800   /* its spec takes diffuse=KD, a Lambert base kd/pi beside the
                                       * lobe (brdf/smith.h, bb_smith_diffuse): compute_albedo adds
                                       * its albedo kd in closed form (host/integrate/albedo.cpp) */
#define BB_TRAIT_LAYER_WALK 0x1000    /* a walk through a volumetric layer with no pointwise f (no
                                       * next-event estimate): albedo, check and lut albedo by the
                                       * layer's walks, lobe by a histogram of exit directions
                                       * (host/integrate/sheen_volume.h); evaluate refused */

#define BB_MODEL_REGISTRY(X)                                                                                      \
    /* NAME                 name                 SPEC                   ARGS     QUAD        */                   \
    X(LAMBERT,              lambert,             "lambert",             PLAIN,   SAMPLER,                         \
      BB_TRAIT_COSINE_SAMPLER | BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL |           \
          BB_TRAIT_FURNACE,                                                                                       \
      -1, -1, -1, "lambert:rho=1")                                                                                \
    X(GGX,                  ggx,                 "ggx",                 FRESNEL, HALFVECTOR,                      \
      BB_TRAIT_SAMPLES_DISK | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE |                    \
          BB_TRAIT_DIFFUSE_KEY,                                                                                   \
      BB_GGX_ALPHA_X, BB_GGX_ALPHA_Y, -1, "ggx:alpha=0.3")                                                        \
    X(BECKMANN,             beckmann,            "beckmann",            FRESNEL, HALFVECTOR,                      \
      BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE |                  \
          BB_TRAIT_DIFFUSE_KEY,                                                                                   \
      BB_BECKMANN_ALPHA_X, BB_BECKMANN_ALPHA_Y, -1, "beckmann:alpha=0.3")                                         \
    X(OREN_NAYAR,           oren_nayar,          "oren-nayar",          PLAIN,   SAMPLER,                         \
      BB_TRAIT_COSINE_SAMPLER | BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL |           \
          BB_TRAIT_FURNACE,                                                                                       \
      -1, -1, -1, "oren-nayar:sigma=0.5")                                                                         \
    X(PHONG,                phong,               "phong",               PLAIN,   SAMPLER,                         \
      BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE,                   \
      -1, -1, BB_PHONG_N, "phong:n=20,normalized=1")                                                              \
    X(PHONG_ORIGINAL,       phong_original,      "phong-original",      PLAIN,   SAMPLER,                         \
      BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_FURNACE,                                         \
      -1, -1, BB_PHONG_N, "phong-original:n=20")                                                                  \
    X(BLINN_PHONG,          blinn_phong,         "blinn-phong",         PLAIN,   HALFVECTOR,                      \
      BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE,                   \
      -1, -1, -1, "blinn-phong:n=20,ks=0.25,normalized=1")                                                        \
    X(TORRANCE_SPARROW,     torrance_sparrow,    "torrance-sparrow",    FRESNEL, HALFVECTOR,                      \
      BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL | BB_TRAIT_KINKED | BB_TRAIT_FURNACE, \
      BB_TORRANCE_SPARROW_ALPHA_X, BB_TORRANCE_SPARROW_ALPHA_Y, -1, "torrance-sparrow:d=beckmann,alpha=0.3")      \
    X(MIRROR,               mirror,              "mirror",              FRESNEL, SAMPLER,                         \
      BB_TRAIT_DELTA | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE,                                                    \
      -1, -1, -1, "mirror")                                                                                       \
    X(DIELECTRIC_SPECULAR,  dielectric_specular, "dielectric-specular", PLAIN,   SAMPLER,                         \
      BB_TRAIT_DELTA | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE,                                                    \
      -1, -1, -1, "dielectric-specular:eta=1.5")                                                                  \
    X(SHEEN,                sheen,               "sheen",               PLAIN,   SAMPLER,                         \
      BB_TRAIT_SAMPLES_VECTOR | BB_TRAIT_EVALS_VECTOR | BB_TRAIT_RECIPROCAL | BB_TRAIT_FURNACE |                  \
          BB_TRAIT_MIRROR_CONE,                                                                                   \
      BB_SHEEN_ALPHA, BB_SHEEN_ALPHA, -1, "sheen:roughness=0.5")                                                 \
    X(MERL,                 merl,                "merl",                PLAIN,   SAMPLER,                         \
      BB_TRAIT_COSINE_SAMPLER | BB_TRAIT_RECIPROCAL | BB_TRAIT_KINKED | BB_TRAIT_FURNACE | BB_TRAIT_MEASURED,     \
      -1, -1, -1, "merl:file=builtin:lambert")                                                                   \
    X(SHEEN_LTC,            sheen_ltc,           "sheen-ltc",           PLAIN,   SAMPLER,                         \
      BB_TRAIT_FURNACE, BB_SHEEN_LTC_ALPHA, BB_SHEEN_LTC_ALPHA, -1, "sheen-ltc:roughness=0.5")                  \
    X(SHEEN_VOLUME,         sheen_volume,        "sheen-volume",        PLAIN,   SAMPLER,                         \
      BB_TRAIT_STOCHASTIC | BB_TRAIT_LAYER_WALK | BB_TRAIT_FURNACE, BB_SHEEN_VOLUME_MODEL_ALPHA,                 \
      BB_SHEEN_VOLUME_MODEL_ALPHA, -1, "sheen-volume:roughness=0.5")

/* The values of the QUAD column. */
#define BB_QUAD_SPACE_SAMPLER 0
#define BB_QUAD_SPACE_HALFVECTOR 1

/* --------------------------------------------------------------- generating from the table */

#define BB_PP_CAT(a, b) BB_PP_CAT_(a, b)
#define BB_PP_CAT_(a, b) a##b
#define BB_PP_SECOND(a, b, ...) b
#define BB_PP_KEEP_1(...) __VA_ARGS__
#define BB_PP_KEEP_0(...)

/* BB_IF_COMPILED(NAME)(code): the code where the model's header is compiled (every model on
 * the host, the kernel's one model), nothing elsewhere; a generated dispatch names only the
 * models it can call. A defined marker BB_COMPILED_<NAME> (`~, 1`) puts 1 in the second
 * argument of BB_PP_SECOND; an undefined one leaves its own name there and 0 second. */
#define BB_PP_IS_MARKED(...) BB_PP_SECOND(__VA_ARGS__, 0, 0)
#define BB_IF_COMPILED(NAME) BB_PP_CAT(BB_PP_KEEP_, BB_PP_IS_MARKED(BB_COMPILED_##NAME))

/* The arguments of a model's functions, by its ARGS column, and whether it takes the Fresnel term. */
#define BB_EVAL_ARGS_PLAIN (p, wo, wi)
#define BB_EVAL_ARGS_FRESNEL (p, fkind, fp, wo, wi)
#define BB_SAMPLE_ARGS_PLAIN (p, wo, u1, u2)
#define BB_SAMPLE_ARGS_FRESNEL (p, fkind, fp, wo, u1, u2)
#define BB_USES_FRESNEL_PLAIN 0
#define BB_USES_FRESNEL_FRESNEL 1

/* The case of one row for bb_model_has_trait: whether the row's TRAITS hold `flag`. */
#define BB_TRAIT_CASE(NAME, name, SPEC, ARGS, QUAD, TRAITS, ...) \
    case BB_MODEL_##NAME:                                     \
        return ((TRAITS) & flag) != 0;

/* Whether the model's TRAITS hold the BB_TRAIT_* flag (every case is compiled: no model function
 * is named). A kernel's model and flag are constants, so the query folds to one. */
BB_FN int bb_model_has_trait(int model, int flag) {
    switch (model) {
        BB_MODEL_REGISTRY(BB_TRAIT_CASE)
    default:
        return 0;
    }
}

/* True for the delta lobes (BB_TRAIT_DELTA): eval is 0, the albedo is analytic. */
BB_FN int bb_model_is_delta(int model) { return bb_model_has_trait(model, BB_TRAIT_DELTA); }

/* The model's sample is a function of the disk point bb_disk_polar(u1, u2) alone (BB_TRAIT_SAMPLES_DISK), so that
 * a kernel can tabulate that point once for all cells: the vector path albedo_replicas_disk. */
BB_FN int bb_model_samples_disk(int model) { return bb_model_has_trait(model, BB_TRAIT_SAMPLES_DISK); }

/* The model's sampler is branch-free (BB_TRAIT_SAMPLES_VECTOR): the generic vector path albedo_replicas_points
 * evaluates it on W lanes; tests/test_albedo_vector.cpp holds it to the scalar kernel. */
BB_FN int bb_model_samples_vector(int model) { return bb_model_has_trait(model, BB_TRAIT_SAMPLES_VECTOR); }

/* The model's evaluation is branch-free (BB_TRAIT_EVALS_VECTOR): qmc's uniform hemisphere weights on W lanes. */
BB_FN int bb_model_evals_vector(int model) { return bb_model_has_trait(model, BB_TRAIT_EVALS_VECTOR); }

/* The sampler is the cosine warp (BB_TRAIT_COSINE_SAMPLER): the sampler-space rule runs in cos(theta_i). */
BB_FN int bb_quad_sampler_is_cosine(int model) { return bb_model_has_trait(model, BB_TRAIT_COSINE_SAMPLER); }

#endif /* BRDFBAKE_BRDF_MODEL_REGISTRY_H */

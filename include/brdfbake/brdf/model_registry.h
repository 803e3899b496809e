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

/* ---------------------------------------------------------------------------- the table
 * X(NAME, name, SPEC, FRESNEL, QUAD, COSINE, DELTA, DISK, VSAMPLE, VEVAL, RECIPROCAL,
 *   ALPHA_X, ALPHA_Y, EXPONENT, KINKED, FURNACE, EXAMPLE), one row per model:
 *   NAME, name  its id is BB_MODEL_<NAME>; its functions are bb_<name>_eval and
 *               bb_<name>_sample, and for QUAD = HALFVECTOR bb_<name>_quad_dist and
 *               bb_<name>_halfvector_weight (integrands.h); its host resolver resolve_<name>.
 *   SPEC        the spec name (`--model SPEC:key=value,...`).
 *   FRESNEL     1: the model multiplies by the Fresnel term of --fresnel, and its functions
 *               take (p, fkind, fp, ...); 0: they take (p, ...).
 *   QUAD        the space of its albedo quadrature: SAMPLER (the model's importance warp on
 *               the unit square) or HALFVECTOR (half-vector space, integrands.h).
 *   COSINE      1: its sampler is the cosine warp (sin^2 theta_i = u1), which the sampler-space
 *               rule runs in cos(theta_i) instead (bb_quad_sampler_is_cosine).
 *   DELTA       1: a delta lobe (eval is 0, the albedo is analytic; host/integrate/analytic.cpp).
 *   DISK        1: its sample is a function of the disk point bb_disk_polar(u1, u2) alone and
 *               it has the closed-form disk weight of the vector path (albedo_replicas_disk).
 *   VSAMPLE     1: its sampler is branch-free (the generic vector path albedo_replicas_points).
 *   VEVAL       1: its evaluation is branch-free (qmc on the vector path, BB_VECTOR_UNIFORM).
 *   RECIPROCAL  1: f(wo, wi) = f(wi, wo) (tests/test_model_battery.cpp holds it to that).
 *   ALPHA_X, ALPHA_Y  the parameter slots a roughness axis sweeps (-1: no roughness axis).
 *   EXPONENT    the slot of a cosine-power exponent N whose lobe lies about the mirror
 *               direction (width sqrt(2/(N+2))) when QUAD = SAMPLER; -1 otherwise.
 *   KINKED      1: the quadrature's integrand has a kink everywhere (the V-groove min()), so its
 *               error estimate never assumes geometric convergence (host/integrate/albedo.cpp).
 *   FURNACE     1: EXAMPLE conserves energy, albedo <= 1 (the white furnace test claims it).
 *   EXAMPLE     a spec of the model for the generic tests. */
#define BB_MODEL_REGISTRY(X)                                                                                      \
    /* NAME                 name                 SPEC                   FR QUAD        CO DE DI VS VE RE */      \
    X(LAMBERT,              lambert,             "lambert",             0, SAMPLER,    1, 0, 0, 1, 1, 1,          \
      -1, -1, -1, 0, 1, "lambert:rho=1")                                                                          \
    X(GGX,                  ggx,                 "ggx",                 1, HALFVECTOR, 0, 0, 1, 0, 1, 1,          \
      BB_GGX_ALPHA_X, BB_GGX_ALPHA_Y, -1, 0, 1, "ggx:alpha=0.3")                                                  \
    X(BECKMANN,             beckmann,            "beckmann",            1, HALFVECTOR, 0, 0, 0, 1, 1, 1,          \
      BB_BECKMANN_ALPHA_X, BB_BECKMANN_ALPHA_Y, -1, 0, 1, "beckmann:alpha=0.3")                                   \
    X(OREN_NAYAR,           oren_nayar,          "oren-nayar",          0, SAMPLER,    1, 0, 0, 1, 1, 1,          \
      -1, -1, -1, 0, 1, "oren-nayar:sigma=0.5")                                                                   \
    X(PHONG,                phong,               "phong",               0, SAMPLER,    0, 0, 0, 1, 1, 1,          \
      -1, -1, BB_PHONG_N, 0, 1, "phong:n=20,normalized=1")                                                        \
    X(PHONG_ORIGINAL,       phong_original,      "phong-original",      0, SAMPLER,    0, 0, 0, 1, 1, 0,          \
      -1, -1, BB_PHONG_N, 0, 1, "phong-original:n=20")                                                            \
    X(BLINN_PHONG,          blinn_phong,         "blinn-phong",         0, HALFVECTOR, 0, 0, 0, 1, 1, 1,          \
      -1, -1, -1, 0, 1, "blinn-phong:n=20,ks=0.25,normalized=1")                                                  \
    X(TORRANCE_SPARROW,     torrance_sparrow,    "torrance-sparrow",    1, HALFVECTOR, 0, 0, 0, 1, 1, 1,          \
      BB_TORRANCE_SPARROW_ALPHA_X, BB_TORRANCE_SPARROW_ALPHA_Y, -1, 1, 1, "torrance-sparrow:d=beckmann,alpha=0.3") \
    X(MIRROR,               mirror,              "mirror",              1, SAMPLER,    0, 1, 0, 0, 0, 1,          \
      -1, -1, -1, 0, 1, "mirror")                                                                                 \
    X(DIELECTRIC_SPECULAR,  dielectric_specular, "dielectric-specular", 0, SAMPLER,    0, 1, 0, 0, 0, 1,          \
      -1, -1, -1, 0, 1, "dielectric-specular:eta=1.5")                                                    \
    X(SHEEN,                sheen,               "sheen",               0, SAMPLER,    0, 0, 0, 1, 1, 1,          \
      BB_SHEEN_ALPHA, BB_SHEEN_ALPHA, -1, 0, 1, "sheen:roughness=0.5")

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

/* The arguments of a model's functions, by its FRESNEL column. */
#define BB_EVAL_ARGS_0 (p, wo, wi)
#define BB_EVAL_ARGS_1 (p, fkind, fp, wo, wi)
#define BB_SAMPLE_ARGS_0 (p, wo, u1, u2)
#define BB_SAMPLE_ARGS_1 (p, fkind, fp, wo, u1, u2)

/* A trait query: `case BB_MODEL_<NAME>: return <column>;` for every model (no model function is
 * named, so every case is compiled). */
#define BB_MODEL_TRAIT_SWITCH(model, COLUMN_MACRO) \
    switch (model) {                               \
        BB_MODEL_REGISTRY(COLUMN_MACRO)            \
    default:                                       \
        return 0;                                  \
    }

/* The case of one row for the trait switch, its value the row's COLUMN: one generator per
 * column, each naming the columns up to its own. */
#define BB_TRAIT_CASE(NAME, value) \
    case BB_MODEL_##NAME:          \
        return value;
#define BB_TRAIT_CASE_COSINE(NAME, name, SPEC, FR, QUAD, CO, ...) BB_TRAIT_CASE(NAME, CO)
#define BB_TRAIT_CASE_DELTA(NAME, name, SPEC, FR, QUAD, CO, DE, ...) BB_TRAIT_CASE(NAME, DE)
#define BB_TRAIT_CASE_DISK(NAME, name, SPEC, FR, QUAD, CO, DE, DI, ...) BB_TRAIT_CASE(NAME, DI)
#define BB_TRAIT_CASE_VSAMPLE(NAME, name, SPEC, FR, QUAD, CO, DE, DI, VS, ...) BB_TRAIT_CASE(NAME, VS)
#define BB_TRAIT_CASE_VEVAL(NAME, name, SPEC, FR, QUAD, CO, DE, DI, VS, VE, ...) BB_TRAIT_CASE(NAME, VE)

/* True for the delta lobes (DELTA): eval is 0, the albedo is analytic. */
BB_FN int bb_model_is_delta(int model) { BB_MODEL_TRAIT_SWITCH(model, BB_TRAIT_CASE_DELTA) }

/* The model's sample is a function of the disk point bb_disk_polar(u1, u2) alone (DISK), so that
 * a kernel can tabulate that point once for all cells: the vector path albedo_replicas_disk. */
BB_FN int bb_model_samples_disk(int model) { BB_MODEL_TRAIT_SWITCH(model, BB_TRAIT_CASE_DISK) }

/* The model's sampler is branch-free (VSAMPLE): the generic vector path albedo_replicas_points
 * evaluates it on W lanes; tests/test_albedo_vector.cpp holds it to the scalar kernel. */
BB_FN int bb_model_samples_vector(int model) { BB_MODEL_TRAIT_SWITCH(model, BB_TRAIT_CASE_VSAMPLE) }

/* The model's evaluation is branch-free (VEVAL): qmc's uniform hemisphere weights on W lanes. */
BB_FN int bb_model_evals_vector(int model) { BB_MODEL_TRAIT_SWITCH(model, BB_TRAIT_CASE_VEVAL) }

/* The sampler is the cosine warp (COSINE): the sampler-space rule runs in cos(theta_i). */
BB_FN int bb_quad_sampler_is_cosine(int model) { BB_MODEL_TRAIT_SWITCH(model, BB_TRAIT_CASE_COSINE) }

#endif /* BRDFBAKE_BRDF_MODEL_REGISTRY_H */

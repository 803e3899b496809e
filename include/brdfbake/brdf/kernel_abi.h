/* The interface between the host and the kernels (the .cl files of kernels/): entry point names, argument
 * codes and buffer layouts, shared so that neither side holds a number the other must match by
 * convention. Compiled as C++ (the host) and OpenCL C (the kernels).
 *
 * Kernel entry points are written with these names (`__kernel void BB_ENTRY_...(...)`); the host
 * creates them with BB_ENTRY_NAME(BB_ENTRY_...), the same name as a string. */
#ifndef BRDFBAKE_BRDF_KERNEL_ABI_H
#define BRDFBAKE_BRDF_KERNEL_ABI_H

#include "brdfbake/brdf/params.h"

#define BB_ENTRY_NAME_(entry) #entry
#define BB_ENTRY_NAME(entry) BB_ENTRY_NAME_(entry)

/* Build options: the macros a kernel is compiled with (-D NAME=VALUE), their names as the host
 * writes them. Engine::build_options (host/engine/engine.cpp) decides every one from a
 * BuildRequest; the kernels test the bare names (#ifdef BB_QUADRATURE, BB_MODEL == ...). */
#define BB_OPTION_REAL_DOUBLE "BB_REAL_DOUBLE"       /* bb_real is double (else float) */
#define BB_OPTION_VECTOR_WIDTH "BB_VECTOR_WIDTH"     /* bb_real is a vector of that many lanes */
#define BB_OPTION_MODEL "BB_MODEL"                   /* the model compiled in (BB_MODEL_*) */
#define BB_OPTION_FRESNEL "BB_FRESNEL"               /* the Fresnel term compiled in (BB_FRESNEL_*) */
#define BB_OPTION_QUADRATURE "BB_QUADRATURE"         /* the quadrature entry points */
#define BB_OPTION_VECTOR_POINTS "BB_VECTOR_POINTS"   /* albedo_replicas_points */
#define BB_OPTION_VECTOR_UNIFORM "BB_VECTOR_UNIFORM" /* with it: qmc's uniform hemisphere weights */
#define BB_OPTION_ISOTROPIC "BB_ISOTROPIC"           /* the disk path of isotropic cells */
#define BB_OPTION_QUAD_SAMPLER_ROWS "BB_QUAD_SAMPLER_ROWS" /* albedo_quadrature_rows in the sampler's square */
#define BB_OPTION_PHILOX "BB_PHILOX"                 /* Random123's Philox for the mc method */

/* -------------------------------------------------------------- kernels/albedo.cl */

/* Sampling methods: the scalar entry point, all three methods. */
#define BB_ENTRY_ALBEDO_REPLICAS albedo_replicas
/* -D BB_VECTOR_WIDTH: importance sampling from the tabulated disk points (BB_DISK_STEP). */
#define BB_ENTRY_ALBEDO_REPLICAS_DISK albedo_replicas_disk
/* -D BB_VECTOR_WIDTH -D BB_VECTOR_POINTS: from the tabulated Hammersley points (BB_POINTS_STEP). */
#define BB_ENTRY_ALBEDO_REPLICAS_POINTS albedo_replicas_points
/* -D BB_QUADRATURE: the scalar rule, and with -D BB_VECTOR_WIDTH one row per lane. */
#define BB_ENTRY_ALBEDO_QUADRATURE albedo_quadrature
#define BB_ENTRY_ALBEDO_QUADRATURE_ROWS albedo_quadrature_rows
/* The rough dielectric by quadrature (kernels/dielectric.cl built with -D BB_QUADRATURE; output
 * layout in brdf/dielectric_quadrature.h): scalar, and one row of the rule per lane. */
#define BB_ENTRY_DIELECTRIC_QUADRATURE dielectric_quadrature
#define BB_ENTRY_DIELECTRIC_QUADRATURE_ROWS dielectric_quadrature_rows

/* The `method` argument of BB_ENTRY_ALBEDO_REPLICAS: the point source and the warp. */
#define BB_METHOD_IMPORTANCE 0 /* the model's sampler, randomised Hammersley points */
#define BB_METHOD_QMC 1        /* uniform hemisphere, randomised Hammersley points */
#define BB_METHOD_MC 2         /* uniform hemisphere, Philox4x32-10 (-D BB_PHILOX) */

/* Model and Fresnel parameters: BB_MAX_PARAMS values per cell (params.h), in the slots of the
 * model's header; the Fresnel term's BB_MAX_PARAMS once per launch.
 *
 * BB_MODEL_DATA_ARG: every entry point that evaluates a model (albedo.cl, scan.cl, eval.cl) takes,
 * right after the Fresnel parameters, `__global const bb_scalar* model_data`: the model's data
 * (a measured model's table, a fitted model's coefficients), uploaded once per launch in the
 * kernel's precision; the entry point puts it in bb_params.data. The closed forms read none: the
 * host passes BB_MODEL_DATA_DUMMY_SIZE numbers (docs/architecture.md, "The seam for new models");
 * merl reads its tables (brdf/merl.h). */
#define BB_MODEL_DATA_DUMMY_SIZE 1

/* The vector paths' point tables, values per step of W points: the disk points' x, y and
 * sqrt(1 - x^2) (albedo and dielectric), or the rotated Hammersley points' u1, u2. */
#define BB_DISK_VALUES 3
#define BB_POINTS_VALUES 2

/* The quadrature's output: per cell BB_QUAD_SLOTS sums, slot = rule * BB_QUAD_PIECES + piece,
 * rule 0 the fine rule (n nodes per axis), 1 the coarse (n/2), 2 the coarsest (n/4), piece
 * 2k + h the half h of quarter k of the azimuth (integrands.h). */
#define BB_QUAD_RULES 3
#define BB_QUAD_PIECES 8
#define BB_QUAD_SLOTS (BB_QUAD_RULES * BB_QUAD_PIECES)

/* ---------------------------------------------------------- kernels/dielectric.cl */

#define BB_ENTRY_DIELECTRIC_REPLICAS dielectric_replicas
#define BB_ENTRY_DIELECTRIC_REPLICAS_DISK dielectric_replicas_disk

/* ------------------------------------------------------------------ kernels/eval.cl */

#define BB_ENTRY_MODEL_EVAL model_eval
#define BB_ENTRY_MODEL_SAMPLE model_sample

/* ------------------------------------------------------------------ kernels/scan.cl */

#define BB_ENTRY_RECIPROCITY_SCAN reciprocity_scan

/* --------------------------------------------------------------- kernels/fresnel.cl */

#define BB_ENTRY_FRESNEL_CURVE fresnel_curve

/* ----------------------------------------------------------- kernels/random_walk.cl */

#define BB_ENTRY_WALK_ALBEDO walk_albedo /* one replica of walks per work-item (brdf/random_walk.h) */
#define BB_WALK_SUMS 5 /* per item: escaped above, its first order, cut-off, escaped below, its first order */
#define BB_ENTRY_WALK_EVAL walk_eval /* one replica of next-event walks per work-item: f(wo, wi) wi.z */
#define BB_WALK_EVAL_SUMS 2 /* per item: f(wo, wi) wi.z (every order up to the limit), its first order */

/* ---------------------------------------------------------- kernels/sheen_volume.cl */

#define BB_ENTRY_SHEEN_VOLUME sheen_volume /* one replica of sheen-layer walks per work-item */
#define BB_SHEEN_SUMS 5                     /* per item: R, R1, T, T0, cut-off shares */
#define BB_SHEEN_LOBE_THETA 16              /* the top exits' histogram: theta bins ... */
#define BB_SHEEN_LOBE_PHI 16                /* ... and |phi| bins */

/* ------------------------------------------------------------------- kernels/ltc.cl */

#define BB_ENTRY_LTC_LOBE_POINTS ltc_lobe_points /* the lobe's fixed sample points per texel */
#define BB_ENTRY_LTC_OBJECTIVE ltc_objective     /* integral of min(p, D) per candidate matrix */
#define BB_LTC_POINT_VALUES 5                    /* per point: wi.xyz, weight, 1/pdf */
#define BB_LTC_CANDIDATE_VALUES 10               /* per candidate: M^-1 row-major, |det M^-1| */
#define BB_ENTRY_LTC_DISTANCE ltc_distance       /* the reported distance on jittered grids */
#define BB_LTC_MATRIX_VALUES 19                  /* per texel: M, M^-1 row-major, |det M^-1| */

/* ------------------------------------------------------------------- kernels/fit.cl */

#define BB_ENTRY_MODEL_FIT_OBJECTIVE model_fit_objective /* weighted squared residuals per (candidate, block) */
#define BB_FIT_PAIR_VALUES 7                             /* per pair: wo.xyz, wi.xyz, weight */
#define BB_FIT_METRIC_CBRT 0 /* (f cos theta_i)^(1/3), Ngan et al. 2005 */
#define BB_FIT_METRIC_LOG 1  /* log(1 + f cos theta_i) */
#define BB_FIT_METRIC_L2 2   /* f cos theta_i */

#endif /* BRDFBAKE_BRDF_KERNEL_ABI_H */

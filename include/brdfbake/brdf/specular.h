/* The delta lobes: the ideal mirror (`mirror`) and the smooth dielectric interface
 * (`dielectric-specular:eta=E`), reflection plus specular transmission.
 *
 * A delta lobe has no finite value f(wo, wi): eval returns 0 for every pair (so the reciprocity
 * and non-finite scans see a reciprocal, non-negative 0), and its directional albedo is known in
 * closed form [PBR4 sec. 9.2-9.3]:
 *   mirror:               E(mu) = F(mu) for the chosen Fresnel term (F = 1 for --fresnel none);
 *   dielectric-specular:  reflection E_R(mu) = F_dielectric(mu, eta) (fresnel.h, exact,
 *                         unpolarised, 1 under total internal reflection), transmission
 *                         E_T(mu) = 1 - E_R(mu) of the energy; the transmitted radiance is
 *                         scaled by eta^2 (light entering the far side; 1/eta^2 leaving it),
 *                         because L/n^2 is invariant across the interface [PBR4 sec. 9.5.2].
 * The host reports these values directly (host/integrate/analytic.cpp); delta lobes are never integrated
 * by Monte Carlo. The sample functions return the one direction the lobe reflects into with the
 * exact weight E(mu), so that a kernel that does sample them (the albedo kernel, point sampling
 * for parity tests) gets the closed form too, with zero variance.
 *   [PBR4] Pharr, Jakob, Humphreys, "Physically Based Rendering", 4th ed., 2023. */
#ifndef BRDFBAKE_BRDF_SPECULAR_H
#define BRDFBAKE_BRDF_SPECULAR_H

#include "brdfbake/brdf/fresnel.h"

/* Parameter slots. */
#define BB_DIELECTRIC_SPECULAR_ETA 0

/* Reflection albedo of the mirror, F(mu). */
BB_FN bb_real bb_mirror_albedo(int fkind, bb_params fp, bb_real mu) {
    return bb_select(BB_R(0.0), bb_fresnel_eval(fkind, fp, bb_clamp_cos(mu)), mu > BB_R(0.0));
}

/* Reflection albedo of the smooth dielectric, F_dielectric(mu, eta). */
BB_FN bb_real bb_dielectric_specular_reflectance(bb_params p, bb_real mu) {
    return bb_select(BB_R(0.0), bb_fresnel_dielectric(bb_clamp_cos(mu), p.v[BB_DIELECTRIC_SPECULAR_ETA]),
                     mu > BB_R(0.0));
}

/* Transmitted energy fraction 1 - F_dielectric(mu, eta) (0 under total internal reflection). */
BB_FN bb_real bb_dielectric_specular_transmittance(bb_params p, bb_real mu) {
    return bb_select(BB_R(0.0), BB_R(1.0) - bb_fresnel_dielectric(bb_clamp_cos(mu), p.v[BB_DIELECTRIC_SPECULAR_ETA]),
                     mu > BB_R(0.0));
}

/* The unused arguments keep the signatures of every other model (models.h dispatch). */
BB_FN bb_real bb_mirror_eval(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_vec3 wi) {
    (void)p, (void)fkind, (void)fp, (void)wo, (void)wi;
    return BB_R(0.0); /* a delta lobe: no finite value */
}

BB_FN bb_sample bb_mirror_sample(bb_params p, int fkind, bb_params fp, bb_vec3 wo, bb_real u1, bb_real u2) {
    (void)p, (void)u1, (void)u2;
    return bb_make_sample(bb_v3(-wo.x, -wo.y, wo.z), bb_mirror_albedo(fkind, fp, wo.z));
}

BB_FN bb_real bb_dielectric_specular_eval(bb_params p, bb_vec3 wo, bb_vec3 wi) {
    (void)p, (void)wo, (void)wi;
    return BB_R(0.0);
}

BB_FN bb_sample bb_dielectric_specular_sample(bb_params p, bb_vec3 wo, bb_real u1, bb_real u2) {
    (void)u1, (void)u2;
    return bb_make_sample(bb_v3(-wo.x, -wo.y, wo.z), bb_dielectric_specular_reflectance(p, wo.z));
}

#endif /* BRDFBAKE_BRDF_SPECULAR_H */

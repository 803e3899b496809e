/* The Beckmann microfacet BRDF with Smith masking-shadowing (`beckmann`):
 *   f = D(wh) G2(wo, wi) F(wo.wh) / (4 cos_theta_o cos_theta_i)      [WMLT07 eq. 20]
 * with the Beckmann D, Lambda (erf form), G1 and G2 (separable or height-correlated) of
 * microfacet.h [WMLT07 eq. 25-27; H14 eq. 71-72, 98-99] or masking only (smith.h); isotropic or
 * anisotropic.
 * Edge cases: microfacet.h's policy. */
#ifndef BRDFBAKE_BRDF_BECKMANN_H
#define BRDFBAKE_BRDF_BECKMANN_H

#include "brdfbake/brdf/smith.h"

/* Parameter slots: those of every Smith lobe (smith.h). */
#define BB_BECKMANN_ALPHA_X BB_SMITH_ALPHA_X
#define BB_BECKMANN_ALPHA_Y BB_SMITH_ALPHA_Y
#define BB_BECKMANN_SHADOWING BB_SMITH_SHADOWING /* BB_SHADOWING_SEPARABLE, _CORRELATED or _MASKING */

/* The Smith lobe (smith.h) with the Beckmann distribution; visible normals [HD14, J14]. */
BB_SMITH_LOBE(beckmann, BB_SMITH_BECKMANN)

#endif /* BRDFBAKE_BRDF_BECKMANN_H */

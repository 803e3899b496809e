// Belcour and Barla 2017's spectral antialiasing of thin-film iridescence (issue 36, item 5): what
// real-time engines evaluate (glTF's KHR_materials_iridescence; the glTF Sample Viewer's
// iridescence.glsl), written here from the paper's equations to measure it against brute-force
// spectral integration of the exact Airy reflectance (brdf/thin_film.h; docs/fresnel.md).
//
// [BB17] L. Belcour, P. Barla, "A Practical Extension to Microfacet Theory for the Modeling of
//        Varying Iridescence", ACM TOG 36(4), 2017, sec. 4 and its supplemental material.
// Per polarisation, with R12 = |r12|^2, T121 = 1 - R12 (a transparent film), R23 = |r23|^2 and
// the phases phi21 = pi - arg r12, phi23 = arg r23, the Airy reflectance is a Fourier series in
// the round-trip phase Delta = 2 pi OPD / lambda, OPD = 2 eta_film d cos_film:
//   R = C0 + 2 sum_{m >= 1} C_m cos(m (Delta + phi21 + phi23)),
//   C0 = R12 + Rs,  Rs = T121^2 R23 / (1 - R12 R23),  C_m = (Rs - T121) (R12 R23)^(m/2).
// Integrated against a colour-matching function, each cosine becomes the function's Fourier
// transform at m OPD, which BB17 fit with Gaussians in frequency (the published constants
// below); the engines keep m <= 2 and convert XYZ (illuminant E, normalised by the integral of
// y-bar) to linear sRGB with the D65 matrix, then average s and p and clamp at 0.
#pragma once

#include <array>
#include <functional>

namespace brdfbake {

/// The series' terms of one polarisation: C0 and the ratio, C_m = c1 r^(m-1), and the phase.
struct AiryFourier {
    double c0 = 0.0, c1 = 0.0, ratio = 0.0, phase = 0.0;  // phase = phi21 + phi23
    double opd_nm = 0.0;                                   // 2 eta_film d cos_film
};

/// The s (0) and p (1) series of a transparent film (index film_eta, thickness d) on a substrate
/// (base_eta + i base_k) at one wavelength's indices, seen from air at cos_theta.
std::array<AiryFourier, 2> airy_fourier(double cos_theta, double film_eta, double thickness_nm, double base_eta,
                                        double base_k);

/// The series summed at wavelength lambda to `terms` (the exact Airy R as terms grows), s and p averaged.
double airy_series(const std::array<AiryFourier, 2>& f, double wavelength_nm, int terms);

/// BB17's colour in linear sRGB (the engines' form: m <= 2, Gaussian-fit sensitivities, XYZ under
/// illuminant E to sRGB by the D65 matrix, s and p averaged, clamped at 0), with the substrate's
/// index taken wavelength-independent (as the engines take it).
std::array<double, 3> bb17_iridescence_srgb(double cos_theta, double film_eta, double thickness_nm, double base_eta,
                                            double base_k);

/// The same colour convention by brute force: sum over 360-830 nm at 1 nm of x-bar, y-bar, z-bar
/// times R(lambda) (illuminant E, over the integral of y-bar), to linear sRGB by the D65 matrix.
std::array<double, 3> illuminant_e_srgb(const std::function<double(double)>& reflectance);

}  // namespace brdfbake

// Belcour and Barla 2017's spectral antialiasing (models/iridescence_bb17.h), from the paper's
// equations; the interface coefficients are brdf/thin_film.h's exact ones.
#include "models/iridescence_bb17.h"

#include <algorithm>
#include <cmath>

#include "brdfbake/brdf/fresnel.h"
#include "models/spectrum.h"

namespace brdfbake {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// One polarisation's series from its two complex interface coefficients.
AiryFourier fourier_of(bb_complex r12, bb_complex r23, double opd_nm) {
    AiryFourier f;
    const double R12 = bb_cx_abs2(r12), R23 = bb_cx_abs2(r23), T121 = 1.0 - R12;
    const double rs = T121 * T121 * R23 / (1.0 - R12 * R23);
    f.c0 = R12 + rs;
    f.ratio = std::sqrt(R12 * R23);
    f.c1 = (rs - T121) * f.ratio;
    f.phase = (kPi - std::atan2(r12.im, r12.re)) + std::atan2(r23.im, r23.re);
    f.opd_nm = opd_nm;
    return f;
}

/// BB17's Gaussian fit of the observer's sensitivities in frequency (their published constants):
/// the XYZ of cos(2 pi opd / lambda + shift), over the integral of y-bar (1.0685e-7 m).
std::array<double, 3> sensitivity(double opd_nm, double shift) {
    const double phase = 2.0 * kPi * opd_nm * 1e-9;
    const double val[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13};
    const double pos[3] = {1.6810e+06, 1.7953e+06, 2.2084e+06};
    const double var[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
    std::array<double, 3> xyz{};
    for (int i = 0; i < 3; ++i)
        xyz[size_t(i)] = val[i] * std::sqrt(2.0 * kPi * var[i]) * std::cos(pos[i] * phase + shift) * std::exp(-phase * phase * var[i]);
    xyz[0] += 9.7470e-14 * std::sqrt(2.0 * kPi * 4.5282e+09) * std::cos(2.2399e+06 * phase + shift) *
              std::exp(-4.5282e+09 * phase * phase);
    for (double& v : xyz) v /= 1.0685e-7;
    return xyz;
}

/// XYZ to linear sRGB by the standard D65 white (x 0.3127, y 0.3290), as the engines' matrix.
std::array<double, 3> to_srgb(const std::array<double, 3>& xyz) {
    static const auto m = xyz_to_linear_srgb({0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290});
    std::array<double, 3> rgb{};
    for (int i = 0; i < 3; ++i) rgb[size_t(i)] = m[size_t(i)][0] * xyz[0] + m[size_t(i)][1] * xyz[1] + m[size_t(i)][2] * xyz[2];
    return rgb;
}

}  // namespace

std::array<AiryFourier, 2> airy_fourier(double cos_theta, double film_eta, double thickness_nm, double base_eta,
                                        double base_k) {
    const double c = std::clamp(cos_theta, 0.0, 1.0), c2 = c * c;
    const bb_complex n0sq = bb_cx(1.0, 0.0), n1sq = bb_cx(film_eta * film_eta, 0.0);
    const bb_complex n2sq = bb_cx((base_eta - base_k) * (base_eta + base_k), 2.0 * base_eta * base_k);
    const bb_complex w0 = bb_cx(c, 0.0);
    const bb_complex w1 = bb_complex_sqrt_upper(film_eta * film_eta - 1.0 + c2, 0.0);
    const bb_complex w2 = bb_complex_sqrt_upper(n2sq.re - 1.0 + c2, n2sq.im);
    const double opd = 2.0 * thickness_nm * w1.re;  // 2 d eta_film cos_film = 2 d w_1
    return {fourier_of(bb_thin_film_rs(w0, w1), bb_thin_film_rs(w1, w2), opd),
            fourier_of(bb_thin_film_rp(n0sq, w0, n1sq, w1), bb_thin_film_rp(n1sq, w1, n2sq, w2), opd)};
}

double airy_series(const std::array<AiryFourier, 2>& f, double wavelength_nm, int terms) {
    double r = 0.0;
    for (const AiryFourier& q : f) {
        const double delta = 2.0 * kPi * q.opd_nm / wavelength_nm;
        double cm = q.c1, sum = q.c0;
        for (int m = 1; m <= terms; ++m, cm *= q.ratio) sum += 2.0 * cm * std::cos(m * (delta + q.phase));
        r += 0.5 * sum;
    }
    return r;
}

std::array<double, 3> bb17_iridescence_srgb(double cos_theta, double film_eta, double thickness_nm, double base_eta,
                                            double base_k) {
    const auto f = airy_fourier(cos_theta, film_eta, thickness_nm, base_eta, base_k);
    std::array<double, 3> rgb{};
    for (const AiryFourier& q : f) {
        // m = 0: the DC term, white in RGB (the engines add C0 to each channel).
        std::array<double, 3> xyz{};
        double cm = q.c1;
        for (int m = 1; m <= 2; ++m, cm *= q.ratio) {
            const auto s = sensitivity(m * q.opd_nm, m * q.phase);
            for (int i = 0; i < 3; ++i) xyz[size_t(i)] += 2.0 * cm * s[size_t(i)];
        }
        const auto c = to_srgb(xyz);
        for (int i = 0; i < 3; ++i) rgb[size_t(i)] += 0.5 * (q.c0 + c[size_t(i)]);
    }
    for (double& v : rgb) v = std::max(v, 0.0);
    return rgb;
}

std::array<double, 3> illuminant_e_srgb(const std::function<double(double)>& reflectance) {
    std::array<double, 3> xyz{};
    double y = 0.0;
    for (const auto& row : cie_observer()) {
        const double r = reflectance(row[0]);
        for (int i = 0; i < 3; ++i) xyz[size_t(i)] += row[size_t(i) + 1] * r;
        y += row[2];
    }
    for (double& v : xyz) v /= y;
    return to_srgb(xyz);
}

}  // namespace brdfbake

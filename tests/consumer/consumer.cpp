// The installed library's one-call API (brdfbake/api.h), used as any other project would:
//  - brdfbake::albedo: a Lambertian surface of rho = 1/2 seen at mu = 1/2, integrated by uniform
//    hemisphere sampling (qmc, not the sampler that returns rho exactly), must give the closed form
//    E = rho (Lambert 1760: f = rho / pi, whose cosine-weighted integral is rho at every mu) within
//    the error the library reports;
//  - brdfbake::lut: an albedo table of GGX at alpha 1e-3 to 2e-3 must hold E = 1 within 1e-2 in
//    every texel: a nearly smooth conductor without Fresnel reflects all the light it receives
//    (single scattering is lossless as alpha -> 0; Heitz 2014, the masking function -> 1).
// Exit status 0 when both hold, 1 when one does not.
#include <brdfbake/api.h>
#include <brdfbake/error.h>
#include <brdfbake/version.h>

#include <cmath>
#include <cstdio>

int main() {
    try {
        const double rho = 0.5, mu = 0.5;
        brdfbake::AlbedoOptions qmc;
        qmc.method = "qmc";
        qmc.samples = 1 << 14;
        const brdfbake::AlbedoValue v = brdfbake::albedo("lambert:rho=0.5", mu, qmc);
        const bool albedo_ok = std::fabs(v.value - rho) <= v.error && v.error < 1e-2;
        std::printf("brdfbake %s: albedo(\"lambert:rho=0.5\", %g) = %.9f +- %.2e, closed form %g: %s\n",
                    BRDFBAKE_VERSION, mu, v.value, v.error, rho, albedo_ok ? "agree" : "DISAGREE");

        brdfbake::LutOptions smooth;
        smooth.model = "ggx";
        smooth.size = {2, 2};
        smooth.alpha_range = std::make_pair(1e-3, 2e-3);
        smooth.samples = 4096;
        const brdfbake::Table t = brdfbake::lut("albedo", smooth);
        bool lut_ok = t.width() == 2 && t.height() == 2 && t.values.size() == 1 && t.values[0].size() == 4;
        for (double e : t.values.at(0)) lut_ok = lut_ok && std::fabs(e - 1.0) < 1e-2;
        std::printf("lut(\"albedo\", ggx, alpha 1e-3 to 2e-3): %dx%d, E from %.6f: %s\n", t.width(), t.height(),
                    t.values.at(0).at(0), lut_ok ? "1 as for a smooth surface" : "NOT 1");
        return albedo_ok && lut_ok ? 0 : 1;
    } catch (const brdfbake::Error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}

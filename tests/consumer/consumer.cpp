// One albedo through the installed library's public API: a Lambertian surface of rho = 1/2 seen
// at mu = 1/2, integrated by uniform hemisphere sampling (qmc), must give the closed form
// E = rho (Lambert 1760: f = rho / pi, whose cosine-weighted integral is rho at every mu)
// within the error the library reports. Exit status 0 when it does, 1 when it does not.
#include <brdfbake/albedo.h>
#include <brdfbake/error.h>
#include <brdfbake/spec.h>
#include <brdfbake/version.h>

#include <cmath>
#include <cstdio>

int main() {
    using namespace brdfbake;
    try {
        const double rho = 0.5, mu = 0.5;
        const ModelConfig model = resolve_model("lambert:rho=0.5");
        AlbedoRequest request;
        request.model = model.id;
        request.fresnel = resolve_fresnel("none");
        request.cells = cells_for({mu}, 0.0, model.params);
        request.method = Method::QuasiMonteCarlo;  // not the sampler that returns rho exactly
        request.samples = 1u << 14;
        Engine engine;
        const AlbedoValue v = compute_albedo(engine, request).values.at(0);
        const bool ok = std::fabs(v.value - rho) <= v.error && v.error < 1e-2;
        std::printf("brdfbake %s on %s: E(mu = %g) = %.9f +- %.2e, closed form %g: %s\n", BRDFBAKE_VERSION,
                    engine.device().name.c_str(), mu, v.value, v.error, rho, ok ? "agree" : "DISAGREE");
        return ok ? 0 : 1;
    } catch (const Error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}

#include "brdfbake/fresnel_curve.h"

#include <cmath>
#include <map>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/error.h"
#include "engine/device_buffer.h"
#include "models/key_reader.h"
#include "models/spectrum.h"

namespace brdfbake {

namespace {

/// F, Rs, Rp of `sets` Fresnel terms of kind `kind` (params: BB_MAX_PARAMS per set) at each
/// cosine, in one launch of the fresnel_curve kernel over cosines x sets: out[3 * (s * n + i)].
std::vector<double> fresnel_sets_on_device(Engine& engine, int kind, const std::vector<double>& params,
                                           Precision precision, const std::vector<double>& cosines) {
    for (double c : cosines)
        if (!(c >= 0.0 && c <= 1.0)) throw Error("cos(theta) must lie in [0, 1]; got " + format_number(c));
    const size_t n = cosines.size(), sets = params.size() / BB_MAX_PARAMS;
    if (n == 0 || sets == 0) return {};
    BuildRequest build;
    build.kernel_file = "fresnel.cl";
    build.precision = precision;
    build.fresnel = kind;
    cl::Program& program = engine.program(build);
    RealBuffers bufs(engine, precision);
    cl::Buffer b_cos = bufs.input(cosines);
    cl::Buffer b_p = bufs.input(params);
    cl::Buffer b_out = bufs.output(3 * n * sets);
    cl::Kernel kernel(program, BB_ENTRY_NAME(BB_ENTRY_FRESNEL_CURVE));
    kernel.setArg(0, b_cos);
    kernel.setArg(1, b_p);
    kernel.setArg(2, cl_uint(n));
    kernel.setArg(3, b_out);
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n, sets), cl::NullRange);
    std::vector<double> out = bufs.read(b_out, 3 * n * sets);
    for (size_t k = 0; k < out.size(); ++k)
        if (!std::isfinite(out[k]))
            throw Error("the Fresnel kernel produced a non-finite value at cos(theta) = " +
                        format_number(cosines[(k / 3) % n]) + "; refusing to report it");
    return out;
}

}  // namespace

FresnelCurves fresnel_on_device(Engine& engine, const FresnelConfig& f, Precision precision,
                                const std::vector<double>& cosines) {
    const std::vector<double> out = fresnel_sets_on_device(
        engine, f.kind, std::vector<double>(f.params.begin(), f.params.end()), precision, cosines);
    FresnelCurves curves;
    for (size_t i = 0; i < cosines.size(); ++i) {
        curves.f.push_back(out[3 * i]);
        curves.rs.push_back(out[3 * i + 1]);
        curves.rp.push_back(out[3 * i + 2]);
    }
    return curves;
}

FresnelColour fresnel_rgb_on_device(Engine& engine, const std::string& fresnel_spec, Precision precision,
                                    const std::vector<double>& cosines, const std::string& colour_space) {
    const SpectralWeights& fine = colour_weights(colour_space, 1);
    const SpectralWeights& coarse = colour_weights(colour_space, 2);
    FresnelColour c;
    c.rgb.assign(cosines.size(), {0.0, 0.0, 0.0});
    c.error.assign(cosines.size(), {0.0, 0.0, 0.0});
    c.wavelengths = int(fine.nm.size());
    if (cosines.empty()) return c;
    // The spec at every wavelength, grouped by kind (a measured term is one kind throughout; a
    // group per kind keeps an nk file whose k vanishes somewhere correct): one launch per kind.
    const auto at = fresnel_over_wavelengths(fresnel_spec);
    std::map<int, std::vector<size_t>> by_kind;  // kind -> indices into fine.nm
    std::map<int, std::vector<double>> params;
    for (size_t i = 0; i < fine.nm.size(); ++i) {
        const FresnelConfig f = at(fine.nm[i]);
        by_kind[f.kind].push_back(i);
        params[f.kind].insert(params[f.kind].end(), f.params.begin(), f.params.end());
    }
    std::vector<std::array<double, 3>> coarse_rgb(cosines.size(), {0.0, 0.0, 0.0});
    const size_t n = cosines.size();
    for (const auto& [kind, indices] : by_kind) {
        const std::vector<double> out = fresnel_sets_on_device(engine, kind, params[kind], precision, cosines);
        ++c.launches;
        for (size_t s = 0; s < indices.size(); ++s) {
            const size_t i = indices[s];
            // The coarse grid holds every second wavelength of the fine one: 380, 382, ...
            const bool on_coarse = i % 2 == 0;
            const size_t k = i / 2;
            if (on_coarse && coarse.nm[k] != fine.nm[i]) throw Error("internal error: the 2 nm grid is not every second 1 nm wavelength");
            for (size_t j = 0; j < n; ++j) {
                const double f = out[3 * (s * n + j)];
                for (int ch = 0; ch < 3; ++ch) {
                    c.rgb[j][ch] += fine.rgb[i][ch] * f;
                    if (on_coarse) coarse_rgb[j][ch] += coarse.rgb[k][ch] * f;
                }
            }
        }
    }
    for (size_t j = 0; j < n; ++j)
        for (int ch = 0; ch < 3; ++ch) c.error[j][ch] = std::fabs(c.rgb[j][ch] - coarse_rgb[j][ch]);
    return c;
}

}  // namespace brdfbake

#include "brdfbake/fresnel_curve.h"

#include <cmath>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/error.h"
#include "engine/device_buffer.h"
#include "models/key_reader.h"
#include "models/spectrum.h"

namespace brdfbake {

FresnelCurves fresnel_on_device(Engine& engine, const FresnelConfig& f, Precision precision,
                                const std::vector<double>& cosines) {
    for (double c : cosines)
        if (!(c >= 0.0 && c <= 1.0)) throw Error("cos(theta) must lie in [0, 1]; got " + format_number(c));
    FresnelCurves curves;
    if (cosines.empty()) return curves;
    BuildRequest build;
    build.kernel_file = "fresnel.cl";
    build.precision = precision;
    build.fresnel = f.kind;
    cl::Program& program = engine.program(build);
    RealBuffers bufs(engine, precision);
    const size_t n = cosines.size();
    cl::Buffer b_cos = bufs.input(cosines);
    cl::Buffer b_p = bufs.input(std::vector<double>(f.params.begin(), f.params.end()));
    cl::Buffer b_out = bufs.output(3 * n);
    cl::Kernel kernel(program, BB_ENTRY_NAME(BB_ENTRY_FRESNEL_CURVE));
    kernel.setArg(0, b_cos);
    kernel.setArg(1, b_p);
    kernel.setArg(2, cl_uint(n));
    kernel.setArg(3, b_out);
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n), cl::NullRange);
    const std::vector<double> out = bufs.read(b_out, 3 * n);
    for (size_t i = 0; i < n; ++i) {
        for (int j = 0; j < 3; ++j)
            if (!std::isfinite(out[3 * i + j]))
                throw Error("the Fresnel kernel produced a non-finite value at cos(theta) = " +
                            format_number(cosines[i]) + "; refusing to report it");
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
    std::vector<std::array<double, 3>> coarse_rgb(cosines.size(), {0.0, 0.0, 0.0});
    const auto at = fresnel_over_wavelengths(fresnel_spec);
    size_t k = 0;  // the coarse grid's index: every second wavelength of the fine one
    for (size_t i = 0; i < fine.nm.size(); ++i) {
        const FresnelCurves f = fresnel_on_device(engine, at(fine.nm[i]), precision, cosines);
        ++c.wavelengths;
        const bool on_coarse = k < coarse.nm.size() && coarse.nm[k] == fine.nm[i];
        for (size_t j = 0; j < cosines.size(); ++j)
            for (int ch = 0; ch < 3; ++ch) {
                c.rgb[j][ch] += fine.rgb[i][ch] * f.f[j];
                if (on_coarse) coarse_rgb[j][ch] += coarse.rgb[k][ch] * f.f[j];
            }
        k += on_coarse;
    }
    c.error.assign(cosines.size(), {0.0, 0.0, 0.0});
    for (size_t j = 0; j < cosines.size(); ++j)
        for (int ch = 0; ch < 3; ++ch) c.error[j][ch] = std::fabs(c.rgb[j][ch] - coarse_rgb[j][ch]);
    return c;
}

}  // namespace brdfbake

#include "brdfbake/fresnel_curve.h"

#include <cmath>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/error.h"
#include "engine/device_buffer.h"
#include "models/key_reader.h"

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

}  // namespace brdfbake

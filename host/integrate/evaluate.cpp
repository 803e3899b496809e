#include "brdfbake/evaluate.h"

#include "brdfbake/error.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "engine/device_buffer.h"

namespace brdfbake {
namespace {

template <size_t N>
std::vector<double> flatten(const std::vector<std::array<double, N>>& v) {
    std::vector<double> out;
    out.reserve(v.size() * N);
    for (const auto& a : v) out.insert(out.end(), a.begin(), a.end());
    return out;
}

cl::Program& eval_program(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel, Precision p) {
    BuildRequest build;
    build.kernel_file = "eval.cl";
    build.precision = p;
    build.defines = {{"BB_MODEL", std::to_string(model.id)}, {"BB_FRESNEL", std::to_string(fresnel.kind)}};
    return engine.program(build);
}

void run_1d(Engine& engine, cl::Kernel& kernel, size_t n) {
    const size_t local = 8;
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((n + local - 1) / local * local),
                                        cl::NDRange(local));
}

}  // namespace

std::vector<double> evaluate_on_device(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                       Precision precision, const std::vector<Vec3>& wo,
                                       const std::vector<Vec3>& wi) {
    if (wo.size() != wi.size()) throw Error("internal error: evaluate_on_device needs as many wo as wi");
    if (wo.empty()) return {};
    RealBuffers bufs(engine, precision);
    cl::Buffer b_wo = bufs.input(flatten(wo)), b_wi = bufs.input(flatten(wi));
    cl::Buffer b_p = bufs.input({model.params.begin(), model.params.end()});
    cl::Buffer b_fp = bufs.input({fresnel.params.begin(), fresnel.params.end()});
    cl::Buffer b_out = bufs.output(wo.size());
    cl::Kernel k(eval_program(engine, model, fresnel, precision), BB_ENTRY_NAME(BB_ENTRY_MODEL_EVAL));
    k.setArg(0, b_wo);
    k.setArg(1, b_wi);
    k.setArg(2, b_p);
    k.setArg(3, b_fp);
    k.setArg(4, cl_uint(wo.size()));
    k.setArg(5, b_out);
    run_1d(engine, k, wo.size());
    return bufs.read(b_out, wo.size());
}

std::vector<DeviceSample> sample_on_device(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                           Precision precision, const std::vector<Vec3>& wo,
                                           const std::vector<std::array<double, 2>>& u) {
    if (wo.size() != u.size()) throw Error("internal error: sample_on_device needs as many wo as u");
    if (wo.empty()) return {};
    RealBuffers bufs(engine, precision);
    cl::Buffer b_wo = bufs.input(flatten(wo)), b_u = bufs.input(flatten(u));
    cl::Buffer b_p = bufs.input({model.params.begin(), model.params.end()});
    cl::Buffer b_fp = bufs.input({fresnel.params.begin(), fresnel.params.end()});
    cl::Buffer b_wi = bufs.output(3 * wo.size()), b_w = bufs.output(wo.size());
    cl::Kernel k(eval_program(engine, model, fresnel, precision), BB_ENTRY_NAME(BB_ENTRY_MODEL_SAMPLE));
    k.setArg(0, b_wo);
    k.setArg(1, b_u);
    k.setArg(2, b_p);
    k.setArg(3, b_fp);
    k.setArg(4, cl_uint(wo.size()));
    k.setArg(5, b_wi);
    k.setArg(6, b_w);
    run_1d(engine, k, wo.size());
    const std::vector<double> wi = bufs.read(b_wi, 3 * wo.size()), w = bufs.read(b_w, wo.size());
    std::vector<DeviceSample> out(wo.size());
    for (size_t i = 0; i < wo.size(); ++i) out[i] = {{wi[3 * i], wi[3 * i + 1], wi[3 * i + 2]}, w[i]};
    return out;
}

}  // namespace brdfbake

#include "brdfbake/evaluate.h"

#include "brdfbake/error.h"
#include "brdfbake/brdf/kernel_abi.h"
#include "engine/device_buffer.h"
#include "integrate/launch.h"

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
    build.model = model.id;
    build.fresnel = fresnel.kind;
    return engine.program(build);
}

void run_1d(Engine& engine, cl::Kernel& kernel, size_t n) {
    const size_t local = 8;
    engine.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((n + local - 1) / local * local),
                                        cl::NDRange(local));
}

/// Runs the eval.cl entry point `entry` over n items. Its arguments: the n directions wo, a second
/// per-item input (wi, or the unit-square points u), the model's and the Fresnel term's
/// parameters, n, and then one output per entry of `output_sizes` (in reals); returns the outputs.
std::vector<std::vector<double>> run_eval_entry(Engine& engine, const char* entry, const ModelConfig& model,
                                                const FresnelConfig& fresnel, Precision precision, size_t n,
                                                const std::vector<double>& wo, const std::vector<double>& second,
                                                const std::vector<size_t>& output_sizes) {
    RealBuffers bufs(engine, precision);
    cl::Buffer b_wo = bufs.input(wo), b_second = bufs.input(second);
    cl::Buffer b_p = bufs.input({model.params.begin(), model.params.end()});
    cl::Buffer b_fp = bufs.input({fresnel.params.begin(), fresnel.params.end()});
    cl::Buffer b_data = model_data_buffer(bufs, model.id);
    cl::Kernel k(eval_program(engine, model, fresnel, precision), entry);
    cl_uint a = set_args(k, 0, b_wo, b_second, b_p, b_fp, b_data, cl_uint(n));
    std::vector<cl::Buffer> outputs;
    for (size_t size : output_sizes) {
        outputs.push_back(bufs.output(size));
        k.setArg(a++, outputs.back());
    }
    run_1d(engine, k, n);
    std::vector<std::vector<double>> out;
    for (size_t i = 0; i < outputs.size(); ++i) out.push_back(bufs.read(outputs[i], output_sizes[i]));
    return out;
}

}  // namespace

std::vector<double> evaluate_on_device(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                       Precision precision, const std::vector<Vec3>& wo,
                                       const std::vector<Vec3>& wi) {
    if (wo.size() != wi.size()) throw Error("internal error: evaluate_on_device needs as many wo as wi");
    if (wo.empty()) return {};
    return run_eval_entry(engine, BB_ENTRY_NAME(BB_ENTRY_MODEL_EVAL), model, fresnel, precision, wo.size(),
                          flatten(wo), flatten(wi), {wo.size()})[0];
}

std::vector<DeviceSample> sample_on_device(Engine& engine, const ModelConfig& model, const FresnelConfig& fresnel,
                                           Precision precision, const std::vector<Vec3>& wo,
                                           const std::vector<std::array<double, 2>>& u) {
    if (wo.size() != u.size()) throw Error("internal error: sample_on_device needs as many wo as u");
    if (wo.empty()) return {};
    const std::vector<std::vector<double>> outputs =
        run_eval_entry(engine, BB_ENTRY_NAME(BB_ENTRY_MODEL_SAMPLE), model, fresnel, precision, wo.size(),
                       flatten(wo), flatten(u), {3 * wo.size(), wo.size()});
    const std::vector<double>& wi = outputs[0];
    const std::vector<double>& w = outputs[1];
    std::vector<DeviceSample> out(wo.size());
    for (size_t i = 0; i < wo.size(); ++i) out[i] = {{wi[3 * i], wi[3 * i + 1], wi[3 * i + 2]}, w[i]};
    return out;
}

}  // namespace brdfbake

#include "engine/device_buffer.h"

#include "brdfbake/error.h"

namespace brdfbake {

cl::Buffer RealBuffers::input(const std::vector<double>& values) { return input(values.data(), values.size()); }

cl::Buffer RealBuffers::input(const double* values, size_t count) {
    const size_t n = std::max<size_t>(count, 1);
    if (precision_ == Precision::Double) {
        if (count > 0)
            return cl::Buffer(engine_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(double),
                              const_cast<double*>(values));
        double zero = 0.0;
        return cl::Buffer(engine_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(double), &zero);
    }
    std::vector<float> v(values, values + count);
    v.resize(n);
    return cl::Buffer(engine_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(float), v.data());
}

cl::Buffer RealBuffers::output(size_t count) {
    const size_t bytes = std::max<size_t>(count, 1) * real_size();
    if (bytes > engine_.device().max_alloc)
        throw Error("result buffer of " + std::to_string(bytes >> 20) + " MiB exceeds the device's " +
                    "largest allocation (" + std::to_string(engine_.device().max_alloc >> 20) + " MiB)");
    return cl::Buffer(engine_.context(), CL_MEM_WRITE_ONLY, bytes);
}

std::vector<double> RealBuffers::read(const cl::Buffer& buffer, size_t count) {
    if (precision_ == Precision::Double) {
        std::vector<double> v(count);
        engine_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(double), v.data());
        return v;
    }
    std::vector<float> f(count);
    engine_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), f.data());
    return std::vector<double>(f.begin(), f.end());
}

double event_seconds(const cl::Event& event) {
    const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    return double(end - start) * 1e-9;
}

}  // namespace brdfbake

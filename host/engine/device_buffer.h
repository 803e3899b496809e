// Buffers of the kernels' `real` type, filled from and read back into double on the host.
#pragma once

#include <vector>

#include "brdfbake/engine.h"

namespace brdfbake {

class RealBuffers {
public:
    RealBuffers(Engine& engine, Precision precision) : engine_(engine), precision_(precision) {}

    /// A read-only device buffer holding `values` converted to the kernel's real type.
    cl::Buffer input(const std::vector<double>& values);
    /// The same from `count` values in place (no copy on the host in double precision).
    cl::Buffer input(const double* values, size_t count);
    /// A write-only device buffer of `count` reals.
    cl::Buffer output(size_t count);
    /// Reads `count` reals back (blocking), converted to double.
    std::vector<double> read(const cl::Buffer& buffer, size_t count);

    size_t real_size() const { return precision_ == Precision::Double ? sizeof(double) : sizeof(float); }

private:
    Engine& engine_;
    Precision precision_;
};

/// Device time of a completed event in seconds (the queue has profiling enabled).
double event_seconds(const cl::Event& event);

}  // namespace brdfbake

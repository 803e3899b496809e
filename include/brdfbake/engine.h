// The OpenCL engine: device discovery and choice, program builds (options assembled in one
// place, sources embedded at build time, PoCL's on-disk kernel cache), and the command queue.
#pragma once

#include <CL/opencl.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace brdfbake {

enum class Precision { Float, Double };
const char* precision_name(Precision p);

/// Facts about one OpenCL device, queried once.
struct DeviceInfo {
    int platform_index = 0;
    int device_index = 0;
    std::string platform;
    std::string name;
    std::string vendor;
    std::string version;         // CL_DEVICE_VERSION
    std::string driver;          // CL_DRIVER_VERSION
    std::string type;            // "cpu", "gpu", "accelerator", "other"
    unsigned compute_units = 0;
    unsigned max_clock_mhz = 0;
    bool fp64 = false;
    std::uint64_t global_mem = 0;
    std::uint64_t max_alloc = 0;
    std::size_t max_work_group = 0;
    /// Lanes of the explicit vector type that kernels with a vector path use (real = floatN /
    /// doubleN, -D BB_VECTOR_WIDTH=N); 1: scalar work-items. CPUs (PoCL) get 16 floats and 8
    /// doubles: PoCL vectorises explicit vector types, not scalar work-items that call
    /// built-ins (issue 9), and two AVX2 registers per value hide the FMA latency. GPUs get 1:
    /// their SIMT hardware already runs work-items in lanes.
    unsigned vector_lanes_float = 1;
    unsigned vector_lanes_double = 1;
    cl::Device device;
};

/// Every device of every platform; throws Error (with installation advice) if there is none.
std::vector<DeviceInfo> list_devices();

/// Chooses a device from a selector "P:D" (platform and device index), "N" (flat index into
/// list_devices()), "cpu" or "gpu"; an empty selector takes $BRDFBAKE_DEVICE, else PoCL's first
/// device, else the first device. Throws Error for a selector that matches nothing.
DeviceInfo choose_device(const std::string& selector);

/// The vector path a build of a kernel file takes where it has lanes (Engine::vector_width > 1):
/// the file's own (the disk points of albedo_replicas_disk, the half-vector rows of
/// albedo_quadrature_rows, the dielectric's), or one chosen by a build option.
enum class VectorPath {
    Default,
    Points,         // -D BB_VECTOR_POINTS: importance sampling from the Hammersley point table
    UniformPoints,  // and -D BB_VECTOR_UNIFORM: qmc's uniform hemisphere weights from that table
    SamplerRows,    // -D BB_QUAD_SAMPLER_ROWS: the quadrature in the sampler's square, one row per lane
};

/// What a program build needs besides the source. Engine::build_options turns it into the
/// compiler's options, the one place they are decided (option names in brdf/kernel_abi.h).
struct BuildRequest {
    std::string kernel_file;                       // e.g. "albedo.cl"
    Precision precision = Precision::Float;
    int model = 0;                 // -D BB_MODEL=<id> (BB_MODEL_*); 0: none (a kernel of no model)
    int fresnel = -1;              // -D BB_FRESNEL=<kind> (BB_FRESNEL_*); -1: none
    bool quadrature = false;       // -D BB_QUADRATURE: the file's quadrature entry points
    bool random123 = false;        // the kernel includes <Random123/philox.h>: -D BB_PHILOX and its -I
    bool has_vector_path = false;  // the kernel file has a vector path for this request
    unsigned vector_width = 0;     // 0: the device's choice; 1: scalar; N: N lanes
    VectorPath vector_path = VectorPath::Default;  // which one, where the build has lanes
    /// Every cell of the launch isotropic: the disk path drops the terms that vanish then
    /// (-D BB_ISOTROPIC, bb_model_disk_isotropic), where the build has lanes.
    bool isotropic = false;
};

class Engine {
public:
    explicit Engine(const std::string& device_selector = "", bool verbose = false);

    const DeviceInfo& device() const { return info_; }
    cl::Context& context() { return context_; }
    cl::CommandQueue& queue() { return queue_; }
    bool verbose() const { return verbose_; }

    /// The built program for a request, built once per engine and options; PoCL keeps the
    /// compiled binary in its own cache (~/.cache/pocl or $POCL_CACHE_DIR) across runs.
    /// Throws Error with the build log on failure.
    cl::Program& program(const BuildRequest& request);

    /// The compiler options for a request on this device (the single place they are assembled).
    std::string build_options(const BuildRequest& request) const;

    /// The lanes of `real` a build of `request` uses (1: the scalar kernels). Decided here and
    /// in build_options only.
    unsigned vector_width(const BuildRequest& request) const;

    /// Seconds spent in program builds so far.
    double build_seconds() const { return build_seconds_; }

private:
    DeviceInfo info_;
    cl::Context context_;
    cl::CommandQueue queue_;
    bool verbose_;
    std::map<std::string, cl::Program> programs_;
    double build_seconds_ = 0.0;
};

/// The source of an embedded kernel file with every `#include "brdfbake/..."` expanded from
/// the embedded headers, so that the binary runs from any directory.
std::string kernel_source(const std::string& kernel_file);

/// A readable name for an OpenCL error code.
std::string cl_error_name(int code);

}  // namespace brdfbake

#include "brdfbake/engine.h"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "brdfbake/error.h"
#include "engine/embedded_sources.h"

namespace brdfbake {

const char* precision_name(Precision p) { return p == Precision::Double ? "double" : "float"; }

std::string cl_error_name(int code) {
    switch (code) {
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE: return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE: return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_DEVICE: return "CL_INVALID_DEVICE";
    case CL_INVALID_BINARY: return "CL_INVALID_BINARY";
    case CL_INVALID_BUILD_OPTIONS: return "CL_INVALID_BUILD_OPTIONS";
    case CL_INVALID_KERNEL_NAME: return "CL_INVALID_KERNEL_NAME";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_ARG_INDEX: return "CL_INVALID_ARG_INDEX";
    case CL_INVALID_ARG_SIZE: return "CL_INVALID_ARG_SIZE";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE: return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    default: return "OpenCL error " + std::to_string(code);
    }
}

namespace {

const char* kNoPlatformAdvice =
    "no OpenCL platform found. brdfbake runs on PoCL (OpenCL on the CPU) by default: install it "
    "with `sudo apt-get install pocl-opencl-icd` (or run scripts/setup.sh); on a GPU machine "
    "install the vendor's OpenCL ICD. `clinfo` lists what the ICD loader sees.";

std::string type_name(cl_device_type t) {
    if (t & CL_DEVICE_TYPE_GPU) return "gpu";
    if (t & CL_DEVICE_TYPE_CPU) return "cpu";
    if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    return "other";
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
    return s;
}

DeviceInfo query(const cl::Platform& platform, const cl::Device& d, int pi, int di) {
    DeviceInfo info;
    info.platform_index = pi;
    info.device_index = di;
    info.platform = trim(platform.getInfo<CL_PLATFORM_NAME>());
    info.name = trim(d.getInfo<CL_DEVICE_NAME>());
    info.vendor = trim(d.getInfo<CL_DEVICE_VENDOR>());
    info.version = trim(d.getInfo<CL_DEVICE_VERSION>());
    info.driver = trim(d.getInfo<CL_DRIVER_VERSION>());
    info.type = type_name(d.getInfo<CL_DEVICE_TYPE>());
    info.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
    info.max_clock_mhz = d.getInfo<CL_DEVICE_MAX_CLOCK_FREQUENCY>();
    info.fp64 = d.getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
    info.global_mem = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
    info.max_alloc = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    info.max_work_group = d.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
    if (info.type == "cpu") {
        info.vector_lanes_float = 16;
        info.vector_lanes_double = info.fp64 ? 8 : 1;
    }
    info.device = d;
    return info;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
    std::vector<cl::Platform> platforms;
    cl_int err = cl::Platform::get(&platforms);
    if (err != CL_SUCCESS || platforms.empty()) throw Error(kNoPlatformAdvice);
    std::vector<DeviceInfo> out;
    for (size_t pi = 0; pi < platforms.size(); ++pi) {
        std::vector<cl::Device> devices;
        try {
            platforms[pi].getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue;  // a platform without devices (CL_DEVICE_NOT_FOUND)
        }
        for (size_t di = 0; di < devices.size(); ++di)
            out.push_back(query(platforms[pi], devices[di], int(pi), int(di)));
    }
    if (out.empty())
        throw Error("OpenCL platforms were found but no device: is /sys mounted (PoCL needs it "
                    "to size its device)? `clinfo` shows what the ICD loader sees.");
    return out;
}

DeviceInfo choose_device(const std::string& selector_arg) {
    std::string selector = selector_arg;
    if (selector.empty()) {
        if (const char* env = std::getenv("BRDFBAKE_DEVICE")) selector = env;
    }
    const std::vector<DeviceInfo> all = list_devices();
    if (selector.empty()) {
        for (const auto& d : all)
            if (d.platform.find("Portable Computing Language") != std::string::npos) return d;
        return all.front();
    }
    if (selector == "cpu" || selector == "gpu" || selector == "accelerator") {
        for (const auto& d : all)
            if (d.type == selector) return d;
        throw Error("no OpenCL device of type '" + selector + "' (see `brdfbake devices`)");
    }
    auto parse_index = [&](const std::string& s) {
        if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
            throw Error("bad device selector '" + selector +
                        "': expected P:D, N, cpu or gpu (see `brdfbake devices`)");
        return std::stoi(s);
    };
    const size_t colon = selector.find(':');
    if (colon != std::string::npos) {
        const int p = parse_index(selector.substr(0, colon));
        const int d = parse_index(selector.substr(colon + 1));
        for (const auto& info : all)
            if (info.platform_index == p && info.device_index == d) return info;
        throw Error("no OpenCL device " + selector + " (see `brdfbake devices`)");
    }
    const int n = parse_index(selector);
    if (n >= int(all.size()))
        throw Error("no OpenCL device " + selector + ": there are " + std::to_string(all.size()) +
                    " (see `brdfbake devices`)");
    return all[size_t(n)];
}

Engine::Engine(const std::string& device_selector, bool verbose)
    : info_(choose_device(device_selector)), verbose_(verbose) {
    try {
        context_ = cl::Context(info_.device);
        queue_ = cl::CommandQueue(context_, info_.device, CL_QUEUE_PROFILING_ENABLE);
    } catch (const cl::Error& e) {
        throw Error("cannot open OpenCL device '" + info_.name + "': " + e.what() + " (" +
                    cl_error_name(e.err()) + ")");
    }
    if (verbose_)
        std::cerr << "brdfbake: device " << info_.platform_index << ":" << info_.device_index << " "
                  << info_.name << " (" << info_.platform << ")\n";
}

unsigned Engine::vector_width(const BuildRequest& request) const {
    if (!request.has_vector_path) return 1;
    if (request.vector_width > 0) return request.vector_width;
    return request.precision == Precision::Double ? info_.vector_lanes_double : info_.vector_lanes_float;
}

std::string Engine::build_options(const BuildRequest& request) const {
    std::ostringstream o;
    // OpenCL C 1.2 is what PoCL and NVIDIA both accept. No -cl-fast-relaxed-math: it lets the
    // compiler assume finite values, and the kernels count non-finite samples (docs/architecture.md).
    o << "-cl-std=CL1.2";
    if (request.precision == Precision::Double) {
        if (!info_.fp64)
            throw Error("device '" + info_.name + "' has no double precision (cl_khr_fp64); use --precision float");
        o << " -D BB_REAL_DOUBLE=1";
    }
    // The vector path (real = floatN/doubleN) where the kernel has one and the device profits.
    const unsigned lanes = vector_width(request);
    if (lanes > 1) {
        if (lanes != 2 && lanes != 4 && lanes != 8 && lanes != 16)
            throw Error("vector width " + std::to_string(lanes) + " is not an OpenCL vector size (2, 4, 8, 16)");
        o << " -D BB_VECTOR_WIDTH=" << lanes;
    }
    for (const auto& d : request.defines) o << " -D " << d.first << "=" << d.second;
    // Random123 is header-only and works in OpenCL C (its openclfeatures.h): the kernel
    // includes the installed headers (librandom123-dev), found by CMake at configure time.
    if (request.random123) o << " -D BB_PHILOX=1 -I " << BRDFBAKE_RANDOM123_INCLUDE_DIR;
    return o.str();
}

cl::Program& Engine::program(const BuildRequest& request) {
    const std::string options = build_options(request);
    const std::string key = request.kernel_file + "|" + options;
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second;

    const std::string source = kernel_source(request.kernel_file);
    const auto t0 = std::chrono::steady_clock::now();
    cl::Program program(context_, source);
    try {
        program.build(std::vector<cl::Device>{info_.device}, options.c_str());
    } catch (const cl::Error& e) {
        std::string log;
        try {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(info_.device);
        } catch (const cl::Error&) {
        }
        throw Error("kernel build failed for " + request.kernel_file + " with options '" + options +
                    "' on '" + info_.name + "' (" + cl_error_name(e.err()) + "); build log:\n" + log);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    build_seconds_ += seconds;
    if (verbose_) {
        std::cerr << "brdfbake: built " << request.kernel_file << " [" << options << "] in "
                  << seconds * 1e3 << " ms\n";
        std::string log;
        try {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(info_.device);
        } catch (const cl::Error&) {
        }
        if (log.find_first_not_of(" \t\r\n") != std::string::npos) std::cerr << "brdfbake: build log:\n" << log << "\n";
    }
    return programs_.emplace(key, std::move(program)).first->second;
}

namespace {

// Expands `#include "..."` from the embedded files. Every occurrence is expanded (an include
// may sit inside an #if that the kernel's options switch off); the include guards of the
// headers keep repeated expansions harmless. `stack` catches include cycles.
void expand(const std::string& name, std::vector<std::string>& stack, std::string& out) {
    for (const auto& s : stack)
        if (s == name) throw Error("internal error: include cycle through '" + name + "'");
    stack.push_back(name);
    const char* text = embedded_source(name);
    if (!text) throw Error("internal error: no embedded source '" + name + "'");
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const size_t p = line.find("#include \"");
        if (p != std::string::npos && line.find_first_not_of(" \t") == p) {
            const size_t q = line.find('"', p + 10);
            expand(line.substr(p + 10, q - p - 10), stack, out);
            continue;
        }
        out += line;
        out += '\n';
    }
    stack.pop_back();
}

}  // namespace

std::string kernel_source(const std::string& kernel_file) {
    std::vector<std::string> stack;
    std::string out;
    expand("kernels/" + kernel_file, stack, out);
    return out;
}

}  // namespace brdfbake

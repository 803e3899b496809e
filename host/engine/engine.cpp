#include "brdfbake/engine.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <thread>

#include "brdfbake/brdf/kernel_abi.h"
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

// --- the environment PoCL needs, checked so that a failure names its cause ----------------------

/// The address space (ulimit -v) below which PoCL cannot start its device and compiler: measured
/// with PoCL 3.1 on 2 cores, `albedo` needs about 490 MiB (below that, depending on the limit,
/// the ICD loader finds no platform, PoCL aborts creating its threads, or a kernel build
/// deadlocks inside PoCL). Each PoCL worker thread reserves a stack and a malloc arena (8 + 64
/// MiB of address space), hence a base plus a share per hardware thread, with a margin.
std::uint64_t min_address_space_bytes() {
    const std::uint64_t threads = std::max(1u, std::thread::hardware_concurrency());
    return (512ull + 80ull * threads) << 20;
}

std::string mib(std::uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

/// The soft address-space limit in bytes, or 0 when there is none.
std::uint64_t address_space_limit() {
    struct rlimit r {};
    if (::getrlimit(RLIMIT_AS, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return 0;
    return std::uint64_t(r.rlim_cur);
}

/// PoCL's kernel cache folder as PoCL 3 chooses it (PoCL's documentation of POCL_CACHE_DIR):
/// $POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl/kcache, else $HOME/.cache/pocl/kcache; empty when
/// none of them is set. `from` names the variable it came from.
std::string pocl_cache_dir(std::string& from) {
    auto env = [](const char* name) {
        const char* v = std::getenv(name);
        return std::string(v ? v : "");
    };
    if (std::getenv("POCL_CACHE_DIR")) {
        from = "POCL_CACHE_DIR";
        return env("POCL_CACHE_DIR");
    }
    if (!env("XDG_CACHE_HOME").empty()) {
        from = "XDG_CACHE_HOME";
        return env("XDG_CACHE_HOME") + "/pocl/kcache";
    }
    if (!env("HOME").empty()) {
        from = "HOME";
        return env("HOME") + "/.cache/pocl/kcache";
    }
    return "";
}

/// Why PoCL cannot create or write its kernel cache folder, or "" when it can (or when the
/// folder is unknown). Creates nothing: it finds the nearest existing folder on the path.
std::string pocl_cache_problem() {
    std::string from;
    const std::string dir = pocl_cache_dir(from);
    if (dir.empty()) return "";
    const std::string advice = "; set POCL_CACHE_DIR to a writable folder";
    const std::string what = "PoCL's kernel cache folder '" + dir + "' (from $" + from + ")";
    std::string path = dir;
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    for (;;) {
        struct stat st {};
        if (::stat(path.c_str(), &st) == 0) {
            if (!S_ISDIR(st.st_mode)) return what + " cannot be created: '" + path + "' is not a folder" + advice;
            // Whether a folder can be made there, tried (access() says yes to root on /proc).
            std::string probe = path + (path == "/" ? "" : "/") + ".brdfbake-probe-XXXXXX";
            if (::mkdtemp(&probe[0])) {
                ::rmdir(probe.c_str());
                return "";
            }
            return what + (path == dir ? " is not writable" : " cannot be created in '" + path + "'") + " (" +
                   std::strerror(errno) + ")" + advice;
        }
        if (errno != ENOENT && errno != ENOTDIR)
            return what + " cannot be used: '" + path + "': " + std::strerror(errno) + advice;
        const size_t slash = path.find_last_of('/');
        if (slash == std::string::npos) return "";  // a relative path: its first part is created in "."
        path = slash == 0 ? "/" : path.substr(0, slash);
    }
}

/// What can be known before the ICD loader starts the platforms, because past it the failure is
/// a misleading code, an abort or a hang inside PoCL.
void check_environment_before_platforms() {
    const char* cache = std::getenv("POCL_CACHE_DIR");
    if (cache && !*cache)
        throw Error("POCL_CACHE_DIR is set but empty (PoCL aborts on it): unset it or name a writable folder");
    const std::uint64_t limit = address_space_limit(), need = min_address_space_bytes();
    if (limit && limit < need)
        throw Error("out of memory: the address space limit (ulimit -v) is " + mib(limit) + ", and the OpenCL device " +
                    "(PoCL with its compiler) needs at least " + mib(need) + " on this machine; raise the limit");
}

/// The advice when no platform or no device starts: the cache folder, the address space limit,
/// or the installation.
std::string no_device_advice(const std::string& otherwise) {
    const std::string cache = pocl_cache_problem();
    if (!cache.empty()) return "no OpenCL device could start: " + cache;
    std::string out = otherwise;
    if (const std::uint64_t limit = address_space_limit())
        out += " The address space is limited (ulimit -v " + std::to_string(limit >> 10) +
               " KiB): too little memory also stops PoCL from starting.";
    return out;
}

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
    check_environment_before_platforms();
    std::vector<cl::Platform> platforms;
    cl_int err = CL_SUCCESS;
    try {
        err = cl::Platform::get(&platforms);
    } catch (const cl::Error& e) {
        err = e.err();  // CL_PLATFORM_NOT_FOUND_KHR when no ICD loads, e.g. for lack of memory
    }
    if (err != CL_SUCCESS || platforms.empty()) throw Error(no_device_advice(kNoPlatformAdvice));
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
        throw Error(no_device_advice("OpenCL platforms were found but no device: is /sys mounted (PoCL needs it "
                                     "to size its device)? `clinfo` shows what the ICD loader sees."));
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
    const auto define = [&o](const char* name, long long value) { o << " -D " << name << "=" << value; };
    // OpenCL C 1.2 is what PoCL and NVIDIA both accept. No -cl-fast-relaxed-math: it lets the
    // compiler assume finite values, and the kernels count non-finite samples (docs/architecture.md).
    o << "-cl-std=CL1.2";
    if (request.precision == Precision::Double) {
        if (!info_.fp64)
            throw Error("device '" + info_.name + "' has no double precision (cl_khr_fp64); use --precision float");
        define(BB_OPTION_REAL_DOUBLE, 1);
    }
    // The vector path (real = floatN/doubleN) where the kernel has one and the device profits.
    const unsigned lanes = vector_width(request);
    if (lanes > 1) {
        if (lanes != 2 && lanes != 4 && lanes != 8 && lanes != 16)
            throw Error("vector width " + std::to_string(lanes) + " is not an OpenCL vector size (2, 4, 8, 16)");
        define(BB_OPTION_VECTOR_WIDTH, lanes);
    }
    if (request.model != 0) define(BB_OPTION_MODEL, request.model);
    if (request.fresnel >= 0) define(BB_OPTION_FRESNEL, request.fresnel);
    if (request.quadrature) define(BB_OPTION_QUADRATURE, 1);
    if (lanes > 1) {
        const VectorPath path = request.vector_path;
        if (path == VectorPath::Points || path == VectorPath::UniformPoints) define(BB_OPTION_VECTOR_POINTS, 1);
        if (path == VectorPath::UniformPoints) define(BB_OPTION_VECTOR_UNIFORM, 1);
        if (request.isotropic) define(BB_OPTION_ISOTROPIC, 1);
        if (path == VectorPath::SamplerRows) define(BB_OPTION_QUAD_SAMPLER_ROWS, 1);
    }
    // Random123 is header-only and works in OpenCL C (its openclfeatures.h): the kernel
    // includes the installed headers (librandom123-dev), found by CMake at configure time.
    if (request.random123) {
        define(BB_OPTION_PHILOX, 1);
        o << " -I " << BRDFBAKE_RANDOM123_INCLUDE_DIR;
    }
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
        // Only a compile error has a log worth reading. After an allocation failure PoCL 3.1 can
        // leave the program locked, and asking for its log then waits forever.
        if (e.err() == CL_OUT_OF_HOST_MEMORY || e.err() == CL_OUT_OF_RESOURCES)
            throw Error("out of memory building the kernel " + request.kernel_file + " on '" + info_.name + "' (" +
                        cl_error_name(e.err()) + ")" +
                        (address_space_limit() ? "; the address space limit (ulimit -v) is " + mib(address_space_limit())
                                               : std::string()));
        std::string log;
        if (e.err() == CL_BUILD_PROGRAM_FAILURE) {
            try {
                log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(info_.device);
            } catch (const cl::Error&) {
            }
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

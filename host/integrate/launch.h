// Launch plumbing shared by every integrator (albedo, rough dielectric, reciprocity scan):
// setting a kernel's arguments in order, running a launch in slices with progress and cancel
// between them, the per-item non-finite counts, and the memory a launch takes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/engine.h"
#include "engine/device_buffer.h"
#include "integrate/replicas.h"

namespace brdfbake {

/// Work-items per work-group of a 1-D integration launch. An explicit small work-group: the
/// default could give PoCL two groups for two cores, or one, whatever the table size (issue 9).
constexpr size_t kLocalSize = 8;

/// Sets the kernel's arguments from index `first` on, in order; returns the index after them.
template <typename... Args>
cl_uint set_args(cl::Kernel& kernel, cl_uint first, const Args&... args) {
    (kernel.setArg(first++, args), ...);
    return first;
}

/// The index space of a launch: `n_items` work-items in groups of `local`, or with `columns` > 0
/// a 2-D range of `columns` x `n_items` work-items (groups of local x local), each item then a
/// row of columns. Slices cut along the items (rows).
struct LaunchShape {
    size_t n_items = 0;
    size_t local = kLocalSize;
    size_t columns = 0;
    /// The work of a slice, at least (in the unit of work_per_item).
    double slice_work = double(1 << 26);
};

/// Runs a kernel over a launch shape and returns the kernel time in seconds. `work_per_item`
/// is the item's cost (albedo samples, or what the shape's slice_work counts): a long launch
/// (more than slice_work) runs in up to 64 slices of the index range (the work-items keep their
/// global ids, so the results are the same), reporting progress (`what`) and honouring a cancel
/// request between slices; a short one is one launch.
double run_items(Engine& engine, cl::Kernel& kernel, const LaunchShape& shape, double work_per_item,
                 const std::string& what);

/// The 1-D launch of n_items work-items in groups of kLocalSize.
inline double run_items(Engine& engine, cl::Kernel& kernel, size_t n_items, double work_per_item,
                        const std::string& what) {
    LaunchShape shape;
    shape.n_items = n_items;
    return run_items(engine, kernel, shape, work_per_item, what);
}

/// The per-item counts of non-finite samples, the last output of every integration kernel.
struct NonFiniteCounts {
    NonFiniteCounts(Engine& engine, size_t n_items)
        : buffer(engine.context(), CL_MEM_WRITE_ONLY, n_items * sizeof(cl_uint)), size(n_items) {}
    /// Reads the counts back (blocking).
    std::vector<cl_uint> read(Engine& engine) const;
    cl::Buffer buffer;
    size_t size;
};

/// What the chunks' launches of a sampling integrator (vector_chunks) sum to: per output, the
/// replica means of every item; the non-finite samples per item; the kernel seconds.
struct ChunkSums {
    std::vector<std::vector<double>> means;
    std::vector<cl_uint> bad;
    double kernel_seconds = 0.0;
};

/// Runs `launch(chunk, bad)` for each chunk of each replica's `points` (it sets the kernel's
/// arguments, `bad` the non-finite counts, and returns run_items' seconds), reads `outputs`
/// (n_items values each) after it, and sums the chunks' means weighted by their share of points.
ChunkSums run_chunks(Engine& engine, RealBuffers& bufs, const std::vector<PointChunk>& chunks, std::uint64_t points,
                     size_t n_items, const std::vector<cl::Buffer>& outputs,
                     const std::function<double(const PointChunk& chunk, const cl::Buffer& bad)>& launch);

/// The model data buffer of an entry point that evaluates a model (BB_MODEL_DATA_ARG in
/// kernel_abi.h): a closed-form model reads none and gets BB_MODEL_DATA_DUMMY_SIZE zeros; merl
/// gets the process's MERL tables (models/merl_file.h).
cl::Buffer model_data_buffer(RealBuffers& buffers, int model);

/// The Fresnel parameters and the model data of a launch: a tabulated Fresnel curve
/// (BB_FRESNEL_TABLE, brdf/fresnel.h) follows the model's data, which is padded to
/// BB_FRESNEL_TABLE_ALIGN numbers, and its block goes into the parameters.
struct FresnelBuffers {
    cl::Buffer params, model_data;
};
FresnelBuffers fresnel_buffers(RealBuffers& buffers, int model, const FresnelConfig& fresnel);

/// The build of `kernel_file` for an albedo request: its precision, model and Fresnel kind.
inline BuildRequest albedo_build(const std::string& kernel_file, const AlbedoRequest& req) {
    BuildRequest build;
    build.kernel_file = kernel_file;
    build.precision = req.precision;
    build.model = req.model;
    build.fresnel = req.fresnel.kind;
    return build;
}

/// Memory a sampling or quadrature launch takes, for check_memory before anything is allocated:
/// the cell arrays (mu, phi and the parameter block, in double on the host and again in the
/// kernel's precision for the upload and on the device), the shared point or node table (per
/// point, `table_values` numbers in double, converted and on the device) and the per-item
/// outputs (value, square, non-finite count; on the device and read back).
double launch_bytes(size_t n_cells, size_t n_items, double table_points, unsigned table_values, Precision p);

}  // namespace brdfbake

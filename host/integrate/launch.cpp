#include "integrate/launch.h"

#include <algorithm>

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/model_registry.h"
#include "brdfbake/brdf/params.h"
#include "brdfbake/cancel.h"
#include "brdfbake/progress.h"
#include "engine/device_buffer.h"
#include "models/merl_file.h"
#include "models/sheen_ltc_table.h"

namespace brdfbake {

double run_items(Engine& engine, cl::Kernel& kernel, const LaunchShape& shape, double work_per_item,
                 const std::string& what) {
    throw_if_cancelled();
    const size_t n_items = shape.n_items, local = shape.local;
    const size_t groups = (n_items + local - 1) / local;
    const double work = double(n_items) * work_per_item;
    const size_t slices = std::min<size_t>({groups, 64, size_t(std::max(1.0, work / shape.slice_work))});
    const size_t per_slice = slices <= 1 ? groups : (groups + slices - 1) / slices;
    const size_t columns = (shape.columns + local - 1) / local * local;  // 2-D: padded to the groups
    double seconds = 0.0;
    if (slices > 1) report_progress(what, 0, n_items);
    for (size_t first = 0; first < groups; first += per_slice) {
        const size_t count = std::min(per_slice, groups - first);
        cl::Event done;
        if (shape.columns == 0)
            engine.queue().enqueueNDRangeKernel(kernel, cl::NDRange(first * local), cl::NDRange(count * local),
                                                cl::NDRange(local), nullptr, &done);
        else
            engine.queue().enqueueNDRangeKernel(kernel, cl::NDRange(0, first * local),
                                                cl::NDRange(columns, count * local), cl::NDRange(local, local),
                                                nullptr, &done);
        done.wait();
        seconds += event_seconds(done);
        if (slices <= 1) break;
        report_progress(what, std::min<std::uint64_t>(std::uint64_t(first + count) * local, n_items), n_items);
        if (first + count < groups) throw_if_cancelled();
    }
    return seconds;
}

ChunkSums run_chunks(Engine& engine, RealBuffers& bufs, const std::vector<PointChunk>& chunks, std::uint64_t points,
                     size_t n_items, const std::vector<cl::Buffer>& outputs,
                     const std::function<double(const PointChunk& chunk, const cl::Buffer& bad)>& launch) {
    ChunkSums sums;
    sums.means.assign(outputs.size(), std::vector<double>(n_items, 0.0));
    sums.bad.assign(n_items, 0u);
    for (const PointChunk& chunk : chunks) {
        const NonFiniteCounts bad_counts(engine, n_items);
        sums.kernel_seconds += launch(chunk, bad_counts.buffer);
        const double share = chunks.size() == 1 ? 1.0 : double(chunk.count) / double(points);
        for (size_t k = 0; k < outputs.size(); ++k) {
            const std::vector<double> part = bufs.read(outputs[k], n_items);
            for (size_t i = 0; i < n_items; ++i) sums.means[k][i] += share * part[i];
        }
        const std::vector<cl_uint> part_bad = bad_counts.read(engine);
        for (size_t i = 0; i < n_items; ++i) sums.bad[i] += part_bad[i];
    }
    return sums;
}

std::vector<cl_uint> NonFiniteCounts::read(Engine& engine) const {
    std::vector<cl_uint> counts(size);
    engine.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, size * sizeof(cl_uint), counts.data());
    return counts;
}

namespace {
std::vector<double> model_data(int model) {
    if (model == BB_MODEL_MERL) {  // the tables of brdf/merl.h
        MerlModelData d;
        merl_model_data(d);
        return d.joined.empty() ? std::vector<double>(d.data, d.data + d.size) : std::move(d.joined);
    }
    if (model == BB_MODEL_SHEEN_LTC) return sheen_ltc_model_data();  // the tables of brdf/sheen_ltc.h
    return std::vector<double>(BB_MODEL_DATA_DUMMY_SIZE, 0.0);
}
}  // namespace

cl::Buffer model_data_buffer(RealBuffers& buffers, int model) {
    if (model != BB_MODEL_MERL) return buffers.input(model_data(model));
    MerlModelData d;  // the tables in place: no host copy of a 11.7 MB table per launch
    merl_model_data(d);
    return buffers.input(d.data, d.size);
}

FresnelBuffers fresnel_buffers(RealBuffers& buffers, int model, const FresnelConfig& fresnel) {
    std::vector<double> params(fresnel.params.begin(), fresnel.params.end());
    if (fresnel.kind != BB_FRESNEL_TABLE) return {buffers.input(params), model_data_buffer(buffers, model)};
    std::vector<double> data = model_data(model);
    const size_t block = (data.size() + BB_FRESNEL_TABLE_ALIGN - 1) / BB_FRESNEL_TABLE_ALIGN;
    data.resize(block * BB_FRESNEL_TABLE_ALIGN, 0.0);
    data.insert(data.end(), fresnel.curve.begin(), fresnel.curve.end());
    params[BB_FRESNEL_TABLE_BLOCK] = double(block);
    params[BB_FRESNEL_TABLE_NODES] = double(fresnel.curve.size());
    return {buffers.input(params), buffers.input(data)};
}

double launch_bytes(size_t n_cells, size_t n_items, double table_points, unsigned table_values, Precision p) {
    const double real_bytes = p == Precision::Double ? 8.0 : 4.0;
    const double per_number = 8.0 + 2.0 * real_bytes;
    return double(n_cells) * (2 + BB_MAX_PARAMS) * per_number + table_points * table_values * per_number +
           double(n_items) * (2.0 * real_bytes + 4.0) * 2.0;
}

}  // namespace brdfbake

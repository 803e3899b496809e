// MERL measured BRDFs (Matusik et al. 2003, brdf/merl.h): the binary file read and validated
// once per process, one channel of it as a table in the process's store (the model data the
// kernels read), and the writer the tests and scripts/make_merl.py's C++ twin use.
//
// The format: three int32 dimensions (90, 90, 180), then three planes (red, green, blue) of
// 90*90*180 little-endian doubles, scaled by 1/1500, 1.15/1500 and 1.66/1500; a negative value
// marks an unmeasured bin. Anything else is refused with an Error naming the problem, and the
// file's size is judged before a byte is read (a file of the wrong size, a directory, a device).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "brdfbake/brdf/merl.h"
#include "brdfbake/spec.h"

namespace brdfbake {

/// The channels a spec can name: r, g, b, and Rec. 709 luminance y.
enum class MerlChannel { R = 0, G = 1, B = 2, Y = 3 };

/// [M03]'s per-channel scales, value = stored * scale.
constexpr std::array<double, 3> kMerlScale = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
/// The file's size: three int32, three planes of doubles.
constexpr std::uintmax_t kMerlFileBytes = 12 + 3 * std::uintmax_t(BB_MERL_BINS) * 8;

/// The node directions (wo, wi) of bins (ih, id, ip): the bins' lower edges (brdf/merl.h), with
/// phi_h = 0. Either may lie below the horizon.
void merl_node_dirs(int ih, int id, int ip, std::array<double, 3>& wo, std::array<double, 3>& wi);

/// Writes a MERL file whose bin (ih, id, ip) holds f(wo, wi) of its node directions per channel
/// (unscaled f; a negative value marks the bin unmeasured). Throws Error if it cannot be written.
void write_merl_file(const std::string& path,
                     const std::function<std::array<double, 3>(const std::array<double, 3>& wo,
                                                               const std::array<double, 3>& wi)>& f);

/// What a table holds beyond its values.
struct MerlTableInfo {
    std::string path;
    MerlChannel channel;
    std::size_t unmeasured = 0;  // bins with a negative value
    /// phi_d nodes k and 180 - k hold the same value in every (theta_h, theta_d) row, within
    /// 1e-9 relative, unmeasured alike (brdf/merl.h, bb_merl_mirror_symmetric).
    bool mirror_symmetric = false;
};

/// The index in the process's store of the table of `channel` of the file at `path`. The file is
/// read into memory (pread) and validated once per process and file version (path, inode, size,
/// modification time; a file rewritten in place is read again, and so is one whose modification
/// time lies within a timestamp tick of its read, compared byte for byte) and every channel is
/// built from those bytes; the same version and channel give the same index. A file truncated or
/// rewritten after its read leaves the tables read from it as they were. Throws Error (wrong size or dimensions, NaN or Inf, not
/// a regular file, unreadable). "builtin:lambert" is an in-memory file, f = 1/pi in every bin.
int merl_table_index(const std::string& path, MerlChannel channel);

/// Table `index`'s information; throws Error for an unknown index.
MerlTableInfo merl_table_info(int index);

/// Every table of the store, one after the other (BB_MERL_BINS values each): the model data of
/// a launch of the merl model (brdf/merl.h reads table k at k * BB_MERL_BINS). A process with
/// one table gets that table in place (`joined` stays empty); several are joined into `joined`.
struct MerlModelData {
    const double* data = nullptr;
    std::size_t size = 0;
    std::vector<double> joined;
};
void merl_model_data(MerlModelData& out);

/// The share of the cosine-weighted hemisphere of wi, at cos(theta_o) = mu, whose lookup (with
/// `interp`) reads an unmeasured value in table `index`: 0 where every bin the integrand reads
/// is measured. A midpoint rule of n x n cells in (cos^2 theta_i, phi_i).
double merl_unmeasured_share(int index, int interp, double mu, int n = 128);

/// The unmeasured bins a merl model reads: the table's count, and per direction mu the share of
/// the cosine-weighted hemisphere of wi that reads one (merl_unmeasured_share); the albedo reads
/// them as 0, so a share s means that the albedo leaves out that part of the hemisphere.
struct MerlUnmeasured {
    std::size_t bins = 0;
    std::vector<double> share;  // per mu
};

/// For a merl model, its unmeasured bins at the directions `mus` (true); false for other models.
bool merl_unmeasured(const ModelConfig& model, const std::vector<double>& mus, MerlUnmeasured& out);

/// The table header line of merl_unmeasured ("# unmeasured: ..."), empty for other models.
std::string merl_unmeasured_line(const ModelConfig& model, const std::vector<double>& mus);

/// Whether a model spec is merl with channel=rgb (a table's one channel per colour).
bool merl_rgb_spec(const std::string& spec);
/// Whether a model spec is merl naming no channel, or channel=rgb (a scene's tables per colour).
bool merl_per_colour(const std::string& spec);
/// The spec with its channel key set to `channel` (r, g, b or y).
std::string merl_channel_spec(const std::string& spec, const std::string& channel);

/// A merl spec read from a file at `from` (a scene): a relative file= path is made relative to
/// that file's folder; any other spec is returned as it is.
std::string merl_spec_beside(const std::string& spec, const std::string& from);

}  // namespace brdfbake

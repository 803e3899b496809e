// What the sampling integrators (the albedo's and the rough dielectric's) share: the replicas'
// Cranley-Patterson shifts, the point tables of the vector paths, and the statistics that turn
// replica means into a value and an error estimate.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"

namespace brdfbake {

/// Cranley-Patterson shifts, two per replica (u1, u2), in [0, 1).
std::vector<double> replica_shifts(unsigned replicas, std::uint64_t seed);

/// A range of each replica's points [first, first + count) of its `points`-point set.
struct PointChunk {
    std::uint64_t first = 0, count = 0;
};

/// The most points (all replicas together) one point table holds.
constexpr std::uint64_t kTablePointsMax = std::uint64_t(1) << 20;

/// The chunks in which the vector paths tabulate and integrate `points` per replica: each a
/// multiple of `lanes`, the table of one chunk (every replica's) at most kTablePointsMax points
/// (or one step of lanes per replica), so that a table's memory is bounded whatever the sample
/// count (torrance-sparrow at --tolerance 1e-7 in double asked 3.3 GB of one table).
std::vector<PointChunk> table_chunks(std::uint64_t points, unsigned replicas, unsigned lanes);

/// The vector paths' plan for `points` per replica: the lanes the engine gives `build` (1, with
/// `build` set back to the scalar kernel, where `points` is not a multiple of them: a ragged last
/// step), and the chunks their point tables are built in, one launch each (table_chunks; all
/// points in one launch on the scalar kernel).
struct VectorChunks {
    unsigned lanes = 1;
    std::vector<PointChunk> chunks;
};
VectorChunks vector_chunks(const Engine& engine, BuildRequest& build, std::uint64_t points, unsigned replicas);

/// The disk point table of the vector paths (albedo_replicas_disk, dielectric_replicas_disk):
/// per replica, per step of `lanes` points, BB_DISK_VALUES rows of lanes; the points `chunk` of
/// each replica's `points`-point set.
std::vector<double> disk_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                               unsigned lanes, Precision precision, PointChunk chunk);

/// The rotated Hammersley point table of the generic vector path (albedo_replicas_points):
/// per replica, per step of `lanes` points, BB_POINTS_VALUES rows of lanes; the points `chunk`.
std::vector<double> point_table(const std::vector<double>& shifts, unsigned replicas, std::uint64_t points,
                                unsigned lanes, Precision precision, PointChunk chunk);

/// Refuses a sample count the replicas cannot split (Error naming --samples).
void check_sampling(std::uint64_t samples, unsigned replicas);

/// What a sampling method did, in words ("importance sampling, randomised Hammersley (16
/// replicas x 4096 points)").
std::string method_text(Method method, unsigned replicas, std::uint64_t points);

/// Mean and error estimate of each cell from its replica means (`means` and the non-finite
/// counts `bad`, replicas per cell consecutive). Throws NonFiniteError, its text from
/// `where(cell)`, if any sample of a cell was non-finite.
std::vector<AlbedoValue> summarize(const std::vector<double>& means, const std::vector<cl_uint>& bad,
                                   unsigned replicas, std::uint64_t samples_per_cell, Precision precision,
                                   const std::function<std::string(size_t)>& where);

/// The replica means of a walk kernel (random_walk.cl, sheen_volume.cl): `width` numbers per item,
/// items = cells x replicas (replicas consecutive), as one summary per column and cell
/// ([column][cell], summarize's), each marked Method::MonteCarlo with `samples_per_cell`.
std::vector<std::vector<AlbedoValue>> summarize_columns(const std::vector<double>& sums, int width,
                                                        const std::vector<cl_uint>& bad, unsigned replicas,
                                                        std::uint64_t samples_per_cell, Precision precision,
                                                        const std::function<std::string(size_t)>& where);

}  // namespace brdfbake

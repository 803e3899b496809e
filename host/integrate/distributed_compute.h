// Where the cells of an integration are computed when more than one process shares a table:
// the ranks of an MPI job (engine/distributed.h) split every request's cells and gather the
// values, so that every rank holds every value and takes the same decisions (refinement rounds,
// table assembly) as one process would; a shard (`lut --shard K/N`) computes only the cells it
// owns and records them; a merge (`brdfbake merge`) replays the command with the shards' records
// instead of the device. compute_albedo and compute_dielectric ask here first.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"

namespace brdfbake {

/// A cell's identity from its content (mu, phi and the model parameters, bit for bit): the mc
/// method's Philox stream and a shard's ownership, neither of which may depend on which other
/// cells share a launch. FNV-1a, 64 bits.
std::uint64_t cell_identity(const AlbedoCell& cell);
std::uint64_t cell_identity(const DielectricCell& cell);

/// The result of `request` computed by the processes sharing it, or nothing when this process
/// computes every cell itself (one process, or a call made from inside this one).
std::optional<AlbedoResult> shared_albedo(Engine& engine, const AlbedoRequest& request);
std::optional<DielectricResult> shared_dielectric(Engine& engine, const DielectricRequest& request);

/// How the ranks of an MPI job split a request's cells: cyclic (cell c to rank c mod N, the
/// default) or block (contiguous runs). $BRDFBAKE_MPI_SPLIT=block selects the latter (for the
/// scaling benchmark, benchmarks/mpi_scaling.sh).
enum class RankSplit { Cyclic, Block };
RankSplit rank_split();

/// The recorded results of a shard: per integration call and cell, a key (the request's settings
/// and the cell) and the cell's values, packed; the method texts they refer to.
struct ShardRecords {
    std::map<std::string, std::string> cells;  // key (16 hex digits) -> packed values
    std::vector<std::string> texts;            // method texts, referred to by index
};

/// Shard K of N: from now on this process computes only the cells it owns (a mix of cell_identity, mod N)
/// and records them; the others are placeholders (0 +- 0) that make no result of their own.
void begin_shard(int index, int count);
/// The shard's records so far.
const ShardRecords& shard_records();

/// Replay: from now on every integration call is answered from `records` (the union of a
/// table's shards) without the device; a cell not in them throws Error.
void begin_replay(ShardRecords records);

}  // namespace brdfbake

#include "cli/mpi_world.h"

#include <cstdlib>

#ifdef BRDFBAKE_HAVE_MPI
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "brdfbake/error.h"
#include "engine/distributed.h"
#endif

namespace brdfbake {

#ifdef BRDFBAKE_HAVE_MPI
namespace {

// Started by an MPI launcher: Open MPI's mpirun, a PMIx launcher (Slurm's srun --mpi=pmix,
// prterun) or a PMI-2 one (srun --mpi=pmi2, MPICH's hydra). A plain run does not initialise MPI:
// it stays the one process it always was, with no MPI start-up cost.
bool launched_by_mpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(v)) return true;
    return false;
}

class MpiWorld : public dist::World {
public:
    MpiWorld() {
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }

    std::vector<std::string> allgather(const std::string& mine) override {
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<std::string> out = gather(mine);
        seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++steps_;
        for (const std::string& p : out) bytes_ += p.size();
        return out;
    }

    // $BRDFBAKE_MPI_STATS: rank 0 reports the collective steps (benchmarks/mpi_scaling.sh). The
    // time in them includes waiting for the slowest rank, so it bounds the communication share.
    void report() const {
        if (rank_ != 0 || !std::getenv("BRDFBAKE_MPI_STATS")) return;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::fprintf(stderr, "brdfbake: mpi: %d ranks, %ld steps, %.0f bytes gathered, %.3f s in steps of %.3f s\n",
                     size_, steps_, bytes_, seconds_, wall);
    }

private:
    std::vector<std::string> gather(const std::string& mine) {
        if (mine.size() > size_t(INT32_MAX)) throw Error("a rank's share of the results exceeds 2 GiB; use more ranks");
        const int length = int(mine.size());
        std::vector<int> lengths(static_cast<size_t>(size_)), offsets(static_cast<size_t>(size_));
        MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD);
        long long total = 0;
        for (int r = 0; r < size_; ++r) {
            offsets[size_t(r)] = int(total);
            total += lengths[size_t(r)];
        }
        if (total > INT32_MAX) throw Error("the ranks' results exceed 2 GiB in one step; use fewer cells per launch");
        std::string all(size_t(total), '\0');
        MPI_Allgatherv(mine.data(), length, MPI_BYTE, all.data(), lengths.data(), offsets.data(), MPI_BYTE,
                       MPI_COMM_WORLD);
        std::vector<std::string> out;
        for (int r = 0; r < size_; ++r) out.push_back(all.substr(size_t(offsets[size_t(r)]), size_t(lengths[size_t(r)])));
        return out;
    }

    int rank_ = 0, size_ = 1;
    long steps_ = 0;
    double bytes_ = 0.0, seconds_ = 0.0;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

std::unique_ptr<MpiWorld> g_world;

}  // namespace

MpiSession::MpiSession() {
    if (!launched_by_mpi()) return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    initialised_ = true;
    g_world = std::make_unique<MpiWorld>();
    dist::set_world(g_world.get());
}

MpiSession::~MpiSession() {
    if (!initialised_) return;
    g_world->report();
    dist::set_world(nullptr);
    g_world.reset();
    MPI_Finalize();
}

bool mpi_built() { return true; }

#else

MpiSession::MpiSession() {}
MpiSession::~MpiSession() {}
bool mpi_built() { return false; }

#endif

}  // namespace brdfbake

#include "cli/mpi_world.h"

#include <cstdlib>

#ifdef BRDFBAKE_HAVE_MPI
#include <mpi.h>

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
        if (mine.size() > size_t(INT32_MAX)) throw Error("a rank's share of the results exceeds 2 GiB; use more ranks");
        const int length = int(mine.size());
        std::vector<int> lengths(size_t(size_)), offsets(size_t(size_));
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

private:
    int rank_ = 0, size_ = 1;
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

// The MPI job this process belongs to, if an MPI launcher started it (mpirun, mpiexec, srun):
// MPI is initialised and the core's World installed (engine/distributed.h) for the lifetime of
// the session; otherwise, or in a build without MPI (BRDFBAKE_HAVE_MPI undefined), nothing.
#pragma once

namespace brdfbake {

class MpiSession {
public:
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

private:
    bool initialised_ = false;
};

/// Whether this build can run as an MPI job.
bool mpi_built();

}  // namespace brdfbake

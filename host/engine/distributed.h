// Several processes computing one result: the ranks of an MPI job, or one process (the default).
// The core never calls MPI: it talks to a World, which the command line installs when it was
// started by an MPI launcher (host/cli/mpi_world.cpp). Every function here is a no-op, or the
// one-process answer, without a World.
//
// The ranks take the same path through a command and meet at collective steps (exchange). A
// rank that fails joins the next step with its error instead of its data (report_failure), and
// every rank then throws JobFailure there: the job ends on all ranks, with the first failing
// rank's message, and nothing is written (output files commit only after agree()).
#pragma once

#include <exception>
#include <string>
#include <vector>

#include "brdfbake/error.h"

namespace brdfbake::dist {

/// The processes of a job and the one collective operation the core needs.
class World {
public:
    virtual ~World() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    /// Every rank contributes `mine`; returns every rank's contribution, in rank order.
    virtual std::vector<std::string> allgather(const std::string& mine) = 0;
};

/// Installs the job's World (nullptr: one process). The caller keeps it alive while installed.
void set_world(World* world);

int rank();       // 0 without a World
int size();       // 1 without a World
bool active();    // more than one rank
bool is_writer(); // the rank that writes outputs and prints results: rank 0

/// Thrown on every rank at the collective step where some rank's failure became known; its
/// message is that of the first failing rank (prefixed with the rank when not all ranks failed).
class JobFailure : public Error {
public:
    using Error::Error;
};

/// One collective step: contributes `payload`, returns every rank's payload in rank order.
/// Throws JobFailure on every rank if any rank reported a failure instead.
std::vector<std::string> exchange(const std::string& payload);

/// A collective step that carries nothing: returns only if no rank has failed.
void agree();

/// The error a failed command reports, for any exception (brdfbake::Error as is; an OpenCL call,
/// host memory, others in words): what main prints, and what a rank sends the others.
Error describe_failure(std::exception_ptr failure);

/// For a rank whose command failed outside a collective step: joins the next step with its
/// error, so that the other ranks end there too, and returns the job's error (the first failing
/// rank's message and exit status). One process, or after a JobFailure: returns `failure` as is.
Error report_failure(const Error& failure);

}  // namespace brdfbake::dist

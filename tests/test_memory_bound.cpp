// Memory bounds of the sampling integrators: the vector paths' point tables are built and
// integrated in chunks of at most kTablePointsMax points (host/integrate/replicas.h), so that a
// large sample count does not allocate a table of its size (torrance-sparrow at --tolerance 1e-7
// in double asked 3.33 GB of one table before).
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cmath>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "integrate/replicas.h"
#include "model_refs.h"
#include "support.h"

extern char** environ;

using namespace brdfbake;

namespace {

// Runs the command line `args` (no shell) and returns its exit status and peak resident memory in bytes.
std::pair<int, double> run_measured(std::vector<std::string> args) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return {-1, 0.0};
    int status = 0;
    struct rusage usage {};
    if (wait4(pid, &status, 0, &usage) != pid) return {-1, 0.0};
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, double(usage.ru_maxrss) * 1024.0};
}

}  // namespace

TEST_CASE("point tables: chunks cover every point once, each a multiple of the lanes, at most 2^20 points",
          "[memory][quick]") {
    for (unsigned replicas : {2u, 16u, 64u})
        for (unsigned lanes : {1u, 4u, 8u})
            for (std::uint64_t points : {std::uint64_t(8), std::uint64_t(1) << 16, (std::uint64_t(1) << 26) + 8 * 3}) {
                const std::vector<PointChunk> chunks = table_chunks(points, replicas, lanes);
                std::uint64_t next = 0;
                for (const PointChunk& c : chunks) {
                    INFO("replicas " << replicas << " lanes " << lanes << " points " << points << ": chunk [" << c.first
                                     << ", +" << c.count << ")");
                    CHECK(c.first == next);
                    CHECK(c.count > 0);
                    CHECK(c.count * replicas <= std::max<std::uint64_t>(kTablePointsMax, std::uint64_t(lanes) * replicas));
                    if (points % lanes == 0) CHECK(c.count % lanes == 0);
                    next = c.first + c.count;
                }
                CHECK(next == points);
            }
}

TEST_CASE("chunked point tables: the albedo from several chunks agrees with independent quadrature",
          "[memory][device]") {
    // 2^23 samples in 16 replicas: 8 chunks of the table. GGX takes the disk table, torrance-sparrow
    // the Hammersley point table; the references are Boost.Math quadrature (model_refs.h).
    const std::vector<double> mus = {0.2, 1.0};
    for (const modelref::Case& c : {modelref::ggx(0.3, true, 1e-10), modelref::torrance_sparrow(ref::Dist::Beckmann, 0.3)}) {
        const AlbedoRequest req = testing::albedo_request(c.spec, mus, Method::Importance, Precision::Double, 1u << 23);
        const AlbedoResult r = compute_albedo(testing::engine(), req);
        for (size_t i = 0; i < mus.size(); ++i) {
            const double want = c.albedo(mus[i]);
            INFO(c.spec << " mu " << mus[i] << ": " << r.values[i].value << " +- " << r.values[i].error << " (vector width "
                        << r.vector_width << "), reference " << want);
            CHECK(std::fabs(r.values[i].value - want) <= r.values[i].error + 1e-7);  // + the reference's own
            CHECK(r.values[i].error < 1e-4);  // the comparison has teeth
        }
    }
}

TEST_CASE("a sample count whose table would take 1 GiB runs in bounded memory", "[memory][device]") {
    // 2^26 samples: one table of every point would be 2^26 x 2 doubles = 1 GiB (and its device
    // copy as much again); in chunks the process stays far below that.
    const auto [status, peak] = run_measured({BRDFBAKE_EXE, "albedo", "--model", "torrance-sparrow:d=beckmann,alpha=0.3",
                                              "--mu", "0.5", "--method", "importance", "--samples", "2^26",
                                              "--precision", "double"});
    INFO("exit status " << status << ", peak resident memory " << peak / 1e6 << " MB");
    CHECK(status == 0);
    CHECK(peak < 600e6);
}

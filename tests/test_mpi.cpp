// MPI jobs (docs/cluster.md): `mpirun -np N brdfbake ...` writes the files one process writes,
// byte for byte, and a rank that fails ends the job with one error and no file. Built only when
// CMake found MPI (BRDFBAKE_MPIEXEC is its launcher). Every rank runs PoCL on one thread
// (POCL_MAX_PTHREAD_COUNT=1), oversubscribed on the two cores of CI.
#include <catch2/catch.hpp>

#ifdef BRDFBAKE_MPIEXEC

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include "support.h"

using testing::run_cli;
using testing::slurp;

namespace {

std::string mpi_path(const std::string& name) { return "/tmp/brdfbake-mpi-" + std::to_string(::getpid()) + "-" + name; }

bool exists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

// Runs `COMMAND` (a shell word list starting with the program) under mpirun with `ranks` ranks;
// Open MPI refuses root without these variables, which a CI container usually is.
testing::CliResult run_mpi(int ranks, const std::string& command) {
    return testing::run_shell("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                              "POCL_MAX_PTHREAD_COUNT=1 timeout 120 " BRDFBAKE_MPIEXEC " -q --oversubscribe -np " +
                              std::to_string(ranks) + " " + command);
}

// `lut ARGS` in one process and with 2 and 3 ranks: the same bytes.
void check_ranks_reproduce(const std::string& args, const std::string& name) {
    const std::string one = mpi_path(name + "-1.exr");
    REQUIRE(run_cli("lut " + args + " --no-preview -q -o " + one).status == 0);
    const std::string reference = slurp(one);
    REQUIRE(!reference.empty());
    for (int ranks : {2, 3}) {
        const std::string many = mpi_path(name + "-" + std::to_string(ranks) + ".exr");
        const auto r = run_mpi(ranks, std::string(BRDFBAKE_EXE) + " lut " + args + " --no-preview -q -o " + many);
        INFO(ranks << " ranks: " << r.err);
        REQUIRE(r.status == 0);
        CHECK(slurp(many) == reference);
        std::remove(many.c_str());
    }
    std::remove(one.c_str());
}

}  // namespace

TEST_CASE("mpirun -np 2 and -np 3 write the one-process table byte for byte", "[mpi][device]") {
    SECTION("fixed sample count") { check_ranks_reproduce("albedo --model ggx --size 8x4 --samples 4096", "fixed"); }
    SECTION("tolerance mode: rounds of quadrature and importance sampling") {
        check_ranks_reproduce("albedo --model torrance-sparrow --size 6x3 --tolerance 1e-3 --max-samples 262144",
                              "tolerance");
    }
    SECTION("3D dielectric table") { check_ranks_reproduce("dielectric --model ggx --size 4x3x3 --samples 1024", "dielectric"); }
}

// The bake folder's lock is taken by rank 0 only (host/scene/bake_folder.cpp): otherwise rank 1
// would wait for rank 0's lock while rank 0 waits for rank 1's cells.
TEST_CASE("mpirun -np 2 bakes a scene into the files one process writes", "[mpi][device][bake]") {
    const std::string one = mpi_path("bake-1"), two = mpi_path("bake-2");
    const std::string scene = std::string(BRDFBAKE_SOURCE_DIR) + "/tests/data/small_bake.json";
    REQUIRE(run_cli("bake " + scene + " -q -o " + one).status == 0);
    const auto r = run_mpi(2, std::string(BRDFBAKE_EXE) + " bake " + scene + " -q -o " + two);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(slurp(one + "/index.json").size() > 0);
    // Every table of the one-process folder byte for byte, and its index but for the seconds
    // each table took to compute (a measurement, not a result).
    const std::string diff = "diff -r -x index.json -x index.html " + one + " " + two + " >/dev/null";
    CHECK(std::system(diff.c_str()) == 0);
    auto without_seconds = [](const std::string& text) {
        std::istringstream in(text);
        std::string line, kept;
        while (std::getline(in, line))
            if (line.find("\"seconds\"") == std::string::npos) kept += line + "\n";
        return kept;
    };
    CHECK(without_seconds(slurp(one + "/index.json")) == without_seconds(slurp(two + "/index.json")));
    std::system(("rm -rf " + one + " " + two).c_str());
}

TEST_CASE("a rank that fails ends the whole job: one error line, non-zero exit, no file", "[mpi][device]") {
    // Rank 1 cannot read the n,k file that rank 0 reads under the same relative path (each rank
    // starts in its own folder, as a file on a node's local disk may be missing on another): the
    // ranks run one command (they compare their command lines first), and fail by their files.
    const std::string good = std::string(BRDFBAKE_SOURCE_DIR) + "/data/nk/Au-Johnson.yml", script = mpi_path("rank.sh"),
                      out = mpi_path("fail.exr");
    ::mkdir(mpi_path("rank0").c_str(), 0700);
    ::mkdir(mpi_path("rank1").c_str(), 0700);
    ::mkdir(mpi_path("rank2").c_str(), 0700);
    std::ofstream(mpi_path("rank0") + "/metal.yml") << slurp(good);
    std::ofstream(mpi_path("rank2") + "/metal.yml") << slurp(good);
    {
        std::ofstream f(script);
        f << "#!/bin/sh\ncd " << mpi_path("rank") << "$OMPI_COMM_WORLD_RANK || exit 3\nexec " << BRDFBAKE_EXE
          << " lut albedo --model ggx --fresnel nk:metal.yml --wavelength 600 --size 6x3 "
          << "--samples 1024 --no-preview -q -o " << out << "\n";
    }
    ::chmod(script.c_str(), 0755);
    REQUIRE(run_cli("lut albedo --model ggx --fresnel nk:" + good +
                    " --wavelength 600 --size 6x3 --samples 1024 --no-preview -q -o " + out)
                .status == 0);  // the command itself is good
    std::remove(out.c_str());
    for (int ranks : {2, 3}) {
        const auto r = run_mpi(ranks, script);
        INFO(r.err);
        CHECK(r.status != 0);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error: rank 1 of " + std::to_string(ranks) + ": ", 0) == 0);
        CHECK(r.err.find("metal.yml") != std::string::npos);
        CHECK(!exists(out));
    }
    std::remove(script.c_str());
    std::system(("rm -rf " + mpi_path("rank0") + " " + mpi_path("rank1") + " " + mpi_path("rank2")).c_str());
}

TEST_CASE("ranks given different arguments end the job before any work", "[mpi][device]") {
    // Rank 1 is started with another --samples (a per-rank wrapper gone wrong): its cells would
    // be mixed into rank 0's table. The ranks compare their commands first.
    const std::string script = mpi_path("samples.sh"), out = mpi_path("mixed.exr");
    {
        std::ofstream f(script);
        f << "#!/bin/sh\nif [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then n=2048; else n=1024; fi\nexec " << BRDFBAKE_EXE
          << " lut albedo --model ggx --size 6x3 --samples $n --no-preview -q -o " << out << "\n";
    }
    ::chmod(script.c_str(), 0755);
    const auto r = run_mpi(2, script);
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(r.err.find("must run one command: rank 1 of 2 has '2048' where rank 0 has '1024'") != std::string::npos);
    CHECK(!exists(out));
    std::remove(script.c_str());
}

#endif  // BRDFBAKE_MPIEXEC

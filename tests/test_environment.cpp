// Hostile environments (issue 16, item 9): an unusable PoCL kernel cache folder and a low address
// space limit stop a run with one line that names the cause, exit status 2, no signal, and no
// folder left behind by `bake`.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <thread>

#include "support.h"

namespace {

struct Run {
    bool exited = false;
    int status = -1;
    std::string err;
};

/// Runs `SETUP brdfbake ARGS` through the shell: SETUP sets variables (`env ...`) or limits
/// (`ulimit -v N;`), so it has to come before the executable.
Run run_in(const std::string& setup, const std::string& args) {
    static int counter = 0;
    const std::string err = "/tmp/brdfbake-env-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".err";
    const std::string cmd = "sh -c '" + setup + " exec " + BRDFBAKE_EXE + " " + args + "' >/dev/null 2>" + err;
    const int raw = std::system(cmd.c_str());
    Run r;
    // sh -c with exec: the status is brdfbake's; a signal shows as 128 + N from a wrapping shell.
    r.exited = WIFEXITED(raw) && WEXITSTATUS(raw) < 128;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.err = testing::slurp(err);
    std::remove(err.c_str());
    return r;
}

const char* kAlbedo = "albedo --model ggx:alpha=0.5 --mu 0.5 --samples 4096";

std::string scene() {
    const std::string here = __FILE__;
    return here.substr(0, here.find_last_of('/')) + "/data/small_bake.json";
}

std::string scratch(const std::string& name) {
    const std::string dir = "/tmp/brdfbake-env-" + std::to_string(::getpid()) + "-" + name;
    std::system(("rm -rf " + dir).c_str());
    return dir;
}

void check_one_line_exit_2(const Run& r, const std::string& must_mention) {
    INFO(r.err);
    CHECK(r.exited);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(r.err.find(must_mention) != std::string::npos);
}

}  // namespace

TEST_CASE("an unusable PoCL kernel cache folder is named as the cause", "[environment]") {
    // Before: "OpenCL platforms were found but no device: is /sys mounted ...?"
    check_one_line_exit_2(run_in("POCL_CACHE_DIR=/etc/passwd/x", kAlbedo),
                          "PoCL's kernel cache folder '/etc/passwd/x' (from $POCL_CACHE_DIR) cannot be created: "
                          "'/etc/passwd' is not a folder");
    // No POCL_CACHE_DIR, no XDG_CACHE_HOME: PoCL uses $HOME/.cache/pocl/kcache.
    check_one_line_exit_2(run_in("unset POCL_CACHE_DIR XDG_CACHE_HOME; HOME=/etc/passwd", kAlbedo), "(from $HOME)");
    // Set but empty: PoCL 3.1 fails an assertion (SIGABRT) on it.
    check_one_line_exit_2(run_in("POCL_CACHE_DIR=", kAlbedo), "POCL_CACHE_DIR is set but empty");
}

TEST_CASE("an address space limit too low for PoCL is named as the cause", "[environment]") {
    // Before: CL_PLATFORM_NOT_FOUND_KHR at 200000 KiB; an abort in PoCL's thread creation or a
    // deadlock in its compiler at other limits below about 490 MiB.
    const Run r = run_in("ulimit -v 200000;", kAlbedo);
    check_one_line_exit_2(r, "out of memory: the address space limit (ulimit -v) is 195 MiB");
    CHECK(r.err.find("raise the limit") != std::string::npos);
    // The minimum it names is enough: a limit just above it runs (a cold kernel build included).
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    const unsigned long enough_kib = (512ul + 80ul * threads + 32ul) * 1024ul;
    const Run ok = run_in("ulimit -v " + std::to_string(enough_kib) + "; POCL_KERNEL_CACHE=0", kAlbedo);
    INFO(ok.err);
    CHECK(ok.status == 0);
}

TEST_CASE("a bake that fails for its environment leaves no output folder", "[environment]") {
    const std::string top = scratch("bake");
    const std::string out = top + "/out";
    for (const std::string& setup : {std::string("POCL_CACHE_DIR=/etc/passwd/x"), std::string("ulimit -v 200000;")}) {
        INFO(setup);
        const Run r = run_in(setup, "bake " + scene() + " -o " + out);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(::access(top.c_str(), F_OK) != 0);
    }
}

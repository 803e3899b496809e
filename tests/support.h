// Test support: one shared OpenCL engine, and running the brdfbake executable.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "brdfbake/albedo.h"
#include "brdfbake/engine.h"
#include "brdfbake/spec.h"

namespace testing {

/// The engine every device test shares (PoCL, or $BRDFBAKE_DEVICE).
inline brdfbake::Engine& engine() {
    static brdfbake::Engine e;
    return e;
}

struct CliResult {
    int status = -1;
    std::string out;
    std::string err;
};

/// An albedo request for a model spec at the given mu (phi = 0), Fresnel none.
inline brdfbake::AlbedoRequest albedo_request(const std::string& spec, const std::vector<double>& mus,
                                              brdfbake::Method method, brdfbake::Precision p,
                                              std::uint64_t samples) {
    const brdfbake::ModelConfig m = brdfbake::resolve_model(spec);
    brdfbake::AlbedoRequest req;
    req.model = m.id;
    req.fresnel = brdfbake::resolve_fresnel("none");
    req.cells = brdfbake::cells_for(mus, 0.0, m.params);
    req.method = method;
    req.precision = p;
    req.samples = samples;
    return req;
}

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Runs a shell command line; returns its exit status, stdout and stderr.
inline CliResult run_shell(const std::string& command) {
    static int counter = 0;
    const std::string base = "/tmp/brdfbake-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const std::string cmd = command + " >" + base + ".out 2>" + base + ".err";
    const int raw = std::system(cmd.c_str());
    CliResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(base + ".out");
    r.err = slurp(base + ".err");
    std::remove((base + ".out").c_str());
    std::remove((base + ".err").c_str());
    return r;
}

/// Runs `brdfbake ARGS` through the shell; returns its exit status, stdout and stderr.
inline CliResult run_cli(const std::string& args) { return run_shell(std::string(BRDFBAKE_EXE) + " " + args); }

/// Number of lines in a string (for "one clear message").
inline int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

}  // namespace testing

// Checks that many tests share, written once: the project's rule for bad input (exit status 2,
// one line `brdfbake: error: ...`, nothing written), a table request by kind, model and --size,
// and the float importance-sampled rerun of a refined table.
#pragma once

#include <catch2/catch.hpp>

#include <cstdint>
#include <fstream>
#include <string>

#include "brdfbake/lut.h"
#include "brdfbake/table.h"
#include "support.h"

namespace testing {

/// An axis whose parameter is its coordinate (synthetic test tables: the value names the texel).
inline brdfbake::Axis identity_axis(const std::string& name, const std::string& mapping, double lo, double hi, int n) {
    brdfbake::Axis a = brdfbake::make_axis(name, mapping, lo, hi, n);
    a.parameter = a.coordinate;
    return a;
}

/// One bad command line and a piece of the one-line message it must give.
struct BadInput {
    const char* args;
    const char* must_mention;
};

/// The rule for bad input: exit status 2 and one line `brdfbake: error: ...` on stderr.
inline void check_usage_error(const CliResult& r) {
    INFO("stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
}

/// `brdfbake ARGS OUT` refused as bad input, with nothing written at OUT.
inline void check_refused(const std::string& args, const std::string& out) {
    INFO(args << out);
    const CliResult r = run_cli(args + out);
    check_usage_error(r);
    CHECK_FALSE(std::ifstream(out).good());
}

/// A table request: `kind` of `model`, width x height texels (x depth for an eta axis; the
/// request's default depth when not given).
inline brdfbake::LutRequest lut_request(const std::string& kind, const std::string& model, int width, int height,
                                       int depth = brdfbake::LutRequest{}.depth) {
    brdfbake::LutRequest r;
    r.kind = kind;
    r.model = model;
    r.width = width;
    r.height = height;
    r.depth = depth;
    return r;
}

/// The table of `r` again in float by importance sampling at `samples` per cell (no tolerance):
/// an independent estimate of a refined table, with its own error.
inline brdfbake::Table float_sampled_table(const brdfbake::LutRequest& r, std::uint64_t samples) {
    brdfbake::LutRequest rf = r;
    rf.precision = brdfbake::Precision::Float;
    rf.tolerance.tolerance = 0.0;
    rf.samples = samples;
    return brdfbake::compute_lut(engine(), rf);
}

}  // namespace testing

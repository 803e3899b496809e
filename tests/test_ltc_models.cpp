// The ltc table of the isotropic models without an alpha (issue 33 item 1): oren-nayar, phong and
// blinn-phong, whose roughness axis the model registry maps (RoughnessAxis in brdfbake/spec.h:
// sigma = alpha, n = 2/alpha^2 - 2). Each family's small table is checked texel by texel by the
// independent numpy reference (tests/ltc_reference.py, check_model_table: the closed forms of
// Oren and Nayar 1994, Lewis 1994 and Blinn 1977 at the key the mapping gives, their albedo by
// their own samplers and the L1 distance of the stored M by multiple importance sampling), so a
// wrong mapping, magnitude or distance fails. Refusals: the key the axis drives given in --model,
// an --alpha-range beyond the mapping, a model without roughness.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

#include "support.h"

namespace {

/// The directory of tests/ltc_reference.py (this file's own). __FILE__ is as the compiler was
/// given it: absolute, or relative to the build directory it ran in, where BRDFBAKE_EXE lies.
std::string tests_dir() {
    const std::string f = __FILE__, exe = BRDFBAKE_EXE;
    const std::string dir = f.substr(0, f.find_last_of('/'));
    return dir.front() == '/' ? dir : exe.substr(0, exe.find_last_of('/')) + "/" + dir;
}

bool have_numpy() { return std::system("/usr/bin/python3 -c 'import numpy' >/dev/null 2>&1") == 0; }

/// `lut ltc --model MODEL`, 3 x 2 centre texels (mu 1/6, 1/2, 5/6; two alphas of RANGE), its
/// header stating the mapping AXIS, checked texel by texel by the numpy reference.
void check_family(const std::string& model, const std::string& range, const std::string& axis) {
    REQUIRE(have_numpy());
    const std::string csv = "/tmp/ltc_models_" + std::to_string(::getpid()) + ".csv";
    const testing::CliResult run = testing::run_cli("lut ltc --model " + model + " --size 3x2 --texels centre --alpha-range " +
                                                    range + " --no-preview -o " + csv);
    INFO(model << ": " << run.err);
    REQUIRE(run.status == 0);
    const std::string text = testing::slurp(csv);
    CHECK(text.find("roughness_axis: alpha sets ") != std::string::npos);
    CHECK(text.find(axis) != std::string::npos);
    CHECK(text.find("fresnel_channel: the magnitude") != std::string::npos);
    const testing::CliResult ref = testing::run_shell(
        "/usr/bin/python3 -c \"import sys; sys.path.insert(0, '" + tests_dir() +
        "'); import ltc_reference as r; sys.exit(1 if r.check_model_table('" + csv + "') else 0)\"");
    INFO(ref.out << ref.err);
    CHECK(ref.status == 0);
    std::remove(csv.c_str());
}

}  // namespace

// Measured (amd-epyc-2c, load ~20): each case 15-17 s for the table (mostly the kernel's build),
// 6-8 s for the reference.
TEST_CASE("ltc models: an oren-nayar table against the numpy closed form", "[ltc][lut][models]") {
    check_family("oren-nayar", "0.3,1.3", "sigma = alpha");
}

TEST_CASE("ltc models: a normalised phong table against the numpy closed form", "[ltc][lut][models]") {
    check_family("phong:normalized=1", "0.25,0.7", "n = 2/alpha^2 - 2");
}

TEST_CASE("ltc models: a blinn-phong table against the numpy closed form", "[ltc][lut][models]") {
    check_family("blinn-phong", "0.25,0.7", "n = 2/alpha^2 - 2");
}

TEST_CASE("ltc models: the numpy closed forms' own checks", "[ltc][models][quick]") {
    REQUIRE(have_numpy());
    // Oren-Nayar at sigma 0 is Lambert, the normalised Phong lobe integrates to 1 at normal
    // incidence, and each model's sampler-based E and L1 agree with a plain solid-angle grid.
    const testing::CliResult ref = testing::run_shell(
        "/usr/bin/python3 -c \"import sys; sys.path.insert(0, '" + tests_dir() +
        "'); import ltc_reference as r; sys.exit(1 if r.model_self_checks() else 0)\"");
    INFO(ref.out << ref.err);
    CHECK(ref.status == 0);
}

TEST_CASE("ltc models: the mapped key in --model, an alpha beyond the mapping, no roughness: one line", "[ltc][cli][models]") {
    for (const char* args : {"--model phong:n=10", "--model oren-nayar:sigma=0.2", "--model phong --alpha-range 0,1.2",
                             "--model oren-nayar --alpha-range 0,2", "--model blinn-phong --alpha-map roughness --alpha-range 0,1.1",
                             "--model lambert"}) {
        const testing::CliResult res = testing::run_cli(std::string("lut ltc ") + args + " --size 4x4 -o /tmp/ltc_models_refused.exr");
        INFO(args << ": " << res.err);
        CHECK(res.status == 2);
        CHECK(testing::count_lines(res.err) == 1);
        CHECK(res.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(testing::run_shell("test -e /tmp/ltc_models_refused.exr").status != 0);
    }
}

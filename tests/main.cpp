// Catch2 v2 test runner. Tags: [quick] host-only math, [device] needs an OpenCL device (PoCL),
// [cli] runs the brdfbake executable, [slow] long numerical references.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>

int main(int argc, char* argv[]) {
    // The tests neither read nor write the user's calibration of estimates (docs/scenes.md,
    // "Estimates"): the commands they run estimate from the built-in figures unless a test says
    // otherwise (tests/test_plan_calibration.cpp).
    ::setenv("BRDFBAKE_CALIBRATION", "off", 0);
    return Catch::Session().run(argc, argv);
}

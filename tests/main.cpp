// Catch2 v2 test runner. Tags: [quick] host-only math, [device] needs an OpenCL device (PoCL),
// [cli] runs the brdfbake executable, [slow] long numerical references.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

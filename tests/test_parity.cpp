// Host vs device parity: the same shared headers evaluated in double on the host and in a PoCL
// kernel in float and double.
#include <catch2/catch.hpp>

#include "parity.h"

using namespace brdfbake;

namespace {

void check_parity(const std::string& spec) { testing::check_host_device_parity(resolve_model(spec), spec, 4000); }

}  // namespace

TEST_CASE("Lambert: host and device agree", "[parity][device]") { check_parity("lambert:rho=0.7"); }

TEST_CASE("GGX: host and device agree", "[parity][device]") {
    check_parity("ggx:alpha=0.3");
    check_parity("ggx:alpha=0.3,shadowing=separable");
    check_parity("ggx:alpha_x=0.05,alpha_y=0.8");
}

// Every model of issue 3. The Phong-type exponents stay moderate here: at N = 1e4 float's own
// rounding of the directions (1e-7) changes cos^N by N * 1e-7 relative, more than the 2e-4
// tolerance; test_models_device.cpp checks that such lobes stay finite and non-negative.
TEST_CASE("Oren-Nayar: host and device agree", "[parity][device][models]") {
    check_parity("oren-nayar:sigma=0.5,rho=0.8");
    check_parity("oren-nayar:sigma=0");
}

TEST_CASE("Phong and Blinn-Phong: host and device agree", "[parity][device][models]") {
    check_parity("phong:n=20");
    check_parity("phong:n=50,ks=0.5,normalized=1");
    check_parity("phong-original:n=20");
    check_parity("blinn-phong:n=20,normalized=1");
    check_parity("blinn-phong:n=0");
}

TEST_CASE("Torrance-Sparrow: host and device agree", "[parity][device][models]") {
    check_parity("torrance-sparrow:d=blinn,n=30");
    check_parity("torrance-sparrow:d=beckmann,alpha=0.3");
    check_parity("torrance-sparrow:d=ggx,alpha=0.3");
    check_parity("torrance-sparrow:d=ggx,alpha_x=0.1,alpha_y=0.5");
}

TEST_CASE("Beckmann: host and device agree", "[parity][device][models]") {
    check_parity("beckmann:alpha=0.3");
    check_parity("beckmann:alpha=0.3,shadowing=separable");
    check_parity("beckmann:alpha_x=0.05,alpha_y=0.8");
    check_parity("beckmann:alpha=1");
}

TEST_CASE("Delta lobes: host and device agree", "[parity][device][models]") {
    check_parity("mirror");
    check_parity("dielectric-specular:eta=1.5");
    check_parity("dielectric-specular:eta=0.6667");
}

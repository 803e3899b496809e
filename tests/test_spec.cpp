// Spec parsing and the model registry (host only).
#include <catch2/catch.hpp>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "spec_checks.h"

using namespace brdfbake;

TEST_CASE("specs split into name and keys", "[spec][quick]") {
    const Spec s = parse_spec("ggx:alpha=0.5,shadowing=separable");
    CHECK(s.name == "ggx");
    REQUIRE(s.keys.size() == 2);
    CHECK(s.keys[1].first == "shadowing");
    CHECK(s.keys[1].second == "separable");
    CHECK(parse_spec("mirror").keys.empty());
    CHECK_THROWS_AS(parse_spec("ggx:alpha"), Error);
    CHECK_THROWS_AS(parse_spec("ggx:alpha=1,,"), Error);
    CHECK_THROWS_AS(parse_spec("ggx:alpha=1,alpha=2"), Error);
    CHECK_THROWS_AS(parse_spec(":alpha=1"), Error);
}

TEST_CASE("model specs resolve to parameter slots", "[spec][quick]") {
    const ModelConfig g = testing::check_resolves("ggx:roughness=0.5", BB_MODEL_GGX,
                                                  {{BB_GGX_ALPHA_X, 0.25}, {BB_GGX_ALPHA_Y, 0.25}, {BB_GGX_SHADOWING, 1.0}},
                                                  "ggx:alpha=0.25,shadowing=correlated");
    CHECK_FALSE(g.anisotropic);
    const ModelConfig a = resolve_model("ggx:alpha_x=0.1,alpha_y=0.3,shadowing=separable");
    CHECK(a.anisotropic);
    CHECK(a.params[BB_GGX_SHADOWING] == 0.0);
    CHECK(resolve_model("lambert").params[BB_LAMBERT_RHO] == 1.0);
}

TEST_CASE("bad model specs are refused", "[spec][quick]") {
    CHECK_THROWS_AS(resolve_model("ggx:alpha=0"), Error);
    CHECK_THROWS_AS(resolve_model("ggx:alpha=1e-5"), Error);  // below the documented floor
    CHECK_THROWS_AS(resolve_model("ggx:alpha=0.5,alpha_x=0.2"), Error);
    CHECK_THROWS_AS(resolve_model("ggx:alpha=0.5,roughness=0.2"), Error);
    CHECK_THROWS_AS(resolve_model("ggx:alpha_x=0.5"), Error);
    CHECK_THROWS_AS(resolve_model("lambert:rho=-1"), Error);
    CHECK_THROWS_AS(resolve_model("lambert:rho=0x1p-3junk"), Error);
    CHECK_THROWS_AS(resolve_model("nonsense"), Error);
}

// Spec parsing and the model registry (host only).
#include <catch2/catch.hpp>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
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

TEST_CASE("a mistyped key, model, Fresnel term or table kind is named with the nearest valid one", "[spec][quick]") {
    // The unknown key is the mistake, not the alpha it hid (before: "needs alpha=VALUE").
    CHECK_THROWS_WITH(resolve_model("ggx:alpah=0.5"), "model 'ggx' has no key 'alpah'; did you mean 'alpha'?");
    CHECK_THROWS_WITH(resolve_model("ggx:alpha=0.5,shadwing=masking"),
                      "model 'ggx' has no key 'shadwing'; did you mean 'shadowing'?");
    CHECK_THROWS_WITH(resolve_model("sheen:rougness=0.5"), "model 'sheen' has no key 'rougness'; did you mean 'roughness'?");
    // Nothing near: the keys the model reads, every one of them.
    try {
        resolve_model("ggx:alpha=0.5,zzz=1");
        FAIL("accepted an unknown key");
    } catch (const Error& e) {
        const std::string m = e.what();
        CHECK(m.rfind("model 'ggx' has no key 'zzz'; its keys: ", 0) == 0);
        for (const char* key : {"alpha", "roughness", "alpha_x", "alpha_y", "shadowing", "transmission_shadowing"})
            CHECK(m.find(key) != std::string::npos);
    }
    CHECK_THROWS_WITH(resolve_model("mirror:eta=1.5"), "model 'mirror' has no key 'eta'; it takes no keys");
    // A missing key alone is still named as missing.
    CHECK_THROWS_WITH(resolve_model("ggx:shadowing=masking"),
                      "model 'ggx' needs alpha=VALUE (or roughness=R with alpha = R^2)");
    CHECK_THROWS_WITH(resolve_model("gxx:alpha=0.5"), Catch::StartsWith("unknown model 'gxx'; did you mean 'ggx'? Known models: "));
    CHECK_THROWS_WITH(resolve_model("frobnicate"), Catch::StartsWith("unknown model 'frobnicate'; known models: "));
    CHECK_THROWS_WITH(resolve_fresnel("schlik:f0=0.04", 0.0),
                      Catch::StartsWith("unknown Fresnel term 'schlik'; did you mean 'schlick'? Known: "));
    CHECK_THROWS_WITH(resolve_fresnel("schlick:fo=0.04", 0.0), "Fresnel 'schlick' has no key 'fo'; did you mean 'f0'?");
    CHECK_THROWS_WITH(table_kind("dielectrc"),
                      Catch::StartsWith("unknown table kind 'dielectrc'; did you mean 'dielectric'? Known: "));
}

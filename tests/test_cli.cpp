// The command line as a user meets it: JSON output parsed and checked, bad input rejected with
// one clear message and exit status 2, nothing half-written left behind.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "reference/reference.h"
#include "checks.h"
#include "support.h"

using testing::run_cli;

TEST_CASE("albedo --format json: ggx alpha=0.5 at mu=0.5 against quadrature", "[cli]") {
    const auto r = run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --format json");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j.at("results").size() == 1);
    const auto& e = j["results"][0];
    const double expect = ref::albedo_halfvector(
        [](ref::Dir wo, ref::Dir wi) { return ref::ggx_f(wo, wi, 0.5, 0.5, true); }, 0.5, 0.0);
    const double got = e.at("albedo").get<double>(), err = e.at("error").get<double>();
    INFO("got " << got << " +- " << err << ", expected " << expect);
    CHECK(e.at("mu").get<double>() == 0.5);
    CHECK(std::fabs(got - expect) <= 1e-4);
    CHECK(std::fabs(got - expect) <= err);
    CHECK(j.at("model").get<std::string>() == "ggx:alpha=0.5,shadowing=correlated");
}

TEST_CASE("albedo --format json: lambert rho=0.8 gives 0.8 at every default mu", "[cli]") {
    const auto r = run_cli("albedo --model lambert:rho=0.8 --format json");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j.at("results").size() >= 5);
    for (const auto& e : j["results"]) CHECK(std::fabs(e.at("albedo").get<double>() - 0.8) <= 1e-6);
}

TEST_CASE("albedo csv and table formats carry every value with its error", "[cli]") {
    const auto csv = run_cli("albedo --model lambert:rho=0.5 --mu 0.25,1 --format csv");
    REQUIRE(csv.status == 0);
    CHECK(csv.out.rfind("mu,phi_deg,albedo,error\n", 0) == 0);
    CHECK(testing::count_lines(csv.out) == 3);
    const auto table = run_cli("albedo --model lambert:rho=0.5 --mu 0.25,1");
    REQUIRE(table.status == 0);
    CHECK(table.out.find("0.50000000") != std::string::npos);
}

TEST_CASE("albedo -o writes the file atomically", "[cli]") {
    const std::string path = "/tmp/brdfbake-test-albedo-" + std::to_string(::getpid()) + ".json";
    const auto r = run_cli("albedo --model lambert:rho=0.5 --mu 1 --format json -o " + path);
    REQUIRE(r.status == 0);
    CHECK(r.out.empty());
    CHECK(nlohmann::json::parse(testing::slurp(path)).at("results").size() == 1);
    std::remove(path.c_str());
}

TEST_CASE("bad input gives one clear message and exit status 2", "[cli]") {
    const testing::BadInput cases[] = {
        {"albedo --model blinn-phongg:n=10", "unknown model 'blinn-phongg'"},
        {"albedo --model ggx:alpha=0", "alpha"},
        {"albedo --model ggx:alpha=-0.5", "out of range"},
        {"albedo --model ggx:alpha=nan", "not a finite number"},
        {"albedo --model ggx:alpha=inf", "not a finite number"},
        {"albedo --model ggx:alpha=abc", "not a number"},
        {"albedo --model ggx", "needs alpha"},
        {"albedo --model ggx:alpha=0.5,beta=2", "no key 'beta'"},
        {"albedo --model ggx:alpha=0.5,shadowing=weird", "shadowing"},
        {"albedo --model ggx:alpha=0.5 --mu 0", "mu"},
        {"albedo --model ggx:alpha=0.5 --mu nan", "--mu"},
        {"albedo --model ggx:alpha=0.5 --mu 1.5", "out of range"},
        {"albedo --model ggx:alpha=0.5 --samples -5", "samples"},
        {"albedo --model ggx:alpha=0.5 --format xml", "format"},
        {"albedo --model lambert:rho=0.5 --fresnel schlick:f0=0.04", "no Fresnel term"},
        {"albedo --model ggx:alpha=0.5 --device 7:7", "no OpenCL device"},
        {"albedo", "model"},
        {"frobnicate", "frobnicate"},
    };
    for (const auto& c : cases) {
        INFO(c.args);
        const auto r = run_cli(c.args);
        testing::check_usage_error(r);
        CHECK(r.out.empty());
        CHECK(r.err.find(c.must_mention) != std::string::npos);
    }
}

TEST_CASE("a failed run leaves no output file behind", "[cli]") {
    const std::string path = "/tmp/brdfbake-test-bad-" + std::to_string(::getpid()) + ".json";
    std::remove(path.c_str());
    const auto r = run_cli("albedo --model ggx:alpha=-1 --format json -o " + path);
    CHECK(r.status == 2);
    CHECK(::access(path.c_str(), F_OK) != 0);
}

TEST_CASE("devices lists PoCL with its facts", "[cli]") {
    const auto r = run_cli("devices --format json");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(!j.at("devices").empty());
    const auto& d = j["devices"][0];
    CHECK(d.at("compute_units").get<int>() >= 1);
    CHECK(d.contains("fp64"));
    CHECK(d.at("global_mem_bytes").get<double>() > 0);
}

TEST_CASE("an option whose 0 means 'not given' refuses a given 0 or a negative value", "[cli]") {
    // Before, each of these ran with the option's default and exited 0.
    const std::string here = __FILE__;
    const std::string scene = here.substr(0, here.find_last_of('/')) + "/data/small_bake.json";
    const std::string cases[] = {
        "albedo --model lambert --mu 0.5 --tolerance 0",
        "albedo --model lambert --mu 0.5 --tolerance -0",
        "lut albedo --model ggx --size 2x2 --tolerance 0 -o /tmp/never-written.exr",
        "plan " + scene + " --samples 0",
        "plan " + scene + " --mu-texels 0",
        "plan " + scene + " --alpha-texels -1",
        "bench --table 0",
        "bench --samples -1",
    };
    for (const std::string& args : cases) {
        const auto r = run_cli(args);
        INFO(args << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(r.err.find("brdfbake: error: --") == 0);
        CHECK(r.err.find("must be a positive number") != std::string::npos);
    }
    CHECK(::access("/tmp/never-written.exr", F_OK) != 0);
}

TEST_CASE("a mistyped option is named with the nearest option of its command", "[cli][messages]") {
    // CLI11 reported the required option the typo hid ("--model is required").
    const auto r = run_cli("lut albedo --mdoel ggx --size 2x2 -o /tmp/never-written-mdoel.exr");
    CHECK(r.status == 2);
    CHECK(r.err == "brdfbake: error: unknown option '--mdoel' of `brdfbake lut`; did you mean '--model'?\n");
    CHECK(::access("/tmp/never-written-mdoel.exr", F_OK) != 0);
    const auto s = run_cli("albedo --model lambert --mu 0.5 --smaples=64");
    CHECK(s.err == "brdfbake: error: unknown option '--smaples' of `brdfbake albedo`; did you mean '--samples'?\n");
    const auto far = run_cli("albedo --model lambert --mu 0.5 --frobnicate");
    CHECK(far.err == "brdfbake: error: unknown option '--frobnicate' of `brdfbake albedo`; see brdfbake albedo --help\n");
    // A mistyped key of a spec gets the same treatment.
    const auto k = run_cli("albedo --model ggx:alpah=0.5 --mu 0.5");
    CHECK(k.err == "brdfbake: error: model 'ggx' has no key 'alpah'; did you mean 'alpha'?\n");
}

TEST_CASE("integer options take 1e6, 2^20 and 1<<20, and say when a value is not an integer", "[cli][messages]") {
    // The same integer written four ways gives the same table (exact equality: same samples).
    const auto plain = run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --format csv --samples 1024");
    REQUIRE(plain.status == 0);
    for (const char* form : {"1.024e3", "2^10", "1<<10"}) {
        const auto r = run_cli(std::string("albedo --model ggx:alpha=0.5 --mu 0.5 --format csv --samples '") + form + "'");
        INFO(form << ": " << r.err);
        CHECK(r.status == 0);
        CHECK(r.out == plain.out);
    }
    const auto half = run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --samples 1.5e0");
    CHECK(half.status == 2);
    CHECK(half.err == "brdfbake: error: --samples: must be an integer (e.g. 1000000, 1e6, 2^20 or 1<<20), got "
                      "'1.5e0' (see brdfbake albedo --help)\n");
    // Every command's integer options share the parser: furnace --pixels, check --samples.
    const auto pixels = run_cli("furnace --model lambert --pixels abc -o /tmp/never-written-furnace.png");
    CHECK(pixels.err.find("brdfbake: error: --pixels: must be an integer") == 0);
    const auto huge = run_cli("albedo --model lambert --mu 0.5 --samples 2^70");
    CHECK(huge.err.find("brdfbake: error: --samples: '2^70' is too large for an integer") == 0);
}

TEST_CASE("a --size that does not match the kind's axes is refused before any work", "[cli][messages]") {
    // Before, 32x32 of a 3D kind silently became 32x32x32 (65,536 cells, minutes of work).
    const auto r = run_cli("lut dielectric --model ggx --size 32x32 --no-preview -o /tmp/never-written-size.exr");
    CHECK(r.status == 2);
    CHECK(r.err == "brdfbake: error: --size: a dielectric table has 3 axes (mu x alpha x eta); give N (the same on "
                   "every axis) or WIDTHxHEIGHTxDEPTH (--size 32x32)\n");
    CHECK(::access("/tmp/never-written-size.exr", F_OK) != 0);
    const auto two = run_cli("lut albedo --model ggx --size 2x2x2 --no-preview -o /tmp/never-written-size.exr");
    CHECK(two.err == "brdfbake: error: --size: an albedo table has 2 axes (mu x alpha); give N (the same on every "
                     "axis) or WIDTHxHEIGHT (--size 2x2x2)\n");
}

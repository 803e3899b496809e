// Limits on what a user can ask for, judged before any work (issue 16): n,k files bounded like
// conductor specs, angles reduced exactly, memory estimated before allocation, and one line of
// error for every parse failure.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "reference/reference.h"
#include "support.h"

using testing::run_cli;

namespace {

std::string scratch(const std::string& name) {
    return "/tmp/brdfbake-limits-" + std::to_string(::getpid()) + "-" + name;
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string nk_file(const std::string& rows) {
    return "DATA:\n  - type: tabulated nk\n    data: |\n" + rows;
}

void require_one_line_error(const testing::CliResult& r, const std::string& must_mention) {
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(r.err.find(must_mention) != std::string::npos);
}

}  // namespace

TEST_CASE("n,k files hold optical constants within the conductor spec's bounds", "[cli][limits]") {
    const std::string huge = scratch("huge.yml"), rows = scratch("rows.yml"), big = scratch("big.yml");
    write_text(huge, nk_file("      0.4 1e308 1e308\n      0.6 1e308 1e308\n"));
    // 100001 rows: one more than a data block may hold.
    std::string many;
    for (int i = 0; i <= 100000; ++i) many += "      " + std::to_string(0.3 + i * 1e-5) + " 1.5 0.1\n";
    write_text(rows, nk_file(many));
    // 17 MiB: past the size limit, refused before it is read (a comment line keeps it valid YAML).
    write_text(big, "# " + std::string(17u << 20, 'x') + "\n" + nk_file("      0.4 1.5 0\n      0.6 1.5 0\n"));
    const std::string fifo = scratch("fifo.yml");
    std::remove(fifo.c_str());
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);

    struct Case {
        std::string spec, must_mention;
    };
    const Case cases[] = {
        {"nk:" + huge, "n must lie in (0, 1e+03]"},
        {"nk:" + rows, "more than 100000 data rows"},
        {"nk:" + big, "the limit is 16 MiB"},
        {"nk:/dev/zero", "not a regular file"},
        {"nk:" + fifo, "not a regular file"},
        {"nk:/tmp", "is a directory"},
    };
    for (const Case& c : cases) {
        INFO(c.spec);
        // `timeout`: a FIFO or a device must be refused, never read (it would block or fill memory).
        for (const std::string& command :
             {"fresnel --fresnel " + c.spec + " --wavelength 500 --theta 0",
              "albedo --model ggx:alpha=0.5 --mu 0.5 --samples 1024 --fresnel " + c.spec + " --wavelength 500"}) {
            const auto r = run_cli(command);
            require_one_line_error(r, c.must_mention);
        }
    }
    for (const std::string& p : {huge, rows, big, fifo}) std::remove(p.c_str());
}

TEST_CASE("an n,k file at the bounds gives finite values that pass check", "[cli][limits]") {
    // n = k = 1e3, the largest a file may hold: the exact conductor is finite (F(0) =
    // ((n-1)^2 + k^2) / ((n+1)^2 + k^2), 0.998002 here) and every check passes its values.
    const std::string bound = scratch("bound.yml");
    write_text(bound, nk_file("      0.4 1000 1000\n      0.6 1000 1000\n"));
    const auto f = run_cli("fresnel --fresnel nk:" + bound + " --wavelength 500 --theta 0 --format json");
    REQUIRE(f.status == 0);
    CHECK(f.out.find("nan") == std::string::npos);
    const double f0 = (999.0 * 999.0 + 1e6) / (1001.0 * 1001.0 + 1e6);
    const auto j = nlohmann::json::parse(f.out);
    CHECK(std::fabs(j.at("results").at(0).at("F").get<double>() - f0) <= 1e-6);
    const auto c = run_cli("check --model ggx:alpha=0.5 --fresnel nk:" + bound +
                           " --wavelength 500 --directions 4 --samples 4096 --resolution 8 --format json");
    INFO(c.err);
    REQUIRE(c.status == 0);
    const auto cj = nlohmann::json::parse(c.out);
    CHECK(cj.at("values").at("nonfinite").get<int>() == 0);
    std::remove(bound.c_str());
}

TEST_CASE("phi is reduced exactly: phi and phi + 360 k give the same albedo", "[cli][limits]") {
    // Anisotropic GGX, whose albedo depends on phi. 1e9 = 2777777 * 360 + 280 in integers.
    const std::string model = "--model ggx:alpha_x=0.1,alpha_y=0.5 --mu 0.5 --format json";
    const double truth_280 = ref::albedo_halfvector(
        [](ref::Dir wo, ref::Dir wi) { return ref::ggx_f(wo, wi, 0.1, 0.5, true); }, 0.5, 280.0 * M_PI / 180.0);
    for (const char* method : {"quadrature", "importance"})
        for (const char* precision : {"float", "double"}) {
            const std::string base = std::string("albedo ") + model + " --method " + method + " --precision " + precision;
            const auto at = [&](const std::string& phi) {
                const auto r = run_cli(base + " --phi " + phi);
                INFO(base << " --phi " << phi << ": " << r.err);
                REQUIRE(r.status == 0);
                CHECK(r.out.find("null") == std::string::npos);
                return nlohmann::json::parse(r.out).at("results").at(0);
            };
            const auto reference = at("280");
            for (const char* phi : {"-80", "640", "1e9", "-359999720"}) {
                INFO(base << " --phi " << phi);
                const auto r = at(phi);
                CHECK(r.at("albedo").get<double>() == reference.at("albedo").get<double>());
                CHECK(r.at("error").get<double>() == reference.at("error").get<double>());
            }
            const double got = reference.at("albedo").get<double>(), err = reference.at("error").get<double>();
            INFO(base << ": " << got << " +- " << err << " against " << truth_280);
            CHECK(std::fabs(got - truth_280) <= err + 1e-6);
            // A phi so large that its double has no fractional turns left: still a finite albedo
            // of this lobe (between its extremes over phi, about 0.797 and 0.806), never NaN or 0.
            const double huge = at("1e100").at("albedo").get<double>();
            CHECK(huge > 0.79);
            CHECK(huge < 0.81);
        }
}

TEST_CASE("work is judged against the memory limit before anything is allocated", "[cli][limits]") {
    // 2^24 samples for one direction are tabulated in chunks of 2^20 points (about 48 MB with the
    // launch's buffers): over a 16 MB limit.
    const auto r = run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --samples 16777216 --max-memory 16M");
    require_one_line_error(r, "of memory; the limit is 16 MB");
    require_one_line_error(run_cli("bench --table 100000"), "bench with a 100000x100000 table needs about");
    require_one_line_error(run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --max-memory 12parsecs"), "--max-memory");
    require_one_line_error(run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --max-memory 0"), "--max-memory");
    // The environment variable, as the option.
    const auto env = run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --samples 16777216");
    CHECK(env.status == 0);  // under the default limit (half the physical memory) on any test machine
    const std::string with_env = std::string("BRDFBAKE_MAX_MEMORY=16M ") + BRDFBAKE_EXE +
                                 " albedo --model ggx:alpha=0.5 --mu 0.5 --samples 16777216 2>/dev/null";
    CHECK(WEXITSTATUS(std::system(with_env.c_str())) == 2);
    // A small run fits a small limit.
    CHECK(run_cli("albedo --model ggx:alpha=0.5 --mu 0.5 --samples 4096 --max-memory 16M").status == 0);
}

TEST_CASE("parse errors are one line, and a bare brdfbake prints a short usage", "[cli][limits]") {
    require_one_line_error(run_cli(""), "usage: brdfbake COMMAND");
    require_one_line_error(run_cli("albedo --model ggx:alpha=0.5 --samples abc"), "--samples");
    require_one_line_error(run_cli("albedo --model ggx:alpha=0.5 --format xml"), "--format");
    require_one_line_error(run_cli("albedo --model ggx:alpha=0.5 --frobnicate"), "--frobnicate");
    require_one_line_error(run_cli("lut albedo --model ggx --size 2x2"), "brdfbake lut --help");
}

TEST_CASE("scene files are judged before they are read: only a regular file of at most 64 MiB", "[cli][limits]") {
    const std::string dir = scratch("scenes");
    REQUIRE(std::system(("mkdir -p " + dir).c_str()) == 0);
    const std::string fifo = dir + "/fifo.json", big = dir + "/big.json";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    write_text(big, "{\"x\": \"" + std::string(65u << 20, 'x') + "\"}");
    require_one_line_error(run_cli("plan " + fifo), "not a regular file");
    require_one_line_error(run_cli("plan " + big), "the limit is 64 MiB");
    require_one_line_error(run_cli("plan /dev/null.json"), "cannot read scene");
    REQUIRE(std::system(("rm -rf " + dir).c_str()) == 0);
}

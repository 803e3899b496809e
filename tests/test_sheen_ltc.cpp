// The LTC sheen as a model (brdf/sheen_ltc.h, `sheen-ltc:roughness=R[,table=FILE]`), checked from
// outside: f cos against the LTC density written here from Heitz, Dupuy, Hill and Neubelt 2016
// eq. 1 with a general 3x3 matrix (its inverse and determinant computed here); the albedo against
// the closed form (an LTC integrates to 1 over the upper hemisphere when M^-1 keeps z, so E = R)
// at the table's nodes and, between them, against the bilinear value computed here; the energy
// check; the shipped table read through io's reader (not the model's); bad tables refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "brdfbake/albedo.h"
#include "brdfbake/brdf/models.h"
#include "brdfbake/table_kinds.h"
#include "support.h"

using namespace brdfbake;

namespace {

// A 3 x 2 table: mu nodes 0, 0.4, 1 (not uniform), roughness nodes 0.2, 0.9.
const double kMu[3] = {0.0, 0.4, 1.0}, kR[2] = {0.2, 0.9};
const double kA[2][3] = {{0.3, 0.35, 0.4}, {0.7, 0.75, 0.8}};
const double kB[2][3] = {{-0.2, -0.1, 0.0}, {-0.05, -0.02, 0.0}};
const double kRefl[2][3] = {{0.2, 0.1, 0.05}, {0.6, 0.5, 0.4}};

std::string header(const std::string& kind, const std::string& x, const std::string& y, int nx, int ny) {
    return "# kind: " + kind + "\n# x_axis: " + x + "\n# x_mapping: mu = u\n# x_range: 0 1\n# x_size: " +
           std::to_string(nx) + "\n# y_axis: " + y + "\n# y_size: " + std::to_string(ny) +
           "\n# channels: a b R error\nmu," + y + ",a,b,R,error\n";
}

/// Writes the table above (or with `r_scale` on R, `nan` in one cell) as `lut sheen-ltc` lays out CSV.
std::string write_table(const std::string& name, const std::string& kind = "sheen-ltc", double r_scale = 1.0,
                        bool nan = false, bool decreasing = false) {
    const std::string path = "/tmp/brdfbake-test-sheen-ltc-" + std::to_string(::getpid()) + "-" + name + ".csv";
    std::ofstream out(path);
    out.precision(17);
    out << header(kind, "mu", "roughness", 3, 2);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            const double mu = decreasing ? kMu[2 - i] : kMu[i];
            out << mu << "," << kR[j] << "," << kA[j][i] << ",";
            if (nan && i == 1 && j == 1)
                out << "nan";
            else
                out << kB[j][i];
            out << "," << kRefl[j][i] * r_scale << ",0\n";
        }
    return path;
}

/// Bilinear between the nodes about (mu, r), each channel on its own (Cycles' lookup_table_read_2D).
double bilinear(const double (&v)[2][3], double mu, double r) {
    const int i = mu < kMu[1] ? 0 : 1;
    const double tx = (mu - kMu[i]) / (kMu[i + 1] - kMu[i]), ty = (std::clamp(r, kR[0], kR[1]) - kR[0]) / (kR[1] - kR[0]);
    const double lo = (1 - tx) * v[0][i] + tx * v[0][i + 1], hi = (1 - tx) * v[1][i] + tx * v[1][i + 1];
    return (1 - ty) * lo + ty * hi;
}

/// The LTC density of Heitz et al. 2016 eq. 1 for the matrix M (row-major): D_o(w_o) / |M^-1 w|^3
/// / |det M| with w_o = M^-1 w / |M^-1 w|, M^-1 by the adjugate.
long double ltc_density(const long double (&m)[3][3], const long double (&w)[3]) {
    const long double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                            m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    long double inv[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            inv[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
        }
    long double v[3];
    for (int r = 0; r < 3; ++r) v[r] = inv[r][0] * w[0] + inv[r][1] * w[1] + inv[r][2] * w[2];
    const long double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::max(0.0L, v[2] / n) / M_PI / (n * n * n) / std::fabs(det);
}

std::string exact(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

double albedo_of(const std::string& spec, double mu, Method method, double& error) {
    const AlbedoRequest req = testing::albedo_request(spec, {mu}, method, Precision::Double, 1u << 16);
    const AlbedoResult res = compute_albedo(testing::engine(), req);
    error = res.values[0].error;
    return res.values[0].value;
}

}  // namespace

TEST_CASE("sheen-ltc: f cos is R times the LTC density of Heitz et al. 2016", "[sheen-ltc]") {
    const std::string table = write_table("density");
    const double r = 0.55, mu = 0.7;  // between every node
    const ModelConfig m = resolve_model("sheen-ltc:roughness=0.55,table=" + table);
    const double a = bilinear(kA, mu, r), b = bilinear(kB, mu, r), R = bilinear(kRefl, mu, r);
    // M = (M^-1)^-1 with M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]]: M = [[1/a, 0, -b/a], [0, 1/a, 0], [0, 0, 1]].
    const long double M[3][3] = {{1 / a, 0, -b / a}, {0, 1 / a, 0}, {0, 0, 1}};
    bb_params p{};
    for (int k = 0; k < BB_MAX_PARAMS; ++k) p.v[k] = m.params[size_t(k)];
    const double phi_o = 0.8, st = std::sqrt(1 - mu * mu);
    const bb_vec3 wo = bb_v3(st * std::cos(phi_o), st * std::sin(phi_o), mu);
    for (double ti : {0.1, 0.6, 1.2, 1.5})
        for (double pi : {0.0, 1.0, 2.5, 4.0}) {
            const double dphi = pi - phi_o;  // wi's azimuth from wo's
            const long double w[3] = {std::sin(ti) * std::cos(dphi), std::sin(ti) * std::sin(dphi), std::cos(ti)};
            const bb_vec3 wi = bb_v3(std::sin(ti) * std::cos(pi), std::sin(ti) * std::sin(pi), std::cos(ti));
            const double expected = double(R * ltc_density(M, w));
            CHECK(bb_sheen_ltc_eval(p, wo, wi) * wi.z == Approx(expected).epsilon(1e-12).margin(1e-15));
        }
}

TEST_CASE("sheen-ltc: the albedo is the table's R at its nodes and bilinear between", "[sheen-ltc]") {
    const std::string table = write_table("albedo");
    struct Point {
        double mu, r;
    };
    for (const Point pt : {Point{0.4, 0.9}, Point{1.0, 0.2}, Point{0.7, 0.55}, Point{0.15, 0.3}, Point{0.9, 0.95}}) {
        const double expected = bilinear(kRefl, pt.mu, pt.r);
        const std::string spec = "sheen-ltc:roughness=" + exact(pt.r) + ",table=" + table;
        double err = 0;
        // qmc integrates f cos with uniform directions (the model's eval, not its sampler)
        const double qmc = albedo_of(spec, pt.mu, Method::QuasiMonteCarlo, err);
        CHECK(std::fabs(qmc - expected) <= err + 1e-6);
        CHECK(err < 0.02 * expected);
        const double imp = albedo_of(spec, pt.mu, Method::Importance, err);  // the LTC sampler: weight R
        CHECK(std::fabs(imp - expected) <= err + 1e-9);
    }
}

TEST_CASE("sheen-ltc: the shipped table's albedo is its R at the nodes", "[sheen-ltc]") {
    const Table t = read_table(std::string(BRDFBAKE_SOURCE_DIR) + "/data/sheen_ltc/sheen_ltc_cycles.csv");
    REQUIRE(t.x.name == "mu");
    REQUIRE(t.y.name == "roughness");
    int r_channel = -1;
    for (size_t c = 0; c < t.channels.size(); ++c)
        if (t.channels[c] == "R") r_channel = int(c);
    REQUIRE(r_channel >= 0);
    const int w = t.width();
    for (int j : {5, 16, 31})
        for (int i : {4, 15, 31}) {
            const double mu = t.x.coordinate[size_t(i)], r = t.y.coordinate[size_t(j)];
            const double R = t.values[size_t(r_channel)][size_t(j * w + i)];
            double err = 0;
            const double e = albedo_of("sheen-ltc:roughness=" + exact(r), mu, Method::QuasiMonteCarlo, err);
            INFO("mu " << mu << " r " << r);
            CHECK(std::fabs(e - R) <= err + 1e-6);
        }
}

TEST_CASE("sheen-ltc: the energy check passes, reciprocity fails (the LTC is not reciprocal)", "[sheen-ltc][cli]") {
    const auto r = testing::run_cli("check --model sheen-ltc:roughness=0.4 --directions 8 --samples 4096 --resolution 8 "
                                    "--phi-resolution 4");
    INFO(r.out << r.err);
    CHECK(r.out.find("energy       pass") != std::string::npos);
    // M^-1 depends on wo alone: f(wo, wi) != f(wi, wo) away from the normal (Zeltner et al. 2022)
    CHECK(r.out.find("reciprocity  FAIL") != std::string::npos);
}

TEST_CASE("sheen-ltc: lobe and lut albedo run on it", "[sheen-ltc][cli]") {
    const std::string table = write_table("lut");
    const std::string csv = "/tmp/brdfbake-test-sheen-ltc-" + std::to_string(::getpid()) + "-lobe.csv";
    auto r = testing::run_cli("lobe --model sheen-ltc:roughness=0.5 --theta-i 60 --resolution 37 --data " + csv);
    INFO(r.err);
    CHECK(r.status == 0);
    std::ifstream rows(csv);
    int n = 0;
    for (std::string line; std::getline(rows, line);) {
        if (line.empty() || line[0] == '#' || line[0] == 'm') continue;
        const double f = std::stod(line.substr(line.rfind(',') + 1));
        CHECK(std::isfinite(f));
        CHECK(f >= 0.0);
        ++n;
    }
    CHECK(n == 37);
    const std::string png = "/tmp/brdfbake-test-sheen-ltc-" + std::to_string(::getpid()) + "-lobe.png";
    r = testing::run_cli("lobe --view 3d --model sheen-ltc:roughness=0.5 --theta-i 60 --resolution 19 -o " + png);
    CHECK(r.status == 0);
    const std::string lut = "/tmp/brdfbake-test-sheen-ltc-" + std::to_string(::getpid()) + "-albedo.csv";
    r = testing::run_cli("lut albedo --model sheen-ltc:table=" + table +
                         " --alpha-map roughness --alpha-range 0.2,0.9 --size 3x2 --samples 16384 -o " + lut);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Table t = read_table(lut);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            const double mu = t.x.parameter[size_t(i)], rough = std::sqrt(t.y.parameter[size_t(j)]);
            INFO("mu " << mu << " r " << rough);
            CHECK(std::fabs(t.values[0][size_t(j * 3 + i)] - bilinear(kRefl, mu, rough)) <= t.error[size_t(j * 3 + i)] + 1e-6);
        }
}

TEST_CASE("sheen-ltc: bad tables are refused with one line", "[sheen-ltc][cli]") {
    const std::string missing = "/tmp/brdfbake-test-sheen-ltc-none.csv";
    for (const std::string& file : {write_table("kind", "albedo"), write_table("R", "sheen-ltc", 3.0),
                                    write_table("nan", "sheen-ltc", 1.0, true),
                                    write_table("order", "sheen-ltc", 1.0, false, true), missing}) {
        const auto r = testing::run_cli("albedo --model sheen-ltc:roughness=0.5,table=" + file + " --mu 0.5");
        INFO(file << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(r.out.empty());
    }
}

TEST_CASE("sheen-ltc: a scene with sheen_model ltc plans and bakes the sheen-ltc table", "[sheen-ltc][scene]") {
    const std::string dir = "/tmp/brdfbake-test-sheen-ltc-" + std::to_string(::getpid()) + "-scene";
    std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
    const std::string scene = dir + "/velvet.json";
    std::ofstream(scene) << R"({"settings": {"samples": 4096, "mu_texels": 4, "alpha_texels": 4, "format": "csv",
                                "sheen_model": "ltc"},
                   "materials": [{"name": "velvet", "model": "sheen", "roughness": [0.3, 0.6]}]})";
    auto r = testing::run_cli("plan " + scene);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("sheen-ltc") != std::string::npos);
    CHECK(r.out.find("sheen-albedo") == std::string::npos);
    r = testing::run_cli("bake " + scene + " -o " + dir + "/out");
    REQUIRE(r.status == 0);
    const std::string listing = testing::run_shell("ls " + dir + "/out").out;
    const size_t at = listing.find("sheen-ltc");
    REQUIRE(at != std::string::npos);
    const Table t = read_table(dir + "/out/" + listing.substr(at, listing.find('\n', at) - at));
    REQUIRE(t.channels.size() >= 3);
    for (size_t k = 0; k < t.values[0].size(); ++k) {
        CHECK(t.values[0][k] > 0.0);  // a
        CHECK(t.values[2][k] >= 0.0);  // R, a reflectance of a layer with albedo 1
        CHECK(t.values[2][k] <= 1.0);
    }
    // the setting's other values are refused with one line
    std::ofstream(scene) << R"({"settings": {"sheen_model": "fuzz"}, "materials": [{"name": "v", "model": "sheen", "roughness": 0.5}]})";
    r = testing::run_cli("plan " + scene);
    CHECK(r.status == 2);
    CHECK(testing::count_lines(r.err) == 1);
    // a glTF sheen (KHR_materials_sheen) asks for it on the command line
    r = testing::run_cli("plan " + std::string(BRDFBAKE_SOURCE_DIR) + "/tests/data/materials.gltf --sheen-model ltc");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("sheen-ltc") != std::string::npos);
}

// MERL measured BRDFs (issue 34; brdf/merl.h, host/models/merl_file.h): files written from known
// BRDFs and read back as `merl:file=PATH`. The truths come from outside the reader: a Lambert
// file's albedo is its rho; a GGX file's albedo is compared with the textbook GGX albedo
// (Boost.Math quadrature, ggx_albedo_reference.h) within the file's tabulation error, which this
// test measures itself with its own parse of the bytes and its own lookup (MERL's BRDFRead.cpp
// recipe: acos, atan2 and two rotations) under a midpoint rule; Rec. 709's luminance weights;
// the energy verdict of `check`; hostile files refused with one line and exit status 2.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/spec.h"
#include "ggx_albedo_reference.h"
#include "models/merl_file.h"
#include "reference/reference.h"
#include "support.h"

using namespace brdfbake;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kBins = 90 * 90 * 180;
const double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};  // Matusik et al. 2003

std::string tmp(const std::string& name) { return "/tmp/brdfbake-merl-" + std::to_string(::getpid()) + "-" + name; }

/// A file written byte by byte here (not by write_merl_file): dims, then the planes, f * 1/scale.
void write_raw(const std::string& path, const std::int32_t dims[3], const std::vector<double>& planes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(dims), 12);  // the test machines are little-endian
    out.write(reinterpret_cast<const char*>(planes.data()), std::streamsize(planes.size() * 8));
}

/// A constant (Lambertian) file, rho per channel.
void write_lambert(const std::string& path, std::array<double, 3> rho) {
    const std::int32_t dims[3] = {90, 90, 180};
    std::vector<double> planes(3 * size_t(kBins));
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < kBins; ++i) planes[size_t(c) * kBins + i] = rho[c] / kPi / kScale[c];
    write_raw(path, dims, planes);
}

/// A GGX file (F = 1, height-correlated) tabulated at the bins' nodes from the textbook GGX
/// (reference.h), unmeasured below the horizon as in MERL's files.
void write_ggx(const std::string& path, double alpha) {
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        if (o[2] <= 0 || i[2] <= 0) return std::array<double, 3>{-1, -1, -1};
        const double f = double(ref::ggx_f({o[0], o[1], o[2]}, {i[0], i[1], i[2]}, alpha, alpha, true));
        return std::array<double, 3>{f, f, f};
    });
}

/// The test's own reading of a file: the first plane, scaled.
std::vector<double> read_red(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(12);
    std::vector<double> v(kBins);
    in.read(reinterpret_cast<char*>(v.data()), std::streamsize(kBins * 8));
    for (double& x : v) x = x < 0 ? -1.0 : x * kScale[0];
    return v;
}

/// BRDFRead.cpp's recipe, written here from its description: half and difference angles by acos,
/// atan2 and the rotations R_z(-phi_h), R_y(-theta_h) of wi, then the nearest bins.
double lookup_nearest(const std::vector<double>& t, const std::array<double, 3>& wo, const std::array<double, 3>& wi) {
    std::array<double, 3> h{wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
    const double l = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (double& x : h) x /= l;
    const double theta_h = std::acos(std::min(1.0, h[2])), phi_h = std::atan2(h[1], h[0]);
    const double c1 = std::cos(-phi_h), s1 = std::sin(-phi_h);
    const double t0 = wi[0] * c1 - wi[1] * s1, t1 = wi[0] * s1 + wi[1] * c1, t2 = wi[2];
    const double c2 = std::cos(-theta_h), s2 = std::sin(-theta_h);
    const double d0 = t0 * c2 + t2 * s2, d1 = t1, d2 = -t0 * s2 + t2 * c2;
    const double theta_d = std::acos(std::max(-1.0, std::min(1.0, d2)));
    double phi_d = std::atan2(d1, d0);
    if (phi_d < 0) phi_d += kPi;
    const int ih = std::min(89, int(std::sqrt(theta_h / (kPi / 2) * 90 * 90)));
    const int id = std::min(89, int(theta_d / (kPi / 2) * 90));
    const int ip = std::min(179, int(phi_d / kPi * 180));
    return t[size_t(ip + 180 * (id + 90 * ih))];
}

/// E(mu) of a table under the nearest lookup, unmeasured as 0: a midpoint rule of n x n cells in
/// (cos^2 theta_i, phi_i) (each cell of equal cosine-weighted measure), E = pi * mean f.
double nearest_albedo(const std::vector<double>& t, double mu, int n) {
    const std::array<double, 3> wo{std::sqrt(1 - mu * mu), 0.0, mu};
    double sum = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const double u = (a + 0.5) / n, phi = 2 * kPi * (b + 0.5) / n;
            const double s = std::sqrt(1 - u);
            sum += std::max(0.0, lookup_nearest(t, wo, {s * std::cos(phi), s * std::sin(phi), std::sqrt(u)}));
        }
    return kPi * sum / (double(n) * n);
}

AlbedoResult albedo_of(const std::string& spec, const std::vector<double>& mus, std::uint64_t samples) {
    return compute_albedo(testing::engine(),
                          testing::albedo_request(spec, mus, Method::Importance, Precision::Double, samples));
}

bool exists(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
}

}  // namespace

TEST_CASE("merl: spec keys, defaults, canonical spelling, one read per file and channel", "[merl][quick]") {
    const std::string path = tmp("rgb.binary");
    write_lambert(path, {0.2, 0.5, 0.8});
    const ModelConfig m = resolve_model("merl:file=" + path);
    CHECK(m.canonical == "merl:file=" + path + ",channel=y,interp=linear");
    CHECK(m.params[BB_MERL_INTERP] == BB_MERL_LINEAR);
    CHECK_FALSE(m.uses_fresnel);
    CHECK(m.traits().alpha_x_slot < 0);
    CHECK(resolve_model(m.canonical).params == m.params);  // the same table, not a second read
    CHECK(resolve_model("merl:file=" + path + ",interp=linear").params[BB_MERL_INTERP] == BB_MERL_LINEAR);
    CHECK(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE] != m.params[BB_MERL_TABLE]);
    CHECK(merl_table_info(int(m.params[BB_MERL_TABLE])).unmeasured == 0);
    std::remove(path.c_str());
}

TEST_CASE("merl: a Lambert file's albedo is its rho, per channel and in Rec. 709 luminance", "[merl]") {
    const std::string path = tmp("lambert.binary");
    const std::array<double, 3> rho{0.2, 0.5, 0.8};
    write_lambert(path, rho);
    const std::vector<double> mus{0.05, 0.5, 1.0};
    const char* names[] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c) {
        const AlbedoResult r = albedo_of("merl:file=" + path + ",channel=" + names[c], mus, 1 << 14);
        for (const auto& v : r.values) CHECK(std::fabs(v.value - rho[c]) <= v.error + 1e-12);
    }
    // ITU-R BT.709 luminance weights
    const double y = 0.2126 * rho[0] + 0.7152 * rho[1] + 0.0722 * rho[2];
    for (const char* interp : {"nearest", "linear"}) {
        const AlbedoResult r = albedo_of("merl:file=" + path + ",interp=" + interp, mus, 1 << 14);
        for (const auto& v : r.values) CHECK(std::fabs(v.value - y) <= v.error + 1e-12);
    }
    std::remove(path.c_str());
}

TEST_CASE("merl: a GGX file's albedo is analytic GGX's within the file's tabulation error", "[merl]") {
    const double alpha = 0.5;
    const std::string path = tmp("ggx.binary");
    write_ggx(path, alpha);
    const std::vector<double> table = read_red(path);
    const std::vector<double> mus{0.3, 1.0};
    const AlbedoResult nearest = albedo_of("merl:file=" + path + ",channel=r,interp=nearest", mus, 1 << 20);
    const AlbedoResult linear = albedo_of("merl:file=" + path + ",channel=r,interp=linear", mus, 1 << 18);
    for (size_t k = 0; k < mus.size(); ++k) {
        const double exact = testing::ggx_albedo_reference<30>(alpha, mus[k], 1e-10);
        // the file's own albedo by the test's lookup; its error from halving the rule
        const double fine = nearest_albedo(table, mus[k], 640), coarse = nearest_albedo(table, mus[k], 320);
        const double rule_error = std::fabs(fine - coarse);
        const double tabulation = std::fabs(fine - exact);
        INFO("mu = " << mus[k] << ": analytic " << exact << ", file (test's lookup) " << fine << " +- " << rule_error
                     << ", brdfbake nearest " << nearest.values[k].value << " +- " << nearest.values[k].error
                     << ", linear " << linear.values[k].value << " +- " << linear.values[k].error);
        CHECK(std::fabs(nearest.values[k].value - fine) <= nearest.values[k].error + rule_error);
        CHECK(std::fabs(nearest.values[k].value - exact) <= tabulation + nearest.values[k].error + rule_error);
        CHECK(tabulation < 0.05);  // 90 x 90 x 180 bins: a few per cent at most for alpha = 0.5
        // trilinear between the nodes is second order where nearest is first: closer to the lobe
        CHECK(std::fabs(linear.values[k].value - exact) + linear.values[k].error < tabulation);
    }
    std::remove(path.c_str());
}

TEST_CASE("merl: unmeasured bins are counted and their share of the hemisphere is what the albedo lacks",
          "[merl]") {
    const std::string path = tmp("holes.binary");
    size_t written = 0;
    const double rho = 0.8;
    // a Lambert file with every bin whose node has a direction below the horizon unmeasured
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        const bool hole = o[2] <= 0 || i[2] <= 0;
        written += hole;
        const double f = hole ? -1.0 : rho / kPi;
        return std::array<double, 3>{f, f, f};
    });
    const auto r = testing::run_cli("albedo --model merl:file=" + path + ",interp=nearest --mu 0.002,0.5 --format json --samples 262144");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    for (const auto& e : j.at("results")) {
        CHECK(e.at("unmeasured_bins").get<size_t>() == written);
        const double share = e.at("unmeasured_share").get<double>(), albedo = e.at("albedo").get<double>();
        // Lambert: the albedo lacks rho times the unmeasured share of the cosine-weighted hemisphere
        // (the share from a 128 x 128 midpoint rule: its cells on the holes' edge, 1/128 of them at most)
        CHECK(std::fabs(albedo - rho * (1 - share)) <= e.at("error").get<double>() + rho / 128);
    }
    CHECK(j.at("results")[0].at("unmeasured_share").get<double>() > 0.0);   // grazing wo reads holes
    CHECK(j.at("results")[1].at("unmeasured_share").get<double>() == 0.0);  // mu = 0.5 reads none
    const auto t = testing::run_cli("albedo --model merl:file=" + path + ",interp=nearest --mu 0.002");
    CHECK(t.out.find("# unmeasured: " + std::to_string(written) + " of 1458000 bins") != std::string::npos);
    std::remove(path.c_str());
}

TEST_CASE("merl: check passes a rho = 0.5 file and flags rho = 1.2", "[merl][cli]") {
    const std::string half = tmp("half.binary"), gain = tmp("gain.binary");
    write_lambert(half, {0.5, 0.5, 0.5});
    write_lambert(gain, {1.2, 1.2, 1.2});
    const auto pass = testing::run_cli("check --model merl:file=" + half + " --directions 8 --samples 4096");
    CHECK(pass.status == 0);
    CHECK(pass.out.find("verdict: PASS") != std::string::npos);
    const auto fail = testing::run_cli("check --model merl:file=" + gain + " --directions 8 --samples 4096");
    CHECK(fail.status == 1);
    CHECK(fail.out.find("energy       FAIL") != std::string::npos);
    CHECK(fail.out.find("reciprocity  pass") != std::string::npos);
    std::remove(half.c_str());
    std::remove(gain.c_str());
}

TEST_CASE("merl: lut albedo of a measured file is a 1D E(mu_o) table", "[merl][cli]") {
    const std::string path = tmp("lut.binary"), out = tmp("lut.csv");
    write_lambert(path, {0.5, 0.5, 0.5});
    const auto r = testing::run_cli("lut albedo --model merl:file=" + path + " --size 8 --samples 16384 -o " + out);
    REQUIRE(r.status == 0);
    const std::string text = testing::slurp(out);
    CHECK(text.find("E(mu_o) =") != std::string::npos);
    CHECK(text.find("alpha") == std::string::npos);
    CHECK(text.find("# x_size: 8") != std::string::npos);
    int rows = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#' || line[0] == 'm') continue;
        double mu, e, err;
        REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf", &mu, &e, &err) == 3);
        CHECK(std::fabs(e - 0.5) <= err + 1e-6);  // float
        ++rows;
    }
    CHECK(rows == 8);
    const auto dfg = testing::run_cli("lut dfg --model merl:file=" + path + " -o " + tmp("dfg.csv"));
    CHECK(dfg.status == 2);
    CHECK(dfg.err.find("no roughness") != std::string::npos);
    std::remove(path.c_str());
    std::remove(out.c_str());
}

TEST_CASE("merl: hostile files are one error line, exit status 2, nothing written", "[merl][cli]") {
    const std::string dir = tmp("dir"), out = tmp("hostile.csv");
    ::mkdir(dir.c_str(), 0700);
    const std::int32_t good[3] = {90, 90, 180}, wrong[3] = {90, 90, 360};
    std::vector<double> planes(3 * size_t(kBins), 0.01);
    write_raw(tmp("dims.binary"), wrong, planes);
    planes[12345] = std::nan("");
    write_raw(tmp("nan.binary"), good, planes);
    planes[12345] = INFINITY;
    write_raw(tmp("inf.binary"), good, planes);
    planes.resize(planes.size() - 1);
    write_raw(tmp("short.binary"), good, planes);
    write_raw(tmp("empty.binary"), good, {});
    { std::ofstream(tmp("zero.binary")); }
    // a sparse file of 4 GiB: refused by its size before a byte is read (bounded memory)
    { std::ofstream(tmp("huge.binary")); }
    REQUIRE(::truncate(tmp("huge.binary").c_str(), off_t(4) << 30) == 0);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {tmp("dims.binary"), "dimensions 90 x 90 x 360"}, {tmp("nan.binary"), "NaN"}, {tmp("inf.binary"), "Inf"},
        {tmp("short.binary"), "truncated"},  {tmp("empty.binary"), "bytes"},         {tmp("zero.binary"), "too short"},
        {tmp("huge.binary"), "limit"},       {dir, "directory"},                      {"/dev/zero", "not a regular file"},
        {tmp("missing.binary"), "No such file"}};
    for (const auto& c : cases) {
        INFO(c.first);
        const auto r = testing::run_cli("lut albedo --model merl:file=" + c.first + " --size 4 -o " + out);
        CHECK(r.status == 2);
        CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.find(c.second) != std::string::npos);
        CHECK_FALSE(exists(out));
    }
    for (const char* spec : {"merl", "merl:fiel=x", "merl:file=builtin:lambert,channel=q",
                             "merl:file=builtin:lambert,interp=cubic"}) {
        const auto r = testing::run_cli(std::string("albedo --model '") + spec + "' --mu 0.5");
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
    }
    for (const char* f : {"dims", "nan", "inf", "short", "empty", "zero", "huge"}) std::remove(tmp(std::string(f) + ".binary").c_str());
    ::rmdir(dir.c_str());
}

TEST_CASE("merl: lobe's numbers are the file's bins, read by the test's own lookup", "[merl][cli]") {
    const std::string path = tmp("lobe.binary");
    write_ggx(path, 0.3);
    const std::vector<double> table = read_red(path);
    // 200 angles: steps of 180/199 degrees keep the half angles off the bins' edges
    const auto r = testing::run_cli("lobe --model merl:file=" + path + ",channel=r,interp=nearest --theta-i 60 --resolution 200 --data -");
    REQUIRE(r.status == 0);
    std::istringstream in(r.out);
    int rows = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] != '"') continue;
        double ti, to, f, fc;
        REQUIRE(std::sscanf(line.c_str() + line.find('"', 1) + 2, "%lf,%lf,%lf,%lf", &ti, &to, &f, &fc) == 4);
        if (std::fabs(to) >= 89.0) continue;
        const double a = ti * kPi / 180, b = to * kPi / 180;
        // theta_o > 0 on the mirror side
        const std::array<double, 3> wo{-std::sin(b), 0.0, std::cos(b)}, wi{std::sin(a), 0.0, std::cos(a)};
        // in the plane of incidence phi_d sits on the fold (0 or pi): d of wi or of wo, either bin
        const double one = std::max(0.0, lookup_nearest(table, wo, wi)), other = std::max(0.0, lookup_nearest(table, wi, wo));
        INFO("theta_o = " << to << ": " << f << " against " << one << " or " << other);
        CHECK((f == Approx(one).epsilon(1e-12) || f == Approx(other).epsilon(1e-12)));
        ++rows;
    }
    CHECK(rows > 150);
    std::remove(path.c_str());
}

TEST_CASE("merl: channel=rgb makes one table channel per colour, and only in tables", "[merl][cli]") {
    const std::string path = tmp("rgb-lut.binary"), out = tmp("rgb-lut.csv");
    write_lambert(path, {0.2, 0.5, 0.8});
    const auto r = testing::run_cli("lut eavg --model merl:file=" + path + ",channel=rgb --samples 1024 -o " + out);
    REQUIRE(r.status == 0);
    const std::string text = testing::slurp(out);
    CHECK(text.find("# channels: Eavg_r Eavg_g Eavg_b error") != std::string::npos);
    CHECK(text.find("channel=rgb") != std::string::npos);
    const std::string last = text.substr(text.rfind("\n", text.size() - 2) + 1);
    double x, er, eg, eb, err;
    REQUIRE(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf,%lf", &x, &er, &eg, &eb, &err) == 5);
    // Eavg of a Lambertian surface is its rho
    CHECK(std::fabs(er - 0.2) <= err + 1e-6);
    CHECK(std::fabs(eg - 0.5) <= err + 1e-6);
    CHECK(std::fabs(eb - 0.8) <= err + 1e-6);
    const auto refused = testing::run_cli("albedo --model merl:file=" + path + ",channel=rgb --mu 0.5");
    CHECK(refused.status == 2);
    CHECK(refused.err.find("one channel: r, g, b or y") != std::string::npos);
    std::remove(path.c_str());
    std::remove(out.c_str());
}

TEST_CASE("merl: a scene's material may name a MERL file beside the scene", "[merl][scene][cli]") {
    const std::string dir = tmp("scene");
    ::mkdir(dir.c_str(), 0700);
    write_lambert(dir + "/paint.binary", {0.5, 0.5, 0.5});
    std::ofstream(dir + "/scene.json") << R"({"materials": [{"name": "paint", "model": "merl:file=paint.binary,channel=g"}]})";
    std::ofstream(dir + "/bad.json") << R"({"materials": [{"name": "paint", "model": "merl:file=missing.binary"}]})";
    const auto r = testing::run_cli("plan " + dir + "/scene.json");
    INFO(r.out << r.err);
    CHECK(r.status == 0);
    CHECK(r.out.find("merl:file=" + dir + "/paint.binary,channel=g,interp=linear") != std::string::npos);
    CHECK(r.out.find("no roughness axis") != std::string::npos);
    const auto bad = testing::run_cli("plan " + dir + "/bad.json");
    CHECK(bad.status == 2);
    CHECK(testing::count_lines(bad.err) == 1);
    CHECK(bad.err.find("material 'paint'") != std::string::npos);
    CHECK(bad.err.find(dir + "/missing.binary") != std::string::npos);
    for (const char* f : {"/paint.binary", "/scene.json", "/bad.json"}) std::remove((dir + f).c_str());
    ::rmdir(dir.c_str());
}

TEST_CASE("merl: the quadrature covers the whole azimuth of a file that is not mirror-symmetric", "[merl]") {
    // f = (1 + c 2 d_x d_y) / pi at every node (below the horizon too), d the difference vector
    // of Rusinkiewicz 1998 in h's frame: 2 d_x d_y = sin^2 theta_d sin 2 phi_d, pi-periodic in
    // phi_d (so the file's fold phi_d + pi changes nothing) and odd under the mirror image of a
    // pair (phi_d -> -phi_d, y -> -y). The viewer at phi_o = 0 lies in the mirror plane, so the
    // odd part integrates to 0 over the hemisphere, and so does its trilinear interpolant (the
    // nodes phi_d = k pi/180 map onto nodes): E = 1 exactly at every mu. A rule that integrates
    // half the azimuth and doubles it (mirror symmetry assumed) finds 1 + c (twice a half-lobe
    // integral of the odd part) instead.
    const double c = 0.9;
    const std::string path = tmp("odd.binary");
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        double h[3] = {o[0] + i[0], o[1] + i[1], o[2] + i[2]};
        const double n = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        for (double& v : h) v /= n;
        // the nodes have phi_h = 0: h = (sin theta_h, 0, cos theta_h), d = R_y(-theta_h) wi
        const double dx = i[0] * h[2] - i[2] * h[0], dy = i[1];
        const double f = (1 + c * 2 * dx * dy) / kPi;
        return std::array<double, 3>{f, f, f};
    });
    const std::vector<double> mus{0.3, 0.8};
    const AlbedoResult r = compute_albedo(
        testing::engine(), testing::albedo_request("merl:file=" + path + ",channel=r,interp=linear", mus,
                                                   Method::Quadrature, Precision::Double, 1 << 16));
    for (size_t k = 0; k < mus.size(); ++k) {
        INFO("mu = " << mus[k] << ": E = " << r.values[k].value << " +- " << r.values[k].error);
        CHECK(std::fabs(r.values[k].value - 1.0) <= r.values[k].error + 1e-9);
        CHECK(r.values[k].error < 0.02);
    }
    std::remove(path.c_str());
}

TEST_CASE("merl: a file is read once per version: a file replaced at the same path is read again", "[merl][quick]") {
    const std::string path = tmp("again.binary"), next = tmp("again-next.binary");
    write_lambert(path, {0.5, 0.5, 0.5});
    const int r0 = int(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE]);
    const int g0 = int(resolve_model("merl:file=" + path + ",channel=g").params[BB_MERL_TABLE]);
    CHECK(r0 != g0);
    CHECK(bb_merl_host_table(r0)[123] == Approx(0.5 / kPi).epsilon(1e-15));
    write_lambert(next, {0.25, 0.25, 0.25});
    REQUIRE(std::rename(next.c_str(), path.c_str()) == 0);
    const int r1 = int(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE]);
    CHECK(r1 != r0);
    CHECK(bb_merl_host_table(r1)[123] == Approx(0.25 / kPi).epsilon(1e-15));
    CHECK(bb_merl_host_table(r0)[123] == Approx(0.5 / kPi).epsilon(1e-15));  // the first version's table stays
    CHECK(int(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE]) == r1);
    std::remove(path.c_str());
}

TEST_CASE("merl: a file rewritten in place with the same inode, size and mtime is read again", "[merl][quick]") {
    const std::string path = tmp("inplace.binary"), next = tmp("inplace-next.binary");
    write_lambert(path, {0.5, 0.5, 0.5});
    struct stat before {};
    REQUIRE(::stat(path.c_str(), &before) == 0);
    const int r0 = int(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE]);
    CHECK(bb_merl_host_table(r0)[123] == Approx(0.5 / kPi).epsilon(1e-15));
    // the new bytes written over the old ones (no truncation, no new inode), the old mtime put back
    write_lambert(next, {0.25, 0.25, 0.25});
    const std::string bytes = testing::slurp(next);
    std::FILE* f = std::fopen(path.c_str(), "r+b");
    REQUIRE(f);
    REQUIRE(std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size());
    REQUIRE(std::fclose(f) == 0);
    const struct timespec times[2] = {before.st_atim, before.st_mtim};
    REQUIRE(::utimensat(AT_FDCWD, path.c_str(), times, 0) == 0);
    struct stat after {};
    REQUIRE(::stat(path.c_str(), &after) == 0);
    REQUIRE(after.st_ino == before.st_ino);
    REQUIRE(after.st_size == before.st_size);
    REQUIRE(after.st_mtim.tv_sec == before.st_mtim.tv_sec);
    REQUIRE(after.st_mtim.tv_nsec == before.st_mtim.tv_nsec);
    const int r1 = int(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE]);
    CHECK(r1 != r0);
    CHECK(bb_merl_host_table(r1)[123] == Approx(0.25 / kPi).epsilon(1e-15));
    CHECK(bb_merl_host_table(r0)[123] == Approx(0.5 / kPi).epsilon(1e-15));  // the first version's table stays
    std::remove(path.c_str());
    std::remove(next.c_str());
}

TEST_CASE("merl: a file truncated after its first use: the next use is one error, never a crash", "[merl][quick]") {
    const std::string path = tmp("truncated.binary");
    write_lambert(path, {0.5, 0.5, 0.5});
    const int r0 = int(resolve_model("merl:file=" + path + ",channel=r").params[BB_MERL_TABLE]);
    REQUIRE(::truncate(path.c_str(), 4096) == 0);
    // a channel not yet read, of the file now truncated
    CHECK_THROWS_AS(resolve_model("merl:file=" + path + ",channel=g"), Error);
    CHECK(bb_merl_host_table(r0)[BB_MERL_BINS - 1] == Approx(0.5 / kPi).epsilon(1e-15));  // what was read stays
    const auto r = testing::run_cli("albedo --model merl:file=" + path + " --mu 0.5");
    CHECK(r.status == 2);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(r.err.find("truncated?") != std::string::npos);
    // Truncated and grown again while being read: every use is an error or data the file held
    // (zeros where it was cut, 0.5/pi elsewhere), never SIGBUS (as a mapping's lost pages give).
    write_lambert(path, {0.5, 0.5, 0.5});
    std::atomic<bool> stop{false};
    std::thread cutter([&] {
        while (!stop) {
            if (::truncate(path.c_str(), 1 << 20) != 0 || ::truncate(path.c_str(), off_t(kMerlFileBytes)) != 0) break;
        }
    });
    int errors = 0, reads = 0;
    for (int k = 0; k < 6; ++k) {
        try {
            const int t = int(resolve_model("merl:file=" + path + ",channel=b").params[BB_MERL_TABLE]);
            const double* v = bb_merl_host_table(t);
            ++reads;
            for (size_t i = 0; i < BB_MERL_BINS; i += 997) CHECK((v[i] == 0.0 || v[i] == Approx(0.5 / kPi).epsilon(1e-15)));
        } catch (const Error&) {
            ++errors;
        }
    }
    stop = true;
    cutter.join();
    INFO("reads " << reads << ", errors " << errors);
    CHECK(reads + errors == 6);
    std::remove(path.c_str());
}

TEST_CASE("merl: a scene's MERL material is planned and baked as E(mu) and Eavg per colour", "[merl][scene][cli]") {
    // a Lambert file: E(mu) = Eavg = rho per channel (closed form), the file named beside the scene
    const std::string dir = tmp("bake"), out = dir + "/out";
    ::mkdir(dir.c_str(), 0700);
    const std::array<double, 3> rho{0.2, 0.5, 0.8};
    write_lambert(dir + "/paint.binary", rho);
    std::ofstream(dir + "/scene.json") << R"({"settings": {"format": "csv", "mu_texels": 8, "samples": 4096},
        "materials": [{"name": "paint", "model": "merl:file=paint.binary"}]})";
    const auto plan = testing::run_cli("plan " + dir + "/scene.json");
    INFO(plan.out << plan.err);
    REQUIRE(plan.status == 0);
    CHECK(plan.out.find("albedo-merl-paint.csv") != std::string::npos);
    CHECK(plan.out.find("eavg-merl-paint.csv") != std::string::npos);
    CHECK(plan.out.find("axes      mu 0..1 (8, linear); no roughness axis (measured)") != std::string::npos);
    CHECK(plan.out.find("axes      one texel; no roughness axis (measured)") != std::string::npos);
    {  // the estimate counts the three colours the bake integrates and writes: per table cells x
       // samples x 3 (albedo: 8 mu cells; eavg: its 48 mu nodes, table_kinds)
        const auto pj = testing::run_cli("plan " + dir + "/scene.json --format json");
        REQUIRE(pj.status == 0);
        const auto j = nlohmann::json::parse(pj.out);
        for (const auto& t : j["tables"]) {
            INFO(t.dump());
            const std::uint64_t cells = t["kind"] == "albedo" ? 8 : 48;
            CHECK(t["cells"].get<std::uint64_t>() == cells);
            CHECK(t["samples_total"].get<std::uint64_t>() == cells * 4096 * 3);
        }
        CHECK(j["tables"].size() == 2);
    }
    const auto bake = testing::run_cli("bake " + dir + "/scene.json -o " + out);
    INFO(bake.out << bake.err);
    REQUIRE(bake.status == 0);
    for (const char* kind : {"albedo", "eavg"}) {
        const std::string text = testing::slurp(out + "/" + kind + "-merl-paint.csv");
        INFO(kind << ":\n" << text);
        CHECK(text.find("channel=rgb") != std::string::npos);
        int rows = 0;
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) {
            if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;  // comments, header
            std::vector<double> v;
            std::istringstream cells(line);
            for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
            REQUIRE(v.size() == 5);  // coordinate, E_r, E_g, E_b, error
            for (int c = 0; c < 3; ++c) CHECK(std::fabs(v[size_t(c) + 1] - rho[size_t(c)]) <= v[4] + 1e-6);
            CHECK(v[4] < 0.01);
            ++rows;
        }
        CHECK(rows == (std::string(kind) == "albedo" ? 8 : 1));
    }
    // the bake report checks the measured lobe (in luminance) like any other
    const std::string report = testing::slurp(out + "/index.html");
    CHECK(report.find("channel=y,interp=linear (Fresnel none)") != std::string::npos);
    CHECK(report.find("not checked") == std::string::npos);
    CHECK(std::system(("rm -rf '" + dir + "'").c_str()) == 0);
}

TEST_CASE("merl: a linear lookup's unmeasured share is what a Lambert file's albedo lacks", "[merl]") {
    // Every node with theta_d >= 60 degrees unmeasured (mirror-symmetric: the share of a linear
    // lookup counts half the cells in phi, twice). The linear lookup renormalises over measured
    // nodes, so a Lambert file reads rho/pi wherever it reads anything: E = rho (1 - share).
    const std::string path = tmp("holes-linear.binary");
    const double rho = 0.8;
    write_merl_file(path, [&](const std::array<double, 3>& o, const std::array<double, 3>& i) {
        double h[3] = {o[0] + i[0], o[1] + i[1], o[2] + i[2]};
        const double n = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        const double cos_d = (i[0] * h[0] + i[1] * h[1] + i[2] * h[2]) / n;
        const double f = cos_d < std::cos(59.5 * kPi / 180) ? -1.0 : rho / kPi;
        return std::array<double, 3>{f, f, f};
    });
    const auto r = testing::run_cli("albedo --model merl:file=" + path + ",interp=linear --mu 0.1,0.3,0.5,1 --format json --samples 262144");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    for (const auto& e : j.at("results")) {
        const double share = e.at("unmeasured_share").get<double>(), albedo = e.at("albedo").get<double>();
        INFO("mu " << e.at("mu").get<double>() << ": share " << share << ", albedo " << albedo);
        CHECK(std::fabs(albedo - rho * (1 - share)) <= e.at("error").get<double>() + rho / 128);
    }
    CHECK(j.at("results")[0].at("unmeasured_share").get<double>() > 0.05);  // grazing wo reads large theta_d
    CHECK(j.at("results")[3].at("unmeasured_share").get<double>() == 0.0);  // wo = n: theta_d = theta_i / 2 < 45 degrees
    std::remove(path.c_str());
}

// Bake folders (issue 16, item 2): two bakes into one folder run one after the other, index.json
// records each table's content hash and the up-to-date check verifies it, a bake that fails
// before writing leaves no folder behind.
#include <catch2/catch.hpp>

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "scene/bake_folder.h"
#include "support.h"

using testing::run_cli;

namespace {

std::string scratch(const std::string& name) {
    const std::string dir = "/tmp/brdfbake-bake-" + std::to_string(::getpid()) + "-" + name;
    std::system(("rm -rf " + dir).c_str());
    return dir;
}

/// A scene of one GGX metal over a roughness range: scenes with other ranges produce tables of
/// the same names (albedo-ggx.exr, eavg-ggx.exr) with other contents and sizes.
std::string scene_file(const std::string& name, double r_lo, double r_hi) {
    const std::string path = "/tmp/brdfbake-bake-" + std::to_string(::getpid()) + "-" + name + ".json";
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fprintf(f,
                 "{\"settings\": {\"samples\": 256, \"mu_texels\": 8, \"alpha_texels\": 16},\n"
                 " \"materials\": [{\"name\": \"%s\", \"model\": \"ggx\", \"fresnel\": \"schlick:f0=0.9\", "
                 "\"roughness\": [%g, %g]}]}\n",
                 name.c_str(), r_lo, r_hi);
    std::fclose(f);
    return path;
}

/// Width x height of an EXR file, read with OpenEXR (not with brdfbake's writer).
std::string exr_size(const std::string& path) {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    return std::to_string(dw.max.x - dw.min.x + 1) + "x" + std::to_string(dw.max.y - dw.min.y + 1);
}

/// The index and the files describe each other: every table the index lists is there, with the
/// content hash and the size the index records.
void check_index_matches_files(const std::string& out) {
    const auto index = nlohmann::json::parse(testing::slurp(out + "/index.json"));
    CHECK(index.at("content_hash_algorithm") == "CRC-64/XZ");
    REQUIRE(index.at("tables").size() == 2);
    for (const auto& t : index["tables"]) {
        const std::string file = out + "/" + t.at("file").get<std::string>();
        INFO(file);
        CHECK(t.at("content_hash").get<std::string>() == brdfbake::content_hash_of_file(file));
        CHECK(t.at("size").get<std::string>() == exr_size(file));
    }
}

}  // namespace

TEST_CASE("CRC-64/XZ gives the catalogue's check value", "[bake][quick]") {
    // The CRC catalogue's check value of CRC-64/XZ: the CRC of the nine ASCII digits "123456789".
    CHECK(brdfbake::crc64_xz("123456789") == 0x995DC9BBDF1939FAULL);
    CHECK(brdfbake::crc64_xz("") == 0);  // all-ones initial value and final XOR cancel on no input
    CHECK(brdfbake::crc64_xz("123456780") != brdfbake::crc64_xz("123456789"));
}

TEST_CASE("two concurrent bakes into one folder run one after the other, index and files agree", "[bake][device]") {
    // Issue 16, item 2: A and C both produce albedo-ggx.exr and eavg-ggx.exr, of other sizes.
    const std::string a = scene_file("A", 0.3, 0.95), c = scene_file("C", 0.7, 0.8);
    for (int round = 0; round < 2; ++round) {
        const std::string out = scratch("concurrent");
        const std::string base = "/tmp/brdfbake-bake-" + std::to_string(::getpid());
        const std::string exe = BRDFBAKE_EXE;
        const std::string cmd = "(" + exe + " bake " + a + " -o " + out + " 2>" + base + "-A.err & " + exe + " bake " +
                                c + " -o " + out + " 2>" + base + "-C.err; s=$?; wait $!; t=$?; exit $((s + t)))";
        INFO("round " << round);
        REQUIRE(std::system(cmd.c_str()) == 0);
        const std::string err = testing::slurp(base + "-A.err") + testing::slurp(base + "-C.err");
        INFO(err);  // usually one of them says "waiting for another bake"; the held-lock test checks that
        check_index_matches_files(out);
        CHECK(::access((out + "/" + brdfbake::BakeFolder::lock_name()).c_str(), F_OK) != 0);  // removed after

        // Whichever bake ran last, baking A into the folder now leaves A's tables described.
        const auto r = run_cli("bake " + a + " -o " + out);
        REQUIRE(r.status == 0);
        check_index_matches_files(out);
        std::system(("rm -rf " + out).c_str());
    }
    std::remove(a.c_str());
    std::remove(c.c_str());
}

TEST_CASE("a table replaced behind the index's back is recomputed by the next bake", "[bake][device]") {
    const std::string a = scene_file("A2", 0.3, 0.95), c = scene_file("C2", 0.7, 0.8);
    const std::string out_a = scratch("repair-a"), out_c = scratch("repair-c");
    REQUIRE(run_cli("bake " + a + " -o " + out_a).status == 0);
    REQUIRE(run_cli("bake " + c + " -o " + out_c).status == 0);
    REQUIRE(exr_size(out_a + "/albedo-ggx.exr") != exr_size(out_c + "/albedo-ggx.exr"));
    // C's table where the index says A's: same name, same request hash in the index, other content.
    REQUIRE(std::system(("cp " + out_c + "/albedo-ggx.exr " + out_a + "/albedo-ggx.exr").c_str()) == 0);
    const auto r = run_cli("bake " + a + " -o " + out_a);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.find("albedo-ggx.exr is not the table index.json describes") != std::string::npos);
    CHECK(r.err.find("baked 1 table (1 up to date)") != std::string::npos);
    check_index_matches_files(out_a);
    CHECK(exr_size(out_a + "/albedo-ggx.exr") != exr_size(out_c + "/albedo-ggx.exr"));
    // A table truncated by a full disk or an edit: the same.
    REQUIRE(::truncate((out_a + "/eavg-ggx.exr").c_str(), 100) == 0);
    const auto again = run_cli("bake " + a + " -o " + out_a);
    REQUIRE(again.status == 0);
    CHECK(again.err.find("baked 1 table (1 up to date)") != std::string::npos);
    check_index_matches_files(out_a);
    // And with nothing touched, nothing is recomputed.
    const auto third = run_cli("bake " + a + " -o " + out_a);
    REQUIRE(third.status == 0);
    CHECK(third.err.find("nothing to compute") != std::string::npos);
    std::system(("rm -rf " + out_a + " " + out_c).c_str());
    std::remove(a.c_str());
    std::remove(c.c_str());
}

TEST_CASE("a bake into a folder another process holds waits up to --lock-timeout, then refuses", "[bake][cli]") {
    const std::string a = scene_file("A3", 0.3, 0.95);
    const std::string out = scratch("held");
    REQUIRE(std::system(("mkdir -p " + out).c_str()) == 0);
    const std::string lock = out + "/" + brdfbake::BakeFolder::lock_name();
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
    REQUIRE(fd >= 0);
    REQUIRE(::flock(fd, LOCK_EX) == 0);

    const auto now = run_cli("bake " + a + " -o " + out + " --lock-timeout 0");
    CHECK(now.status == 2);
    CHECK(now.err.rfind("brdfbake: error: another bake is writing into '" + out + "'", 0) == 0);
    CHECK(testing::count_lines(now.err) == 1);
    const auto later = run_cli("bake " + a + " -o " + out + " --lock-timeout 0.3");
    CHECK(later.status == 2);
    CHECK(later.err.find("brdfbake: waiting for another bake") == 0);
    CHECK(later.err.find("did not finish within 0.3 s") != std::string::npos);
    CHECK(::access((out + "/index.json").c_str(), F_OK) != 0);  // nothing computed or written
    CHECK(run_cli("bake " + a + " -o " + out + " --lock-timeout -1").status == 2);
    ::close(fd);  // releases the lock
    std::system(("rm -rf " + out).c_str());
    std::remove(a.c_str());
}

TEST_CASE("a bake that fails before writing a table leaves no folder behind, -o FILE is refused at once",
          "[bake][cli]") {
    const std::string a = scene_file("A4", 0.3, 0.95);
    const std::string top = scratch("never");
    // The device fails after the folder was created and locked: the folders this bake created go.
    const auto r = run_cli("bake " + a + " -o " + top + "/sub/out --device 7:7");
    CHECK(r.status == 2);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(::access(top.c_str(), F_OK) != 0);
    // A folder that was there stays, and is left as it was (empty).
    REQUIRE(std::system(("mkdir -p " + top).c_str()) == 0);
    CHECK(run_cli("bake " + a + " -o " + top + " --device 7:7").status == 2);
    CHECK(std::system(("test -d " + top + " && test -z \"$(ls -A " + top + ")\"").c_str()) == 0);
    // -o naming a file: refused before any work, the file untouched.
    const std::string file = top + "/file.txt";
    REQUIRE(std::system(("echo keep > " + file).c_str()) == 0);
    const auto f = run_cli("bake " + a + " -o " + file);
    CHECK(f.status == 2);
    CHECK(f.err.find("is not a folder") != std::string::npos);
    CHECK(testing::slurp(file) == "keep\n");
    std::system(("rm -rf " + top).c_str());
    std::remove(a.c_str());
}

TEST_CASE("a deep 3D table's full-size preview lands with its summary or not at all, no temporary stays",
          "[bake][cli]") {
    const std::string out = scratch("deep");
    const std::string scene = "/tmp/brdfbake-bake-" + std::to_string(::getpid()) + "-deep.json";
    std::FILE* f = std::fopen(scene.c_str(), "w");
    std::fprintf(f, "{\"settings\": {\"samples\": 256, \"mu_texels\": 8, \"alpha_texels\": 8},\n"
                    " \"materials\": [{\"name\": \"glass\", \"model\": \"ggx\", \"eta\": [1.3, 1.6], "
                    "\"roughness\": [0.2, 0.4]}]}\n");
    std::fclose(f);
    // The full-size picture's place is taken by a folder: its rename fails, the bake fails, and
    // neither picture's temporary file stays (nor the summary without its full-size picture).
    const std::string previews = out + "/previews", summary = previews + "/dielectric-ggx.exr.png";
    REQUIRE(std::system(("mkdir -p " + previews + "/dielectric-ggx.exr.full.png").c_str()) == 0);
    // An orphan of a killed bake (a process that is gone) goes too.
    const std::string orphan = previews + "/.dielectric-ggx.exr.full.png.tmp-999999999";
    REQUIRE(std::system(("touch " + orphan).c_str()) == 0);
    const auto r = run_cli("bake " + scene + " -o " + out + " --no-report");
    CHECK(r.status == 2);
    CHECK(r.err.find("brdfbake: error: ") != std::string::npos);
    CHECK(r.err.find("dielectric-ggx.exr.full.png") != std::string::npos);
    CHECK(std::system(("test -z \"$(ls -A " + previews + " | grep -e '\\.tmp-')\"").c_str()) == 0);
    CHECK(::access(summary.c_str(), F_OK) != 0);
    CHECK(::access((out + "/dielectric-ggx.exr").c_str(), F_OK) != 0);
    // With the place free, both land and the index names them.
    REQUIRE(std::system(("rmdir " + previews + "/dielectric-ggx.exr.full.png").c_str()) == 0);
    REQUIRE(run_cli("bake " + scene + " -o " + out + " --no-report -q").status == 0);
    const auto index = nlohmann::json::parse(testing::slurp(out + "/index.json"));
    CHECK(index["tables"][0]["preview"] == "previews/dielectric-ggx.exr.png");
    CHECK(index["tables"][0]["preview_full"] == "previews/dielectric-ggx.exr.full.png");
    CHECK(::access((previews + "/dielectric-ggx.exr.full.png").c_str(), R_OK) == 0);
    std::system(("rm -rf " + out).c_str());
    std::remove(scene.c_str());
}

// A bake killed at any moment (issue 31, item 2): every table file in the folder is listed in
// index.json with its content hash; an entry can be ahead of its file only between the two
// renames that commit a table (one entry at most, which the next bake recomputes); the next bake
// leaves no temporary file, preview temporary or staging folder of the killed one behind.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "scene/bake_folder.h"
#include "support.h"

namespace {

using Clock = std::chrono::steady_clock;

std::string scratch(const std::string& name) {
    const std::string dir = "/tmp/brdfbake-kill-" + std::to_string(::getpid()) + "-" + name;
    std::system(("rm -rf " + dir).c_str());
    return dir;
}

/// Eight tables (albedo and eavg of four models), each computed in a fraction of a second.
std::string scene_file() {
    const std::string path = "/tmp/brdfbake-kill-" + std::to_string(::getpid()) + "-scene.json";
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fprintf(f, "{\"settings\": {\"samples\": 2048, \"mu_texels\": 16, \"alpha_texels\": 32},\n"
                    " \"materials\": [\n"
                    "  {\"name\": \"a\", \"model\": \"ggx\", \"roughness\": [0.2, 0.8]},\n"
                    "  {\"name\": \"b\", \"model\": \"beckmann\", \"roughness\": [0.2, 0.8]},\n"
                    "  {\"name\": \"c\", \"model\": \"ggx:shadowing=separable\", \"roughness\": [0.2, 0.8]},\n"
                    "  {\"name\": \"d\", \"model\": \"beckmann:shadowing=separable\", \"roughness\": [0.2, 0.8]}]}\n");
    std::fclose(f);
    return path;
}

pid_t start_bake(const std::string& scene, const std::string& out) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1);
        ::dup2(null, 2);
        ::execl(BRDFBAKE_EXE, BRDFBAKE_EXE, "bake", scene.c_str(), "-o", out.c_str(), "--no-report", (char*)nullptr);
        ::_exit(127);
    }
    return pid;
}

std::vector<std::string> names_in(const std::string& dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) names.push_back(e.path().filename().string());
    return names;
}

bool is_file(const std::string& path) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

/// The folder's table files (not hidden, not the index or the report page).
std::vector<std::string> table_files(const std::string& dir) {
    std::vector<std::string> out;
    for (const auto& n : names_in(dir))
        if (n[0] != '.' && n != "index.json" && n != "index.html" && is_file(dir + "/" + n)) out.push_back(n);
    return out;
}

/// How the index and the folder disagree: table files the index does not list (`unlisted`), and
/// entries whose file is absent or not the one they describe (`stale`).
struct Disagreement {
    int unlisted = 0, stale = 0;
    std::string what;
};

Disagreement compare_index(const std::string& dir) {
    Disagreement d;
    std::map<std::string, std::string> listed;  // file -> content hash
    if (is_file(dir + "/index.json")) {
        const auto index = nlohmann::json::parse(testing::slurp(dir + "/index.json"));
        for (const auto& e : index.at("tables")) listed[e.at("file")] = e.at("content_hash");
    }
    for (const auto& f : table_files(dir))
        if (!listed.count(f)) {
            ++d.unlisted;
            d.what += f + " is in the folder but not in the index; ";
        }
    for (const auto& [file, hash] : listed)
        if (!is_file(dir + "/" + file) || brdfbake::content_hash_of_file(dir + "/" + file) != hash) {
            ++d.stale;
            d.what += file + " is listed but absent or another file; ";
        }
    return d;
}

bool index_agrees(const std::string& dir, std::string& why) {
    const Disagreement d = compare_index(dir);
    why = d.what;
    return d.unlisted == 0 && d.stale == 0;
}

/// Files a killed bake may leave and the next bake must remove: temporaries, staging folders.
std::vector<std::string> leftovers(const std::string& dir) {
    std::vector<std::string> out;
    for (const std::string& sub : {std::string(), std::string("/previews")})
        for (const auto& n : names_in(dir + sub))
            if (n.find(".tmp-") != std::string::npos || n.rfind(".brdfbake-staging-", 0) == 0) out.push_back(sub + n);
    return out;
}

}  // namespace

TEST_CASE("a bake killed at any moment leaves an index that agrees with its folder", "[bake][device][slow]") {
    const std::string scene = scene_file();
    // The length of a whole bake, to place timed kills across it.
    const std::string whole = scratch("whole");
    const auto t0 = Clock::now();
    REQUIRE(testing::run_cli("bake " + scene + " -o " + whole + " --no-report -q").status == 0);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    std::string why;
    CHECK(index_agrees(whole, why));
    REQUIRE(table_files(whole).size() == 8);

    int kills = 0, unlisted = 0, disagreements = 0;
    pid_t last_killed = 0;  // a process that is gone
    std::string what;
    const std::string out = scratch("killed");
    // Kills when the k-th preview or table appears (a table is committed then), and at moments
    // spread over the bake. The folder keeps what each killed bake left; the next one goes on.
    for (int round = 0; round < 12; ++round) {
        const pid_t pid = start_bake(scene, out);
        bool ended = false;
        int status = 0;
        if (round < 8) {
            const size_t k = size_t(round % 4) + 1;
            const std::string watched = round < 4 ? out + "/previews" : out;
            const size_t before = round < 4 ? names_in(watched).size() : table_files(out).size();
            const auto deadline = Clock::now() + std::chrono::seconds(60);
            while (Clock::now() < deadline) {
                const size_t now = round < 4 ? names_in(watched).size() : table_files(out).size();
                if (now >= before + std::min(k, size_t(8) - std::min(before, size_t(7)))) break;
                if ((ended = ::waitpid(pid, &status, WNOHANG) == pid)) break;
                std::this_thread::sleep_for(std::chrono::microseconds(200));
            }
        } else {
            std::this_thread::sleep_for(std::chrono::duration<double>(seconds * (0.2 + 0.15 * (round - 8))));
        }
        if (!ended) {
            last_killed = pid;
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
        }
        ++kills;
        // Never a table the index does not list. The index is replaced just before the table is
        // renamed in: a kill between those two renames leaves one entry ahead of its file, which
        // the next bake recomputes (checked at the end).
        const Disagreement d = compare_index(out);
        unlisted += d.unlisted;
        if (d.stale > 1) ++disagreements;
        if (d.unlisted || d.stale) what += "after kill " + std::to_string(round) + ": " + d.what + "\n";
        // Start over now and then, so that kills land in early tables too.
        if (round == 3 || round == 7) std::system(("rm -rf " + out).c_str());
    }
    CHECK(kills == 12);
    INFO(what);
    CHECK(unlisted == 0);
    CHECK(disagreements == 0);

    // The next bake finishes what the killed ones began and leaves nothing of theirs.
    const auto r = testing::run_cli("bake " + scene + " -o " + out + " --no-report");
    REQUIRE(r.status == 0);
    CHECK(index_agrees(out, why));
    CHECK(table_files(out).size() == 8);
    CHECK(leftovers(out).empty());
    CHECK(!is_file(out + "/.brdfbake.lock"));

    // A preview's temporary file of a killed bake goes with the next bake, also one that has
    // nothing to compute (it survived such bakes before).
    const std::string orphan = out + "/previews/.albedo-ggx.exr.png.tmp-" + std::to_string(last_killed);
    std::FILE* f = std::fopen(orphan.c_str(), "w");
    REQUIRE(f);
    std::fclose(f);
    const auto again = testing::run_cli("bake " + scene + " -o " + out + " --no-report");
    REQUIRE(again.status == 0);
    CHECK(again.err.find("nothing to compute") != std::string::npos);
    CHECK(leftovers(out).empty());
    std::system(("rm -rf " + out + " " + whole + " " + scene).c_str());
}

TEST_CASE("a bake that stops after taking the folder leaves every table file listed, a replaced one too",
          "[bake][device]") {
    const std::string out = scratch("stopped");
    const std::string scene = std::string(BRDFBAKE_SOURCE_DIR) + "/tests/data/small_bake.json";
    REQUIRE(testing::run_cli("bake " + scene + " -o " + out + " --no-report -q").status == 0);
    // A table replaced behind the index's back (as a bake killed between its two renames leaves
    // it), then a bake of another request that stops before computing (no such device).
    std::FILE* f = std::fopen((out + "/albedo-ggx.exr").c_str(), "a");
    REQUIRE(f);
    std::fputc('x', f);
    std::fclose(f);
    const auto r = testing::run_cli("bake " + scene + " -o " + out + " --no-report --samples 512 --device 9:9");
    CHECK(r.status == 2);
    const Disagreement d = compare_index(out);
    INFO(d.what);
    CHECK(d.unlisted == 0);
    CHECK(d.stale == 1);  // the replaced file, recomputed by the next bake:
    REQUIRE(testing::run_cli("bake " + scene + " -o " + out + " --no-report -q").status == 0);
    std::string why;
    CHECK(index_agrees(out, why));
    std::system(("rm -rf " + out).c_str());
}

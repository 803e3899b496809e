// Output paths: an output replaces a regular file (or creates one) and nothing else. A device, a
// FIFO, a socket or a directory at the path is refused with one line and exit status 2 and left
// as it was; a symbolic link is followed and its target replaced, the link kept; temporary files
// are hidden from "*.ext" globs and the next run into the folder removes those of dead runs.
#include <catch2/catch.hpp>

#include <dirent.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "support.h"

namespace {

std::string scratch_dir(const std::string& name) {
    const std::string dir = "/tmp/brdfbake-outpaths-" + std::to_string(::getpid()) + "-" + name;
    std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str());
    return dir;
}

mode_t lmode(const std::string& path) {
    struct stat st {};
    REQUIRE(::lstat(path.c_str(), &st) == 0);
    return st.st_mode;
}

std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> names;
    if (DIR* d = ::opendir(dir.c_str())) {
        while (const dirent* e = ::readdir(d))
            if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") names.push_back(e->d_name);
        ::closedir(d);
    }
    return names;
}

const std::string kAlbedo = "albedo --model lambert:rho=0.5 --mu 0.5 --samples 4096 --format csv -o ";

void require_refused(const std::string& path, const std::string& kind) {
    const auto r = testing::run_cli(kAlbedo + "'" + path + "'");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(r.err.find("brdfbake: error: refusing to write") == 0);
    CHECK(r.err.find(kind) != std::string::npos);
}

}  // namespace

TEST_CASE("an output never replaces a device, FIFO, socket or directory", "[cli][output]") {
    const std::string dir = scratch_dir("special");

    const std::string fifo = dir + "/pipe.csv";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    require_refused(fifo, "a FIFO");
    CHECK(S_ISFIFO(lmode(fifo)));

    const std::string folder = dir + "/folder.csv";
    REQUIRE(::mkdir(folder.c_str(), 0700) == 0);
    require_refused(folder, "a directory");
    CHECK(S_ISDIR(lmode(folder)));

    const std::string sock = dir + "/socket.csv";
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    REQUIRE(fd >= 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", sock.c_str());
    REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
    require_refused(sock, "a socket");
    CHECK(S_ISSOCK(lmode(sock)));
    ::close(fd);

    // /dev/null itself: run as root, a rename onto it would replace the device.
    require_refused("/dev/null", "a device");
    CHECK(S_ISCHR(lmode("/dev/null")));

    // A table, and its preview, are checked before any work.
    const std::string fifo_png = dir + "/pipe.png";
    REQUIRE(::mkfifo(fifo_png.c_str(), 0600) == 0);
    const auto lut = testing::run_cli("lut albedo --model ggx --size 2x2 --samples 256 -o '" + dir +
                                      "/t.exr' --preview '" + fifo_png + "'");
    CHECK(lut.status == 2);
    CHECK(lut.err.find("a FIFO") != std::string::npos);
    CHECK(::access((dir + "/t.exr").c_str(), F_OK) != 0);

    std::system(("rm -rf '" + dir + "'").c_str());
}

TEST_CASE("an output through a symbolic link replaces the link's target and keeps the link", "[cli][output]") {
    const std::string dir = scratch_dir("link");
    const std::string target = dir + "/real.csv", link = dir + "/link.csv";
    std::ofstream(target) << "old\n";
    REQUIRE(::symlink("real.csv", link.c_str()) == 0);
    const auto r = testing::run_cli(kAlbedo + "'" + link + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(S_ISLNK(lmode(link)));
    const std::string written = testing::slurp(target);
    CHECK(written.find("old") == std::string::npos);
    // The CSV's last row is mu,phi_deg,albedo,error: the albedo of lambert:rho=0.5 is rho, and
    // the cosine-weighted sampler's every weight is rho, so the estimate is exact.
    const std::string last = written.substr(written.rfind('\n', written.size() - 2) + 1);
    const size_t second_comma = last.find(',', last.find(',') + 1);
    REQUIRE(second_comma != std::string::npos);
    CHECK(std::stod(last.substr(second_comma + 1)) == Approx(0.5).margin(1e-12));

    const std::string dangling = dir + "/dangling.csv";
    REQUIRE(::symlink("missing/nothing.csv", dangling.c_str()) == 0);
    const auto d = testing::run_cli(kAlbedo + "'" + dangling + "'");
    CHECK(d.status == 2);
    CHECK(testing::count_lines(d.err) == 1);
    CHECK(d.err.find("symbolic link to nothing") != std::string::npos);
    CHECK(S_ISLNK(lmode(dangling)));
    std::system(("rm -rf '" + dir + "'").c_str());
}

TEST_CASE("temporary files match no output glob and the next run removes those of dead runs", "[cli][output]") {
    const std::string dir = scratch_dir("tmp");
    // A process that is gone: a child that has exited and been reaped.
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    REQUIRE(child > 0);
    ::waitpid(child, nullptr, 0);
    const std::string dead = dir + "/.old.csv.tmp-" + std::to_string(child);
    const std::string dead_old_style = dir + "/old.exr.tmp-" + std::to_string(child) + ".exr";
    const std::string alive = dir + "/.busy.csv.tmp-" + std::to_string(::getpid());
    for (const auto& f : {dead, dead_old_style, alive}) std::ofstream(f) << "partial";

    const auto r = testing::run_cli(kAlbedo + "'" + dir + "/e.csv'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(::access(dead.c_str(), F_OK) != 0);
    CHECK(::access(dead_old_style.c_str(), F_OK) != 0);
    CHECK(::access(alive.c_str(), F_OK) == 0);  // a run still going keeps its file
    for (const std::string& name : entries(dir)) {
        INFO(name);
        // Only the output and the live run's hidden file: nothing ending in .csv but e.csv.
        const bool csv = name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0;
        CHECK((name == "e.csv" || !csv));
        CHECK((name == "e.csv" || name[0] == '.'));
    }
    std::system(("rm -rf '" + dir + "'").c_str());
}

TEST_CASE("a result that cannot be written to standard output is an error", "[cli][output]") {
    const std::string err = "/tmp/brdfbake-outpaths-" + std::to_string(::getpid()) + "-stdout.err";
    for (const std::string& redirect : {std::string(">/dev/full"), std::string(">&-")}) {
        for (const std::string& args : {std::string("albedo --model lambert --mu 0.5 --samples 4096"),
                                        std::string("fresnel --fresnel dielectric:eta=1.5 --theta 0,45")}) {
            const std::string cmd = std::string(BRDFBAKE_EXE) + " " + args + " " + redirect + " 2>" + err;
            const int raw = std::system(cmd.c_str());
            const std::string message = testing::slurp(err);
            INFO(cmd << ": " << message);
            CHECK(WIFEXITED(raw));
            CHECK(WEXITSTATUS(raw) == 2);
            CHECK(message.find("brdfbake: error: cannot write standard output") == 0);
            CHECK(testing::count_lines(message) == 1);
        }
    }
    std::remove(err.c_str());
}

TEST_CASE("a picture that cannot be written stops the run before the table is written", "[cli][output]") {
    const std::string dir = scratch_dir("picture");
    const std::string missing = dir + "/no-such-folder";
    const std::vector<std::pair<std::string, std::string>> runs = {
        {"lut albedo --model ggx --size 2x2 --samples 256 -o '" + dir + "/t.exr' --preview '" + missing + "/p.png'",
         dir + "/t.exr"},
        {"reciprocity --model ggx:alpha=0.3 --resolution 8 -o '" + dir + "/r.exr' --plot '" + missing + "/r.png'",
         dir + "/r.exr"},
        {"albedo --model lambert --mu 0.5 --samples 4096 -o '" + dir + "/a.csv' --plot '" + missing + "/a.png'",
         dir + "/a.csv"},
    };
    for (const auto& run : runs) {
        const auto r = testing::run_cli(run.first);
        INFO(run.first << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(testing::count_lines(r.err) == 1);
        CHECK(r.err.find("does not exist") != std::string::npos);
        CHECK(::access(run.second.c_str(), F_OK) != 0);  // the table (or values) not written either
    }
    CHECK(entries(dir).empty());
    std::system(("rm -rf '" + dir + "'").c_str());
}

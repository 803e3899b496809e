// Faults the user meets outside the computation (issue 31): a full disk, headers a compiler must
// take, text that must read back as the numbers, corrupted part files, FIFOs, and files whose
// numbers or description do not agree. Each case asserts what the README promises: exit status 2
// with one "brdfbake: error:" line naming the fault, and nothing left behind.
#include <catch2/catch.hpp>

#include <dirent.h>
#include <png.h>
#include <sys/wait.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "brdfbake/memory_limit.h"
#include "brdfbake/table.h"
#include "scene/texture_image.h"
#include "support.h"

namespace {

std::string scratch(const std::string& name) {
    std::string dir = "/tmp/brdfbake-faults-" + name + "-" + std::to_string(::getpid());
    std::system(("rm -rf '" + dir + "'").c_str());
    REQUIRE(::mkdir(dir.c_str(), 0700) == 0);
    return dir;
}

std::set<std::string> listing(const std::string& dir) {
    std::set<std::string> names;
    if (DIR* d = ::opendir(dir.c_str())) {
        while (const dirent* e = ::readdir(d))
            if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0) names.insert(e->d_name);
        ::closedir(d);
    }
    return names;
}

std::string names_of(const std::set<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += " " + n;
    return s;
}

/// A 200 kB tmpfs at `dir`, filled up to `room` free bytes by a file "fill"; unmounted at the end.
/// Mounting needs root (CAP_SYS_ADMIN): where the test cannot mount, `mounted` is false.
struct SmallDisk {
    std::string dir;
    bool mounted = false;
    explicit SmallDisk(const std::string& name) : dir(scratch(name)) {
        mounted = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=200k") == 0;
    }
    ~SmallDisk() {
        if (mounted) ::umount2(dir.c_str(), MNT_DETACH);
        ::rmdir(dir.c_str());
    }
    /// Fills the disk, then frees `room` bytes (in whole 4 kB pages).
    void fill(size_t room) {
        const std::string path = dir + "/fill";
        std::FILE* f = std::fopen(path.c_str(), "wb");
        REQUIRE(f);
        std::setvbuf(f, nullptr, _IONBF, 0);
        const std::vector<char> block(4096, 'x');
        size_t written = 0;
        while (std::fwrite(block.data(), 1, block.size(), f) == block.size()) written += block.size();
        std::fclose(f);
        REQUIRE(::truncate(path.c_str(), off_t(written > room ? written - room : 0)) == 0);
    }
};

/// The run failed as a fault must: exit 2, one error line, no libpng or abort text, and the folder
/// holds only its filler.
void require_clean_failure(const testing::CliResult& r, const std::string& dir) {
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("brdfbake: error:") != std::string::npos);
    CHECK(r.err.find("libpng") == std::string::npos);
    CHECK(listing(dir) == std::set<std::string>{"fill"});
    INFO("left:" << names_of(listing(dir)));
}

const std::string kSmallLut = "lut albedo --model ggx --size 8x8 --samples 256 ";

}  // namespace

TEST_CASE("a full disk ends every writer in exit 2 with nothing left", "[faults][output]") {
    SmallDisk disk("full");
    if (!disk.mounted) {
        WARN("SKIPPED: cannot mount a 200 kB tmpfs here (" << std::strerror(errno)
                                                             << "; the test needs root): the full-disk cases did not run");
        return;
    }
    const std::string& d = disk.dir;
    // Room for the CSV (about 5 kB) but not for its preview: the table must not stay alone.
    disk.fill(12 << 10);
    require_clean_failure(testing::run_cli(kSmallLut + "-o " + d + "/t.csv"), d);
    // Room for the .npy's sidecar (about 6 kB) but not for its array (16 kB): neither stays.
    disk.fill(8 << 10);
    require_clean_failure(testing::run_cli("lut albedo --model ggx --size 32x32 --samples 256 --no-preview -o " + d +
                                           "/t.npy"),
                          d);
    // No room at all: every format.
    disk.fill(0);
    for (const char* name : {"t.png", "t.exr", "t.csv", "t.h"})
        require_clean_failure(testing::run_cli(kSmallLut + "--no-preview -o " + d + "/" + name), d);
    require_clean_failure(testing::run_cli("albedo --model ggx:alpha=0.5 --mu 0.2,0.5,1 --samples 256 --plot " + d +
                                           "/p.png"),
                          d);
    require_clean_failure(testing::run_cli("albedo --model ggx:alpha=0.5 --mu 0.2,0.5,1 --samples 256 --plot " + d +
                                           "/p.svg"),
                          d);
}

namespace {

/// Compiles `header` as C and as C++ (syntax only); returns the compilers' complaints, or "".
std::string compile_errors(const std::string& header) {
    std::string errors;
    for (const char* compiler : {"gcc -x c -std=c99", "g++ -x c++ -std=c++17"}) {
        const auto r = testing::run_shell("echo '#include \"" + header + "\"' | " + compiler + " -fsyntax-only -");
        if (r.status != 0) errors += std::string(compiler) + ": " + r.err;
    }
    return errors;
}

/// The values of a .npy brdfbake wrote, parsed from the file's own header (numpy format 1.0).
std::vector<double> npy_values(const std::string& path, std::vector<size_t>* shape) {
    const std::string bytes = testing::slurp(path);
    REQUIRE(bytes.size() > 10);
    REQUIRE(bytes.compare(0, 6, "\x93NUMPY") == 0);
    const size_t len = size_t(static_cast<unsigned char>(bytes[8])) | size_t(static_cast<unsigned char>(bytes[9])) << 8;
    const std::string header = bytes.substr(10, len);
    REQUIRE(header.find("'<f8'") != std::string::npos);
    const size_t open = header.find("'shape': ("), close = header.find(')', open);
    std::istringstream dims(header.substr(open + 10, close - open - 10));
    shape->clear();
    for (std::string d; std::getline(dims, d, ',');)
        if (d.find_first_not_of(' ') != std::string::npos) shape->push_back(std::stoul(d));
    std::vector<double> v((bytes.size() - 10 - len) / 8);
    std::memcpy(v.data(), bytes.data() + 10 + len, v.size() * 8);  // little-endian hosts only
    return v;
}

/// The data rows of a CSV table: every field of each row that is not a comment or the heading.
std::vector<std::vector<double>> csv_rows(const std::string& path, std::vector<std::string>* heading) {
    std::istringstream in(testing::slurp(path));
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::vector<std::string> words;
        for (std::string f; std::getline(fields, f, ',');) words.push_back(f);
        if (heading->empty()) {
            *heading = words;
            continue;
        }
        std::vector<double> row;
        for (const auto& w : words) row.push_back(std::strtod(w.c_str(), nullptr));
        rows.push_back(row);
    }
    return rows;
}

}  // namespace

TEST_CASE("every header brdfbake writes compiles as C and C++", "[faults][formats]") {
    const std::string d = scratch("headers");
    // Whole numbers (0 and 1), the extremes of float and a double table, written by the writer
    // the commands use: each must be a floating literal of the array's type.
    brdfbake::Table t;
    t.kind = "albedo";
    t.quantity = "test values";
    t.x = brdfbake::make_axis("mu", "mu = u", 0.0, 1.0, 4);
    t.y = brdfbake::make_axis("roughness", "alpha = r^2", 0.0, 1.0, 1);
    t.z = brdfbake::make_axis("z", "z", 0.0, 1.0, 1);
    t.channels = {"E", "odd-name"};
    t.values = {{0.0, 1.0, 0.5, 1e-30}, {3e38, 1.0 / 3.0, 2.0, 1e-45}};
    t.error = {0.0, 1e-7, 1.0, 0.0};
    for (const char* precision : {"float", "double"}) {
        t.attributes["precision"] = precision;
        const std::string path = d + "/synthetic_" + precision + ".h";
        brdfbake::write_table(t, path);
        INFO(testing::slurp(path));
        CHECK(compile_errors(path).empty());
        // The values read back: a program prints each array element as the compiler read it.
        std::ofstream(d + "/print.cpp") << "#include <cstdio>\n#include \"" << path
                                        << "\"\nint main() { for (int i = 0; i < 4; ++i) std::printf(\"%.17g %.17g "
                                           "%.17g\\n\", double(brdfbake_synthetic_"
                                        << precision << "_E[i]), double(brdfbake_synthetic_" << precision
                                        << "_odd_name[i]), double(brdfbake_synthetic_" << precision << "_error[i])); }\n";
        const auto run = testing::run_shell("g++ -o " + d + "/print " + d + "/print.cpp && " + d + "/print");
        REQUIRE(run.status == 0);
        std::istringstream printed(run.out);
        for (size_t i = 0; i < 4; ++i) {
            double e = 0, odd = 0, err = 0;
            printed >> e >> odd >> err;
            const bool f = std::string(precision) == "float";
            CHECK(e == (f ? double(float(t.values[0][i])) : t.values[0][i]));
            CHECK(odd == (f ? double(float(t.values[1][i])) : t.values[1][i]));
            CHECK(err == (f ? double(float(t.error[i])) : t.error[i]));
        }
    }
    // Headers of the commands: a table in float, in double, an eavg (1D), a 3D dielectric, and
    // the Cycles preset (double, with E = 1 in its r = 0 column: the "1f" of issue 30).
    for (const std::string& args :
         {std::string("lut --preset cycles --no-preview -o ") + d + "/ggx_E.h",
          std::string("lut albedo --model ggx --size 4x4 --samples 256 --no-preview -o ") + d + "/albedo.h",
          std::string("lut albedo --model ggx --size 4x4 --samples 256 --precision double --no-preview -o ") + d +
              "/albedo_double.h",
          std::string("lut eavg --model ggx --size 4 --samples 256 --no-preview -o ") + d + "/eavg.hpp",
          std::string("lut dielectric --model ggx --size 2x2x2 --samples 256 --no-preview -o ") + d + "/glass.h"}) {
        const auto r = testing::run_cli(args);
        INFO(args << "\n" << r.err);
        REQUIRE(r.status == 0);
        const std::string path = args.substr(args.rfind(' ') + 1);
        INFO(testing::slurp(path));
        CHECK(compile_errors(path).empty());
    }
    std::system(("rm -rf '" + d + "'").c_str());
}

TEST_CASE("a double table's CSV reads back as its .npy exactly", "[faults][formats]") {
    const std::string d = scratch("digits");
    const std::string lut = "lut albedo --model ggx --size 5x3 --samples 4096 --precision double --no-preview -o ";
    // The same deterministic computation written twice, and the .npy converted by show.
    REQUIRE(testing::run_cli(lut + d + "/t.npy").status == 0);
    REQUIRE(testing::run_cli(lut + d + "/t.csv").status == 0);
    REQUIRE(testing::run_cli("show " + d + "/t.npy -o " + d + "/converted.csv").status == 0);
    std::vector<size_t> shape;
    const std::vector<double> npy = npy_values(d + "/t.npy", &shape);
    REQUIRE(shape == std::vector<size_t>{3, 5, 2});  // (roughness, mu, channel: E and error)
    for (const char* name : {"/t.csv", "/converted.csv"}) {
        std::vector<std::string> heading;
        const auto rows = csv_rows(d + name, &heading);
        INFO(name);
        REQUIRE(rows.size() == 15);
        REQUIRE(heading.size() >= 3);
        const size_t value = heading.size() - 2, error = heading.size() - 1;
        for (size_t k = 0; k < rows.size(); ++k) {
            CHECK(rows[k][value] == npy[k * 2]);
            CHECK(rows[k][error] == npy[k * 2 + 1]);
        }
        // Coordinates print exactly too: the centre of texel 1 of 3 on [0, 1] is 0.5, of texel 0 of 5 is 0.1.
        CHECK(rows[0][0] == 0.1);
    }
    std::system(("rm -rf '" + d + "'").c_str());
}

namespace {

/// Writes `text` to `path`.
void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// Runs `command` with a shell timeout: a run that blocks (a FIFO) ends with status 124.
testing::CliResult run_limited(const std::string& args, int seconds = 20) {
    return testing::run_shell("timeout " + std::to_string(seconds) + " " + std::string(BRDFBAKE_EXE) + " " + args);
}

void require_error(const testing::CliResult& r, const std::string& needle) {
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(testing::count_lines(r.err) == 1);
    CHECK(r.err.rfind("brdfbake: error:", 0) == 0);
    CHECK(r.err.find(needle) != std::string::npos);
}

}  // namespace

TEST_CASE("merge refuses a part file changed by one digit, and shards split an 8x8 table", "[faults][shard]") {
    const std::string d = scratch("parts");
    const std::string lut = "lut albedo --model ggx --size 8x8 --samples 256 --no-preview ";
    for (int k = 0; k < 2; ++k) {
        const auto r = testing::run_cli(lut + "--shard " + std::to_string(k) + "/2 -o " + d + "/part" +
                                        std::to_string(k) + ".json");
        INFO(r.err);
        REQUIRE(r.status == 0);
        // Each shard holds part of the 64 cells, never none or all (it held 0 and 64).
        const size_t cells = r.err.find(" cells");
        REQUIRE(cells != std::string::npos);
        const int count = std::stoi(r.err.substr(r.err.rfind(' ', cells - 1) + 1));
        CHECK(count > 8);
        CHECK(count < 56);
    }
    REQUIRE(testing::run_cli("merge " + d + "/part0.json " + d + "/part1.json -o " + d + "/merged.csv").status == 0);
    REQUIRE(testing::run_cli(lut + "-o " + d + "/whole.csv").status == 0);
    CHECK(testing::slurp(d + "/merged.csv") == testing::slurp(d + "/whole.csv"));

    // One hex digit of a record changed: the checksum no longer matches, exit 2, nothing written.
    std::string part = testing::slurp(d + "/part1.json");
    const size_t cells = part.find("\"cells\"");
    REQUIRE(cells != std::string::npos);
    const size_t digit = part.find_first_of("0123456789abcdef", part.find(": \"", cells + 10) + 3);
    part[digit] = part[digit] == '0' ? '1' : '0';
    write_text(d + "/bad.json", part);
    require_error(testing::run_cli("merge " + d + "/part0.json " + d + "/bad.json -o " + d + "/t.csv"),
                  "bad.json' is corrupted");
    CHECK(::access((d + "/t.csv").c_str(), F_OK) != 0);
    std::system(("rm -rf '" + d + "'").c_str());
}

TEST_CASE("show and merge refuse a FIFO instead of waiting on it", "[faults][input]") {
    const std::string d = scratch("fifo");
    for (const char* name : {"t.exr", "t.csv", "t.npy", "part.json"}) REQUIRE(::mkfifo((d + "/" + name).c_str(), 0600) == 0);
    write_text(d + "/u.npy", "not read");
    REQUIRE(::mkfifo((d + "/u.npy.json").c_str(), 0600) == 0);
    for (const char* name : {"t.exr", "t.csv", "u.npy"}) require_error(run_limited("show " + d + "/" + name), "not a regular file");
    require_error(run_limited("merge " + d + "/part.json -o " + d + "/m.csv"), "not a regular file");
    std::system(("rm -rf '" + d + "'").c_str());
}

TEST_CASE("readers refuse NaN, Inf and descriptions that disagree with the data, naming the field", "[faults][input]") {
    const std::string d = scratch("readers");
    REQUIRE(testing::run_cli("lut albedo --model ggx --size 4x2 --samples 256 --no-preview -o " + d + "/t.npy").status == 0);
    REQUIRE(testing::run_cli("show " + d + "/t.npy -o " + d + "/t.csv").status == 0);
    REQUIRE(testing::run_cli("show " + d + "/t.csv").status == 0);
    const std::string npy = testing::slurp(d + "/t.npy"), side = testing::slurp(d + "/t.npy.json"),
                      csv = testing::slurp(d + "/t.csv");
    auto replaced = [](std::string text, const std::string& from, const std::string& to) {
        const size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        return text.replace(at, from.size(), to);
    };
    auto case_npy = [&](const std::string& array, const std::string& sidecar, const std::string& needle) {
        write_text(d + "/c.npy", array);
        write_text(d + "/c.npy.json", sidecar);
        require_error(testing::run_cli("show " + d + "/c.npy"), needle);
    };
    // A NaN value and an infinite error in the array.
    std::string nan_array = npy, inf_array = npy;
    const double nan = std::nan(""), inf = HUGE_VAL;
    std::memcpy(&nan_array[npy.size() - 8 * 2], &nan, 8);  // texel (3, 1)'s value
    std::memcpy(&inf_array[npy.size() - 8], &inf, 8);       // texel (3, 1)'s error
    case_npy(nan_array, side, "channel E holds nan at texel (3, 1)");
    case_npy(inf_array, side, "the error channel holds inf at texel (3, 1)");
    // The sidecar: a range that is not finite, an unknown kind, its shape, dtype, axes, channels.
    case_npy(npy, replaced(side, "\"x_range\": \"0 1\"", "\"x_range\": \"nan 1\""), "x_range 'nan'");
    case_npy(npy, replaced(side, "\"kind\": \"albedo\"", "\"kind\": \"albedo2\""), "kind 'albedo2'");
    case_npy(npy, replaced(side, "\"dtype\": \"<f8\"", "\"dtype\": \"<f4\""), "dtype '<f4'");
    case_npy(npy, replaced(side, "\"channels\": [\n    \"E\"", "\"channels\": [\n    \"F\""), "channels");
    case_npy(npy, replaced(side, "\"name\": \"mu\"", "\"name\": \"sqrt_mu\""), "axes[1]");
    case_npy(npy, replaced(side, "\"x_size\": \"4\"", "\"x_size\": \"2\""), "shape");
    case_npy(replaced(npy, "'shape': (2, 4, 2)", "'shape': (4, 2, 2)"), side, "the array's shape (4, 2, 2)");
    // A CSV with a NaN value, an Inf error, a size that is not a whole number.
    const size_t last = csv.rfind('\n', csv.size() - 2) + 1;
    std::string row = csv.substr(last);
    const size_t value_at = row.find(',', row.find(',') + 1) + 1;  // mu, roughness, then E
    write_text(d + "/c.csv", csv.substr(0, last) + row.substr(0, value_at) + "nan" + row.substr(row.find(',', value_at)));
    require_error(testing::run_cli("show " + d + "/c.csv"), "channel E holds nan");
    write_text(d + "/c.csv", csv.substr(0, csv.rfind(',')) + ",inf\n");
    require_error(testing::run_cli("show " + d + "/c.csv"), "the error channel holds inf");
    write_text(d + "/c.csv", replaced(csv, "# x_size: 4", "# x_size: 4.5"));
    require_error(testing::run_cli("show " + d + "/c.csv"), "x_size '4.5'");
    std::system(("rm -rf '" + d + "'").c_str());
}

TEST_CASE("help and version to a full stdout, and a closed pipe, exit 2 with the message", "[faults][cli]") {
    for (const char* args : {"--help", "--version", "lut --help"}) {
        const auto r = testing::run_shell("(" + std::string(BRDFBAKE_EXE) + " " + args + " >/dev/full)");
        INFO(args << ": " << r.err);
        CHECK(r.status == 2);
        CHECK(r.err.find("brdfbake: error: cannot write standard output") != std::string::npos);
    }
    // A reader that is gone before the first byte: the write fails (EPIPE) and the README's
    // promise holds (exit 2, one line), where SIGPIPE used to end the process silently.
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    ::close(fds[0]);
    const std::string err_path = "/tmp/brdfbake-faults-pipe-" + std::to_string(::getpid()) + ".err";
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        ::dup2(fds[1], 1);
        std::FILE* err = std::freopen(err_path.c_str(), "w", stderr);
        (void)err;
        ::execl(BRDFBAKE_EXE, BRDFBAKE_EXE, "--help", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(fds[1]);
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    const std::string err = testing::slurp(err_path);
    std::remove(err_path.c_str());
    INFO(err);
    REQUIRE(WIFEXITED(status));  // not killed by SIGPIPE
    CHECK(WEXITSTATUS(status) == 2);
    CHECK(err.find("cannot write standard output: Broken pipe") != std::string::npos);
}

TEST_CASE("a name whose temporary file cannot exist is refused before any work", "[faults][output]") {
    const std::string d = scratch("names");
    // 251 characters: the name fits (255), its temporary ".NAME.tmp-PID" does not.
    const std::string long_name = std::string(247, 'n') + ".csv", long_preview = std::string(247, 'p') + ".png";
    const std::string heavy = "lut albedo --model ggx --size 64x64 --samples 4194304 ";  // minutes, if it ran
    auto timed = [](const std::string& args) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto r = testing::run_cli(args);
        return std::make_pair(r, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    };
    const auto [table, table_s] = timed(heavy + "-o " + d + "/" + long_name);
    require_error(table, "give a shorter name");
    CHECK(table_s < 10);
    const auto [preview, preview_s] = timed(heavy + "-o " + d + "/t.csv --preview " + d + "/" + long_preview);
    require_error(preview, "give a shorter name");
    CHECK(preview_s < 10);
    // The sidecar of a .npy is longer than the array's name: 246 + ".npy" fits, its ".json" temporary not.
    require_error(testing::run_cli(heavy + "-o " + d + "/" + std::string(240, 'a') + ".npy"), "give a shorter name");
    CHECK(listing(d).empty());
    std::system(("rm -rf '" + d + "'").c_str());
}

namespace {

void append_bytes(png_structp png, png_bytep data, png_size_t n) {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}

/// An 8-bit RGB PNG, w x h, every sample `fill` but pixel (x0, y0) = lo and (x1, y1) = hi in
/// channel 1; interlaced (Adam7) or not.
std::string png_bytes(unsigned w, unsigned h, bool interlaced, unsigned x0, unsigned y0, unsigned x1, unsigned y1) {
    std::string out;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_set_write_fn(png, &out, append_bytes, nullptr);
    png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const int passes = png_set_interlace_handling(png);
    std::vector<png_byte> row(size_t(w) * 3);
    for (int pass = 0; pass < passes; ++pass)
        for (unsigned y = 0; y < h; ++y) {
            std::fill(row.begin(), row.end(), png_byte(100));
            if (y == y0) row[size_t(x0) * 3 + 1] = 7;
            if (y == y1) row[size_t(x1) * 3 + 1] = 201;
            png_write_row(png, row.data());
        }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return out;
}

}  // namespace

TEST_CASE("a PNG texture's ranges are read a row at a time, whatever its size", "[faults][texture]") {
    // 4000 x 4000 RGB decodes to 48 MB: under a 4 MB limit it was refused; read a row at a time
    // it needs 12 kB, and its ranges are the samples it holds.
    const std::string big = png_bytes(4000, 4000, false, 3999, 3998, 17, 2500);
    brdfbake::set_memory_limit(std::uint64_t(4) << 20);
    const brdfbake::ChannelRanges r = brdfbake::png_channel_ranges(big, "texture big.png");
    CHECK(r.width == 4000);
    CHECK(r.height == 4000);
    CHECK(r.lo[0] == 100 / 255.0);
    CHECK(r.hi[0] == 100 / 255.0);
    CHECK(r.lo[1] == 7 / 255.0);
    CHECK(r.hi[1] == 201 / 255.0);
    CHECK(r.lo[3] == 1.0);
    // Interlaced: each pixel comes in one of seven passes; the extremes sit in the last pass
    // (odd rows) and in a middle one.
    const brdfbake::ChannelRanges a = brdfbake::png_channel_ranges(png_bytes(37, 23, true, 5, 7, 2, 4), "texture a.png");
    CHECK(a.lo[1] == 7 / 255.0);
    CHECK(a.hi[1] == 201 / 255.0);
    CHECK(a.lo[2] == 100 / 255.0);
    CHECK(a.hi[2] == 100 / 255.0);
    brdfbake::set_memory_limit(0);
}

// The fuzz test (issue 16): random and mutated model and Fresnel specs (every registered model),
// n,k files, scene JSON and glTF, run through albedo, fresnel, check, reciprocity, lut, plan and
// bake, and (issue 31, directed cases) hostile tables, a corrupted part file and FIFOs through
// show and merge; tests/test_faults.cpp has the full disks, and the cases that need files made
// by brdfbake itself. For every run it asserts what holds for any input:
//   - the exit status is 0, 1 or 2, the run ends by itself (no signal) within its time limit;
//   - no NaN or infinity in standard output or in any written file (EXR files read back with
//     OpenEXR, text files scanned for nan/inf, JSON for null);
//   - after exit status 2 nothing is left in the output folder, and never a temporary file.
//
// CI runs a fixed seed and a few hundred small cases; scripts/fuzz.sh runs more with any seed.
// Environment: BRDFBAKE_FUZZ_SEED (default 16), BRDFBAKE_FUZZ_COUNT (default 200),
// BRDFBAKE_FUZZ_ONLY (one case index), BRDFBAKE_FUZZ_TIMEOUT (seconds per run, default 20),
// BRDFBAKE_FUZZ_JOBS (runs at a time, default 2),
// BRDFBAKE_FUZZ_HOSTILE=1 (also /dev/zero and /dev/urandom as input files: memory-hungry),
// BRDFBAKE_FUZZ_VERBOSE=1 (every case with its exit status and time).
// Every case is reproducible alone from its seed and index; a failing case prints its command
// line and keeps its folder.
#include <catch2/catch.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <dirent.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <mutex>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "scene/bake_folder.h"
#include "support.h"

namespace {

using json = nlohmann::json;

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

std::string source_dir() {
    const std::string here = __FILE__;
    return here.substr(0, here.find_last_of('/')) + "/..";
}

/// The random choices of one case.
class Gen {
public:
    explicit Gen(std::uint64_t seed) : rng_(seed) {}
    bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
    int between(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    template <class T>
    const T& pick(const std::vector<T>& v) { return v[size_t(between(0, int(v.size()) - 1))]; }
    std::mt19937_64& rng() { return rng_; }

    /// A number as text: mostly plausible, often hostile (huge, tiny, negative, NaN, not a number).
    std::string number() {
        static const std::vector<std::string> hostile = {
            "0",    "-0",    "1",      "-1",     "2",     "10",    "1e3",  "1e6",   "1e30",   "1e100",
            "1e155", "1e308", "1e309", "-1e308", "1e-10", "1e-300", "5e-324", "nan",  "NaN",    "-nan",
            "inf",  "-inf",  "infinity", "",     "abc",   "0x1p-3", " 0.5", "0.5 ",  "+0.5",   "1e",
            ".",    "-",     "99999999999999999999999", "0.5.5", "1/2", "1e-5", "0.999999"};
        const double p = uniform(0, 1);
        const double hostile_share = level == 0 ? 0.0 : level == 1 ? 0.15 : 0.35;
        if (p < hostile_share) return pick(hostile);
        if (level == 0 || p < hostile_share + 0.35) return fmt(uniform(0.01, 1.0));
        if (p < hostile_share + 0.55) return fmt(uniform(-0.5, 1.5));
        return fmt(std::pow(10.0, uniform(-300, 300)) * (chance(0.2) ? -1 : 1));  // any magnitude
    }
    /// How hostile the case is: 0 plausible values only (most runs compute something), 1 some
    /// hostile values, 2 many.
    int level = 1;
    /// p scaled by the level: none at 0, p at 1, twice p at 2.
    bool mutate(double p) { return chance(p * level); }
    static std::string fmt(double x) {
        char b[40];
        std::snprintf(b, sizeof b, "%.6g", x);
        return b;
    }
    std::string list(int max_items) {
        std::string s;
        const int n = between(1, max_items);
        for (int i = 0; i < n; ++i) s += (i ? "," : "") + number();
        return s;
    }

private:
    std::mt19937_64 rng_;
};

// --- specs ---------------------------------------------------------------------------------------

/// Every registered model's example spec, split into name and keys.
const std::vector<brdfbake::Spec>& model_examples() {
    static const std::vector<brdfbake::Spec> all = [] {
        std::vector<brdfbake::Spec> out;
        for (const auto& m : brdfbake::model_registry()) {
            if (m.layer_walk) continue;  // a layer's walk has no pointwise f; its refusals: test_sheen_volume_model.cpp
            out.push_back(brdfbake::parse_spec(brdfbake::resolve_model(m.example).canonical));
        }
        return out;
    }();
    return all;
}

std::string join_spec(const brdfbake::Spec& s) {
    std::string out = s.name;
    for (size_t i = 0; i < s.keys.size(); ++i)
        out += (i ? "," : ":") + s.keys[i].first + (s.keys[i].second == "\x01" ? "" : "=" + s.keys[i].second);
    return out;
}

/// A model spec: a registered model's example with its values mutated, keys dropped or added,
/// or its name or syntax broken. `roughness` false drops alpha keys (for lut's `--model`).
std::string model_spec(Gen& g, bool roughness = true) {
    brdfbake::Spec s = g.pick(model_examples());
    std::vector<std::pair<std::string, std::string>> keys;
    for (auto kv : s.keys) {
        if (kv.first == "alpha" && roughness && g.chance(0.3)) {  // anisotropic: then --phi matters
            keys.push_back({"alpha_x", g.chance(0.7) ? Gen::fmt(g.uniform(0.01, 1)) : g.number()});
            keys.push_back({"alpha_y", g.chance(0.7) ? Gen::fmt(g.uniform(0.01, 1)) : g.number()});
            continue;
        }
        if (!roughness && kv.first.rfind("alpha", 0) == 0 && !g.mutate(0.05)) continue;
        if (g.mutate(0.05)) continue;                         // a key dropped
        const bool numeric = kv.second.find_first_not_of("0123456789.e+-") == std::string::npos;
        if (g.mutate(0.15) || (numeric && g.chance(0.3))) kv.second = g.number();  // a value changed
        if (g.mutate(0.015)) kv.second = "\x01";               // `key` without `=value`
        keys.push_back(kv);
    }
    if (g.mutate(0.05)) keys.push_back({g.pick(std::vector<std::string>{"beta", "alpha", "ALPHA", "", "n", "eta"}), g.number()});
    if (g.mutate(0.02)) keys.push_back(keys.empty() ? std::make_pair(std::string("alpha"), g.number()) : keys.front());
    if (g.mutate(0.02)) s.name = g.pick(std::vector<std::string>{"", "GGX", "ggx ", "nosuchmodel", "ggx:ggx", "\xff"});
    s.keys = keys;
    std::string out = join_spec(s);
    if (g.mutate(0.02)) out += g.pick(std::vector<std::string>{",", ":", "=", ",,", "=1=2", ":a=1"});
    return out;
}

/// A Fresnel spec; `nk_file` is an n,k file of the case, or empty.
std::string fresnel_spec(Gen& g, const std::string& nk_file) {
    switch (g.between(0, g.level == 0 ? 7 : 8)) {
    case 0: return "none";
    case 1: return "schlick:f0=" + g.number();
    case 2: return "dielectric:eta=" + g.number();
    case 3: return "conductor:eta=" + g.number() + ",k=" + g.number();
    case 4: return "conductor-approx:eta=" + g.number() + ",k=" + g.number();
    case 5: return "metal:" + (g.mutate(0.15) ? g.pick(std::vector<std::string>{"Xx", "", "au"})
                                              : g.pick(std::vector<std::string>{"Al", "Au", "Ag", "Cu"}));
    case 6:
    case 7: return nk_file.empty() ? "metal:Au" : "nk:" + nk_file;
    default: return g.pick(std::vector<std::string>{"", "schlick", "schlick:f0", "dielectric:eta=1.5,eta=2", "nk:",
                                                    "nk:/nonexistent.yml", "conductor:eta=1", "x:y=z"});
    }
}

// --- input files ---------------------------------------------------------------------------------

void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

/// An n,k file in the refractiveindex.info YAML layout brdfbake reads, with random rows (sorted
/// or not, huge, negative, NaN), or empty, or binary garbage.
std::string nk_text(Gen& g) {
    const int kind = g.level == 0 ? 9 : g.between(0, 9);
    if (kind == 0) return "";
    if (kind == 1) {
        std::string bytes(size_t(g.between(1, 4096)), '\0');
        for (auto& c : bytes) c = char(g.between(0, 255));
        return bytes;
    }
    std::ostringstream o;
    if (kind != 2) o << "DATA:\n  - type: tabulated nk\n    data: |\n";
    if (kind == 4) {  // plausible wavelengths, hostile n and k (huge, zero, negative)
        static const std::vector<std::string> values = {"1e308", "1e155", "1e100", "1e30", "1e10", "0", "-1", "1e-300"};
        for (double w = 0.3; w < 1.6; w += 0.1)
            o << "        " << Gen::fmt(w) << " " << g.pick(values) << " " << g.pick(values) << "\n";
        return o.str();
    }
    const int rows = kind == 3 ? g.between(2000, 20000) : g.between(0, 8);
    double w = g.uniform(0.2, 0.5);
    for (int i = 0; i < rows; ++i) {
        w += g.chance(0.9) ? g.uniform(0.001, 0.1) : -g.uniform(0, 0.2);
        o << "        " << (g.chance(0.9) ? Gen::fmt(w) : g.number());
        const int cols = g.chance(0.9) ? 2 : g.between(0, 4);
        for (int c = 0; c < cols; ++c)
            o << " " << (g.chance(0.7) ? Gen::fmt(g.uniform(0.05, 8)) : g.number());
        o << "\n";
    }
    if (g.chance(0.1)) o << "  - type: tabulated n\n    data: |\n        0.5 1.5\n";
    return o.str();
}

/// The value a mutated JSON node takes.
json mutant_value(Gen& g, const std::string& nk_file) {
    switch (g.between(0, 9)) {
    case 0: return nullptr;
    case 1: return g.chance(0.5);
    case 2: {
        const std::string t = g.number();
        char* end = nullptr;
        const double v = std::strtod(t.c_str(), &end);
        if (end != t.c_str() && *end == 0 && std::isfinite(v)) return v;
        return t;
    }
    case 3: return g.uniform(-1, 2);
    case 4: return json::array({g.uniform(-0.5, 1.5), g.uniform(-0.5, 1.5)});
    case 5: return model_spec(g);
    case 6: return fresnel_spec(g, nk_file);
    case 7: return json::object();
    case 8: return json::array();
    default: return g.pick(std::vector<std::string>{"", "ggx", "lambert:rho=0.5", "dfg-ms", "albedo", "dielectric",
                                                    "conductor", "eavg", "nosuchkind", "data:,", "missing.bin"});
    }
}

/// Mutates a JSON document in place: values replaced, keys removed or added, array items
/// duplicated or removed.
void mutate_json(Gen& g, json& j, const std::string& nk_file, int depth = 0) {
    if (j.is_object()) {
        std::vector<std::string> keys;
        for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
        for (const auto& k : keys) {
            if (g.chance(0.06)) j.erase(k);
            else if (g.chance(0.12)) j[k] = mutant_value(g, nk_file);
            else if (depth < 6) mutate_json(g, j[k], nk_file, depth + 1);
        }
        if (g.chance(0.05))
            j[g.pick(std::vector<std::string>{"alpha", "roughness", "eta", "tables", "transmission", "samples",
                                              "eta_step", "ior", "extensions", "name", "x"})] = mutant_value(g, nk_file);
    } else if (j.is_array()) {
        if (!j.empty() && g.chance(0.08)) j.push_back(j[size_t(g.between(0, int(j.size()) - 1))]);
        if (!j.empty() && g.chance(0.06)) j.erase(size_t(g.between(0, int(j.size()) - 1)));
        for (auto& x : j)
            if (g.chance(0.1)) x = mutant_value(g, nk_file);
            else if (depth < 6) mutate_json(g, x, nk_file, depth + 1);
    }
}

/// A scene file: a mutated copy of one under examples/ or tests/data, as JSON or bytes.
std::string scene_file(Gen& g, const std::string& dir, const std::string& nk_file) {
    static const std::vector<std::string> bases = {"examples/scene.json",        "examples/scene.gltf",
                                                   "tests/data/small_bake.json", "tests/data/small_glass.json",
                                                   "tests/data/metals_glass.json", "tests/data/merge.json",
                                                   "tests/data/materials.gltf",  "tests/data/truncated.glb"};
    const std::string base = g.pick(bases);
    const std::string ext = base.substr(base.find_last_of('.'));
    std::string text = testing::slurp(source_dir() + "/" + base);
    if (ext != ".glb" && g.chance(0.8)) {
        json j = json::parse(text, nullptr, false);
        if (!j.is_discarded()) {
            const int rounds = g.between(0, g.level + 1);
            for (int r = 0; r < rounds; ++r) mutate_json(g, j, nk_file);
            // Invalid UTF-8 from a mutated spec becomes U+FFFD; the byte edits below add raw bytes.
            text = j.dump(g.chance(0.5) ? 2 : -1, ' ', false, json::error_handler_t::replace);
        }
    }
    if (g.mutate(0.08) && !text.empty()) {  // bytes: flipped, cut or inserted
        const int edits = g.between(1, 4);
        for (int e = 0; e < edits && !text.empty(); ++e) {
            const size_t at = size_t(g.between(0, int(text.size()) - 1));
            switch (g.between(0, 2)) {
            case 0: text[at] = char(g.between(0, 255)); break;
            case 1: text.resize(at); break;
            default: text.insert(at, g.pick(std::vector<std::string>{"{", "}", "\"", ",", "[", "\\u0000", "1e999"})); break;
            }
        }
    }
    const std::string path = dir + "/scene" + ext;
    write_text(path, text);
    return path;
}

// --- one run and what it must satisfy --------------------------------------------------------------

struct Case {
    std::string args;  // the command line after `brdfbake`
    std::string dir;   // the case's folder: in/ holds inputs, out/ receives outputs
};

/// The failures issues 16 and 31 reported, as cases run before the random ones in every run (so
/// that CI meets them whatever its seed finds). `in` receives their input files.
std::vector<std::string> directed_cases(const std::string& in, const std::string& out) {
    write_text(in + "/huge.yml", "DATA:\n  - type: tabulated nk\n    data: |\n        0.3 1e308 1e308\n"
                                 "        0.4 1e308 1e308\n        0.6 1e308 1e308\n");
    write_text(in + "/h155.yml", "DATA:\n  - type: tabulated nk\n    data: |\n        0.3 1e155 1e155\n"
                                 "        0.6 1e155 1e155\n");
    write_text(in + "/huge_scene.json", "{\"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"fresnel\": \"nk:" + in +
                                            "/huge.yml\", \"wavelength\": 500, \"roughness\": 0.5, \"tables\": [\"conductor\"]}]}\n");
    const std::string aniso = "albedo --model ggx:alpha_x=0.1,alpha_y=0.5 --mu 0.5";
    // Issue 31's readers: tables whose numbers or description no table holds (each field in turn
    // made hostile), a corrupted part file, and FIFOs, through show and merge.
    std::vector<std::string> readers;
    const std::vector<std::pair<std::string, std::string>> fields = {
        {"# x_range: 0 1", "# x_range: nan 1"}, {"# x_size: 2", "# x_size: 2.5"}, {"# x_size: 2", "# x_size: 1e300"},
        {"# kind: albedo", "# kind: nosuchkind"}, {"0.25,0.5,", "0.25,nan,"}, {"0.25,0.5,", "0.25,-inf,"},
        {",0.001\n0.75", ",inf\n0.75"}, {"0.25,0.5,", "0.25,1e999,"}};
    const std::string table = "# kind: albedo\n# quantity: test\n# x_axis: mu\n# x_mapping: mu = u\n# x_range: 0 1\n"
                              "# x_size: 2\n# channels: E error\nmu,E,error\n0.25,0.5,0.001\n0.75,0.5,0.001\n";
    for (size_t k = 0; k < fields.size(); ++k) {
        std::string text = table;
        text.replace(text.find(fields[k].first), fields[k].first.size(), fields[k].second);
        const std::string path = in + "/hostile" + std::to_string(k) + ".csv";
        write_text(path, text);
        readers.push_back("show " + path + (k % 2 ? " --format json" : ""));
        readers.push_back("show " + path + " -o " + out + "/converted.npy");
    }
    write_text(in + "/part.json", "{\"format\": \"brdfbake part file 2\", \"version\": \"0\", \"source\": \"0\", "
                                  "\"command\": [\"lut\"], \"shard\": 0, \"shards\": 1, \"texts\": [], "
                                  "\"cells\": {\"00\": \"00\"}, \"checksum\": \"0000000000000000\"}\n");
    readers.push_back("merge " + in + "/part.json -o " + out + "/merged.csv");
    ::mkfifo((in + "/fifo.csv").c_str(), 0600);
    ::mkfifo((in + "/fifo.exr").c_str(), 0600);
    ::mkfifo((in + "/fifo.json").c_str(), 0600);
    readers.push_back("show " + in + "/fifo.csv");
    readers.push_back("show " + in + "/fifo.exr");
    readers.push_back("merge " + in + "/fifo.json -o " + out + "/merged.csv");
    std::vector<std::string> cases = {
        aniso + " --phi 1e100 --method quadrature --format csv",
        aniso + " --phi 1e100 --method quadrature --format json",
        aniso + " --phi 1e100 --format table",
        aniso + " --phi 1e12 --method quadrature --precision double --format csv",
        "fresnel --fresnel nk:" + in + "/huge.yml --wavelength 500 --theta 0",
        "fresnel --fresnel nk:" + in + "/h155.yml --wavelength 500 --theta 0,45 --format json",
        "check --model ggx:alpha=0.3 --fresnel nk:" + in + "/huge.yml --wavelength 500 --directions 4 --phis 2 "
        "--samples 1024 --resolution 4 --phi-resolution 4 --format json",
        "reciprocity --model ggx:alpha=0.3 --fresnel nk:" + in + "/huge.yml --wavelength 500 --resolution 4 "
        "--phi-resolution 4 -o " + out + "/recip.exr",
        "lut conductor --model ggx --fresnel nk:" + in + "/huge.yml --wavelength 500 --size 4x4 --samples 256 "
        "--no-preview -o " + out + "/table.exr",
        "albedo --model ggx:alpha=0.5 --fresnel nk:" + in + "/huge.yml --wavelength 500 --mu 0.5 --samples 1024 --format json",
        "bake " + in + "/huge_scene.json -o " + out + "/bake --samples 64 --mu-texels 4 --alpha-texels 4 --no-previews --no-report",
    };
    cases.insert(cases.end(), readers.begin(), readers.end());
    return cases;
}

/// The case of index i of a seed: one command with its generated inputs.
Case make_case(std::uint64_t seed, std::uint64_t index, const std::string& root, bool hostile) {
    Gen g(seed * 0x9E3779B97F4A7C15ULL + index);
    g.level = g.chance(0.45) ? 0 : g.chance(0.5) ? 1 : 2;
    Case c;
    c.dir = root + "/case-" + std::to_string(index);
    std::system(("rm -rf " + c.dir + " && mkdir -p " + c.dir + "/in " + c.dir + "/out").c_str());
    const std::string in = c.dir + "/in", out = c.dir + "/out";

    std::string nk;
    if (g.chance(0.35)) {
        if (hostile && g.chance(0.1)) nk = g.chance(0.5) ? "/dev/zero" : "/dev/urandom";
        else {
            nk = in + "/metal.yml";
            write_text(nk, nk_text(g));
        }
    }
    auto wavelength = [&] {
        if (!(g.level == 0 || g.chance(0.6))) return std::string();
        return " --wavelength '" + (g.level == 0 || g.chance(0.6) ? Gen::fmt(g.uniform(300, 1200)) : g.number()) + "'";
    };
    std::string extension = "txt";  // of a text output file: json for --format json, csv for csv
    auto format = [&](const std::vector<std::string>& f) {
        if (!g.chance(0.6)) return std::string();
        const std::string chosen = g.pick(f);
        extension = chosen == "table" ? "txt" : chosen;
        return " --format " + chosen;
    };
    auto precision = [&] { return g.chance(0.3) ? " --precision " + g.pick(std::vector<std::string>{"float", "double"}) : ""; };
    std::ostringstream a;
    switch (g.between(0, 9)) {
    case 0:
    case 1:
        a << "albedo --model '" << model_spec(g) << "'";
        if (g.chance(0.5)) a << " --fresnel '" << fresnel_spec(g, nk) << "'";
        a << wavelength();
        if (g.chance(0.6)) a << " --mu '" << g.list(3) << "'";
        if (g.chance(0.4)) a << " --phi '" << g.list(3) << "'";
        if (g.chance(0.15)) a << " --tolerance 1e-3 --max-samples 65536";
        else a << " --samples " << g.pick(std::vector<std::string>{"256", "1024", "4096", "7"});
        if (g.chance(0.4)) a << " --method " << g.pick(std::vector<std::string>{"auto", "importance", "qmc", "mc", "quadrature"});
        a << precision() << format({"table", "json", "csv"});
        if (g.chance(0.3)) a << " -o " << out << "/albedo." << extension;
        break;
    case 2:
        a << "fresnel --fresnel '" << fresnel_spec(g, nk) << "'" << wavelength();
        if (g.chance(0.6)) a << " --theta '" << g.list(4) << "'";
        a << precision() << format({"table", "json", "csv"});
        if (g.chance(0.3)) a << " -o " << out << "/fresnel." << extension;
        break;
    case 3:
        a << "check --model '" << model_spec(g) << "'";
        if (g.chance(0.4)) a << " --fresnel '" << fresnel_spec(g, nk) << "'";
        a << wavelength() << " --directions 4 --phis 2 --samples 1024 --resolution 4 --phi-resolution 4" << precision()
          << format({"table", "json"});
        if (g.chance(0.3)) a << " -o " << out << "/check." << extension;
        break;
    case 4:
        a << "reciprocity --model '" << model_spec(g) << "'";
        if (g.chance(0.4)) a << " --fresnel '" << fresnel_spec(g, nk) << "'";
        a << wavelength() << " --resolution " << (g.mutate(0.15) ? g.pick(std::vector<std::string>{"0", "-3", "1", "x"}) : "4")
          << " --phi-resolution " << g.pick(std::vector<std::string>{"4", "3", "1"}) << precision();
        a << " -o " << out << "/recip." << g.pick(std::vector<std::string>{"exr", "csv", "h"});
        break;
    case 5:
    case 6: {
        std::vector<std::string> kinds;
        for (const auto* k : brdfbake::table_kinds()) kinds.push_back(k->name);
        const std::string kind = g.mutate(0.05) ? "nosuchkind" : g.pick(kinds);
        // A model with a roughness axis (but now and then one without); a Fresnel the kind takes.
        std::string model = model_spec(g, false);
        for (int tries = 0; tries < 20 && !g.mutate(0.05); ++tries) {
            const std::string name = model.substr(0, model.find(':'));
            const auto& reg = brdfbake::model_registry();
            if (std::any_of(reg.begin(), reg.end(), [&](const brdfbake::ModelTraits& m) {
                    return name == m.name && m.alpha_x_slot >= 0 && !m.delta;
                }))
                break;
            model = model_spec(g, false);
        }
        a << "lut " << kind << " --model '" << model << "'";
        if (kind == "conductor" && !g.mutate(0.2))
            a << " --fresnel '" << g.pick(std::vector<std::string>{"metal:Au", "conductor:eta=" + g.number() + ",k=" + g.number(),
                                                                   nk.empty() ? "metal:Cu" : "nk:" + nk}) << "'";
        else if (kind != "dielectric" && g.chance(0.3)) a << " --fresnel '" << fresnel_spec(g, nk) << "'";
        a << wavelength();
        const bool one_d = kind == "eavg", three_d = kind == "dielectric";
        std::string size = one_d ? std::to_string(g.between(1, 6))
                                 : std::to_string(g.between(1, 5)) + "x" + std::to_string(g.between(1, 5)) +
                                       (three_d ? "x" + std::to_string(g.between(1, 3)) : "");
        if (g.mutate(0.1)) size = g.pick(std::vector<std::string>{"0x4", "4x", "-1x4", "1e9x1e9", "abc", "4x4x4x4", "", "100000x100000"});
        a << " --size '" << size << "' --samples " << g.pick(std::vector<std::string>{"256", "1024"});
        auto range = [&](double lo, double hi) {
            if (g.mutate(0.3)) return g.list(3);
            double a0 = g.uniform(lo, hi), a1 = g.uniform(lo, hi);
            if (a0 > a1) std::swap(a0, a1);
            return Gen::fmt(a0) + "," + Gen::fmt(a1);
        };
        if (g.chance(0.3)) a << " --alpha-range '" << range(0, 1) << "'";
        if (g.chance(0.3) || three_d) a << " --eta-range '" << range(1.01, 3) << "'";
        if (g.chance(0.2)) a << " --mu-map sqrt";
        if (g.chance(0.2)) a << " --alpha-map roughness";
        if (g.chance(0.1)) a << " --half";
        a << precision() << " --no-preview -o " << out << "/table." << g.pick(std::vector<std::string>{"exr", "csv", "h"});
        break;
    }
    case 7:
        a << "plan " << scene_file(g, in, nk) << format({"table", "json"});
        if (g.chance(0.5)) a << " --samples 64 --mu-texels 4 --alpha-texels 4";
        break;
    default:
        a << "bake " << scene_file(g, in, nk) << " -o " << out << "/bake --samples 64 --mu-texels 4 --alpha-texels 4 --no-previews --no-report";
        if (g.chance(0.3)) a << " --table-format " << g.pick(std::vector<std::string>{"exr", "csv", "h"});
        if (g.chance(0.1)) a << " --half";
        a << precision();
        break;
    }
    c.args = a.str();
    return c;
}

/// Every file under `dir` (hidden ones included), as paths.
void list_files(const std::string& dir, std::vector<std::string>& out) {
    DIR* d = ::opendir(dir.c_str());
    if (!d) return;
    while (const dirent* e = ::readdir(d)) {
        const std::string name = e->d_name;
        if (name == "." || name == "..") continue;
        const std::string path = dir + "/" + name;
        struct stat st {};
        if (::lstat(path.c_str(), &st) != 0) continue;
        if (S_ISDIR(st.st_mode)) list_files(path, out);
        else out.push_back(path);
    }
    ::closedir(d);
}

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// "nan", "inf", "infinity" as words (not inside "info" or "infinite"), but for check's label
/// "0 NaN or Inf" (a count of them).
bool has_non_finite_text(const std::string& text) {
    static const std::regex word(R"((^|[^A-Za-z_])[-+]?(nan|inf|infinity)([^A-Za-z_]|$))", std::regex::icase);
    static const std::regex label(R"(NaN or Inf)");
    return std::regex_search(std::regex_replace(text, label, "values"), word);
}

bool has_null(const json& j) {
    if (j.is_null()) return true;
    if (j.is_structured())
        for (const auto& x : j)
            if (has_null(x)) return true;
    return false;
}

/// Why a written file holds a non-finite value, or "".
std::string non_finite_in_file(const std::string& path) {
    if (ends_with(path, ".exr")) {
        try {
            Imf::InputFile in(path.c_str());
            const Imath::Box2i dw = in.header().dataWindow();
            const long w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
            for (auto c = in.header().channels().begin(); c != in.header().channels().end(); ++c) {
                std::vector<float> v(size_t(w * h));
                Imf::FrameBuffer fb;
                fb.insert(c.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()) -
                                                               (dw.min.x + long(dw.min.y) * w) * long(sizeof(float)),
                                               sizeof(float), sizeof(float) * size_t(w)));
                in.setFrameBuffer(fb);
                in.readPixels(dw.min.y, dw.max.y);
                for (float x : v)
                    if (!std::isfinite(x)) return std::string("channel ") + c.name() + " holds " + std::to_string(x);
            }
        } catch (const std::exception& e) {
            return std::string("unreadable EXR: ") + e.what();
        }
        return "";
    }
    if (ends_with(path, ".png")) return "";
    const std::string text = testing::slurp(path);
    if (has_non_finite_text(text)) return "nan/inf in the text";
    if (ends_with(path, ".json")) {
        const json j = json::parse(text, nullptr, false);
        if (j.is_discarded()) return "not valid JSON";
        if (has_null(j)) return "null in the JSON";
    }
    return "";
}

/// A failure the lead or another owner is fixing (issue 16): matched by command line and kind of
/// failure, counted and printed, never silent. Remove an entry when its fix is merged.
struct KnownBug {
    const char* name;
    std::regex args;
    std::regex failure;
};

const std::vector<KnownBug>& known_bugs() {
    // Bugs the fuzz has found and whose fix has not landed: {name, args regex, failure regex}.
    // Empty: the phi reduction and the n,k bounds of issue 16 (items 3 and 4) fixed the three
    // it found first (phi = 1e100, n = k = 1e308, nk:/dev/urandom).
    static const std::vector<KnownBug> bugs = {};
    return bugs;
}

struct Outcome {
    std::string failure;  // empty: every assertion held
    std::string known;    // the known bug it matches, or empty
    int status = -1;
    double seconds = 0.0;
};

Outcome run_case(const Case& c, int timeout_s) {
    const std::string o = c.dir + "/stdout", e = c.dir + "/stderr";
    // 4 GiB of address space (or PoCL's minimum plus 1 GiB on a machine with many threads) keeps
    // a runaway input from taking the machine's memory; see README "Limits".
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    const unsigned long kib = std::max(4096ul, 512ul + 80ul * threads + 1024ul) * 1024ul;
    const std::string cmd = "cd " + c.dir + " && timeout -s KILL " + std::to_string(timeout_s) + " sh -c 'ulimit -v " +
                            std::to_string(kib) + "; exec \"$0\" \"$@\"' " + BRDFBAKE_EXE + " " + c.args + " >" + o +
                            " 2>" + e + " </dev/null";
    const auto t0 = std::chrono::steady_clock::now();
    const int raw = std::system(cmd.c_str());
    Outcome r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    const std::string out = testing::slurp(o), err = testing::slurp(e);
    std::remove(o.c_str());
    std::remove(e.c_str());
    std::string failure;
    if (status == 137 || status == 124) failure = "no exit within " + std::to_string(timeout_s) + " s (killed)";
    else if (status >= 128) failure = "killed by signal " + std::to_string(status - 128);
    else if (status < 0 || status > 2) failure = "exit status " + std::to_string(status);
    if (failure.empty() && has_non_finite_text(out)) failure = "nan/inf on standard output";
    if (failure.empty()) {
        const json j = json::parse(out, nullptr, false);
        if (!j.is_discarded() && has_null(j)) failure = "null in the JSON on standard output";
    }
    std::vector<std::string> files;
    list_files(c.dir + "/out", files);
    // A bake that fails after finishing some tables keeps them (docs/scenes.md): after exit 2,
    // what is in its folder must be index.json and the tables it lists, each with its hash.
    const std::string bake_dir = c.dir + "/out/bake";
    const json index = json::parse(testing::slurp(bake_dir + "/index.json"), nullptr, false);
    auto indexed = [&](const std::string& path) {
        if (path == bake_dir + "/index.json") return !index.is_discarded();
        if (index.is_discarded() || !index.contains("tables")) return false;
        for (const auto& t : index["tables"])
            if (bake_dir + "/" + t.value("file", "") == path)
                return t.value("content_hash", "") == brdfbake::content_hash_of_file(path);
        return false;
    };
    for (const auto& f : files) {
        if (!failure.empty()) break;
        const std::string name = f.substr(f.find_last_of('/') + 1);
        if (name.find(".tmp-") != std::string::npos || name == ".brdfbake.lock") failure = "temporary file left: " + f;
        else if (status == 2 && !indexed(f)) failure = "file left after exit status 2: " + f;
        else if (const std::string why = non_finite_in_file(f); !why.empty()) failure = f + ": " + why;
    }
    if (failure.empty() && status == 2 && files.empty()) {
        struct stat st {};
        if (::stat(bake_dir.c_str(), &st) == 0) failure = "empty bake folder left after exit status 2";
    }
    r.status = status;
    if (failure.empty()) return r;
    r.failure = failure + " (exit " + std::to_string(status) + "); stderr: " + err.substr(0, 400);
    for (const auto& k : known_bugs())
        if (std::regex_search(c.args, k.args) && std::regex_search(r.failure, k.failure)) {
            r.known = k.name;
            break;
        }
    return r;
}

}  // namespace

TEST_CASE("fuzz: random and mutated specs, n,k files and scenes across the commands", "[fuzz]") {
    const std::uint64_t seed = env_number("BRDFBAKE_FUZZ_SEED", 16);
    const std::uint64_t count = env_number("BRDFBAKE_FUZZ_COUNT", 200);
    const int timeout_s = int(env_number("BRDFBAKE_FUZZ_TIMEOUT", 20));
    const unsigned jobs = unsigned(std::max<std::uint64_t>(1, env_number("BRDFBAKE_FUZZ_JOBS", 2)));
    const bool hostile = env_number("BRDFBAKE_FUZZ_HOSTILE", 0) != 0;
    const bool verbose = env_number("BRDFBAKE_FUZZ_VERBOSE", 0) != 0;
    const char* only = std::getenv("BRDFBAKE_FUZZ_ONLY");
    const std::string root = "/tmp/brdfbake-fuzz-" + std::to_string(::getpid());
    std::uint64_t first = 0, last = count;
    if (only && *only) {
        first = std::strtoull(only, nullptr, 10);
        last = first + 1;
    }

    // The directed cases first (unless one random case is asked for), each in its own folder.
    std::vector<Case> directed;
    if (!(only && *only)) {
        const std::string in = root + "/directed-inputs";
        std::system(("mkdir -p " + in).c_str());
        const std::vector<std::string> args = directed_cases(in, "OUT");
        for (size_t k = 0; k < args.size(); ++k) {
            Case c;
            c.dir = root + "/directed-" + std::to_string(k);
            std::system(("mkdir -p " + c.dir + "/out").c_str());
            c.args = std::regex_replace(args[k], std::regex("OUT/"), c.dir + "/out/");
            directed.push_back(c);
        }
    }
    const std::uint64_t n_directed = directed.size();

    // `jobs` cases at a time (each run is one brdfbake process); judged afterwards, in order.
    const std::uint64_t total = n_directed + (last - first);
    std::vector<Case> cases(total);
    std::vector<Outcome> outcomes(total);
    std::atomic<std::uint64_t> next{0};
    std::mutex log;
    auto worker = [&] {
        for (std::uint64_t k; (k = next++) < total;) {
            const std::uint64_t i = k < n_directed ? k : first + (k - n_directed);
            Case c;
            Outcome r;
            try {
                c = k < n_directed ? directed[k] : make_case(seed, i, root, hostile);
                r = run_case(c, timeout_s);
            } catch (const std::exception& e) {
                r.failure = std::string("the fuzz harness itself failed: ") + e.what();
            }
            if (verbose) {
                std::lock_guard<std::mutex> lock(log);
                std::fprintf(stderr, "fuzz: %s %llu exit %d in %.2f s: brdfbake %s\n", k < n_directed ? "directed" : "case",
                             static_cast<unsigned long long>(i), r.status, r.seconds, c.args.c_str());
            }
            if (r.failure.empty()) std::system(("rm -rf " + c.dir).c_str());
            cases[k] = std::move(c);
            outcomes[k] = std::move(r);
        }
    };
    std::vector<std::thread> pool;
    for (unsigned k = 0; k < jobs; ++k) pool.emplace_back(worker);
    for (auto& t : pool) t.join();

    int failures = 0, known = 0;
    for (std::uint64_t k = 0; k < total; ++k) {
        const Case& c = cases[k];
        const Outcome& r = outcomes[k];
        if (r.failure.empty()) continue;
        const std::uint64_t i = k < n_directed ? k : first + (k - n_directed);
        const std::string where = k < n_directed ? "directed case " + std::to_string(k) + ": brdfbake " + c.args
                                                 : "seed " + std::to_string(seed) + " case " + std::to_string(i) +
                                                       ": brdfbake " + c.args;
        if (!r.known.empty()) {
            ++known;
            std::cerr << "fuzz: known bug [" << r.known << "] " << where << "\n    " << r.failure << "\n";
            continue;
        }
        ++failures;
        std::cerr << "fuzz: FAILED " << where << "\n    " << r.failure << "\n    inputs kept in " << c.dir;
        if (k >= n_directed) std::cerr << " (BRDFBAKE_FUZZ_SEED=" << seed << " BRDFBAKE_FUZZ_ONLY=" << i << " reruns it)";
        std::cerr << "\n";
        INFO(where);
        INFO(r.failure);
        CHECK(r.failure.empty());
    }
    std::cerr << "fuzz: seed " << seed << ", " << n_directed << " directed and " << (last - first)
              << " random cases: " << failures << " failed, " << known
              << " matched a known bug (listed above)\n";
    if (failures == 0) std::system(("rm -rf " + root).c_str());
}

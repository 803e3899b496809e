#include "scene/calibration.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <set>
#include <sstream>
#include <thread>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "brdfbake/table_kinds.h"
#include "models/input_file.h"

namespace brdfbake {

namespace {

using json = nlohmann::json;

constexpr const char* kFormat = "brdfbake-calibration";
constexpr int kVersion = 2;  // 1: a rate and a fixed time per kind (replaced)
/// Measurements a running mean (or a line's runs) keeps: older ones fade out.
constexpr int kMeanOf = 8;
/// Runs of one size a line keeps.
constexpr int kRunsPerSize = 2;
/// A calibration file is a few KiB; a larger one is not ours.
constexpr std::uintmax_t kMaxFileBytes = 1 << 20;

std::string this_host() {
    char name[256] = {0};
    if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
    return name;
}

unsigned this_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

/// A figure from its JSON object {"value": V, "measurements": N}; throws a line saying what is wrong.
CalibratedFigure figure_of(const json& j, const std::string& name) {
    if (!j.is_object() || !j.contains("value") || !j["value"].is_number() || !j.contains("measurements") ||
        !j["measurements"].is_number_integer())
        throw std::runtime_error("'" + name + "' is not {\"value\": V, \"measurements\": N}");
    CalibratedFigure f;
    f.value = j["value"].get<double>();
    f.measurements = j["measurements"].get<int>();
    if (!positive_finite(f.value) || f.measurements < 1)
        throw std::runtime_error("'" + name + "' has value " + j["value"].dump() + " and " + j["measurements"].dump() +
                                 " measurements (a positive value of at least 1 measurement)");
    return f;
}

/// A line from its JSON object {"runs": [[size, seconds], ...]}; throws a line saying what is wrong.
CalibratedLine line_of(const json& j, const std::string& name) {
    if (!j.is_object() || !j.contains("runs") || !j["runs"].is_array())
        throw std::runtime_error("'" + name + "' is not {\"runs\": [[size, seconds], ...]}");
    CalibratedLine line;
    for (const auto& r : j["runs"]) {
        if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number())
            throw std::runtime_error("'" + name + "': a run " + r.dump() + " is not [size, seconds]");
        const double size = r[0].get<double>(), seconds = r[1].get<double>();
        if (!(std::isfinite(size) && size >= 0) || !positive_finite(seconds))
            throw std::runtime_error("'" + name + "': the run " + r.dump() +
                                     " is not a size of at least 0 and a positive time");
        line.runs.emplace_back(size, seconds);
    }
    if (line.runs.size() > size_t(kMeanOf)) line.runs.erase(line.runs.begin(), line.runs.end() - kMeanOf);
    return line;
}

json json_of(const CalibratedLine& l) {
    json runs = json::array();
    for (const auto& [size, seconds] : l.runs) runs.push_back({size, seconds});
    return {{"runs", runs}};
}

json json_of(const CalibratedFigure& f) { return {{"value", f.value}, {"measurements", f.measurements}}; }

/// Fills `c` from the file's JSON; throws std::runtime_error with the reason.
void parse(const json& j, Calibration& c) {
    if (!j.is_object() || j.value("format", "") != kFormat)
        throw std::runtime_error(std::string("it is not a brdfbake calibration (no \"format\": \"") + kFormat + "\")");
    if (j.value("version", 0) != kVersion)
        throw std::runtime_error("its version " + j.value("version", json()).dump() + " is not " + std::to_string(kVersion));
    c.host = j.value("host", "");
    c.hardware_threads = j.value("hardware_threads", 0u);
    c.bakes = j.value("bakes", 0);
    if (j.contains("tables")) {
        if (!j["tables"].is_object()) throw std::runtime_error("'tables' is not an object");
        for (const auto& [key, f] : j["tables"].items()) c.tables[key] = line_of(f, "tables: " + key);
    }
    if (j.contains("previews")) c.previews = line_of(j["previews"], "previews");
    const std::pair<const char*, CalibratedFigure*> singles[] = {{"kernel_build_seconds", &c.build_seconds_per_program},
                                                                 {"report_check_seconds", &c.report_check_seconds}};
    for (const auto& [name, f] : singles)
        if (j.contains(name)) *f = figure_of(j[name], name);
}

std::string utc_now() {
    char s[32];
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    std::strftime(s, sizeof s, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return s;
}

/// mkdir -p of the folder holding `path`.
void make_parent(const std::string& path) {
    for (size_t at = path.find('/', 1); at != std::string::npos; at = path.find('/', at + 1))
        ::mkdir(path.substr(0, at).c_str(), 0755);
}

}  // namespace

void CalibratedFigure::add(double x) {
    if (!positive_finite(x)) return;
    const int n = std::min(measurements, kMeanOf - 1);
    value = (value * n + x) / (n + 1);
    ++measurements;
}

bool Calibration::applies() const {
    return !path.empty() && bakes > 0 && host == this_host() && hardware_threads == this_threads();
}

namespace {

double wall_now() {
    timespec t{};
    ::clock_gettime(CLOCK_MONOTONIC, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// The process's CPU seconds (user and system, every thread: PoCL's workers too).
double cpu_now() {
    rusage u{};
    ::getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

SlowdownClock::SlowdownClock() : wall0_(wall_now()), cpu0_(cpu_now()) {}

double SlowdownClock::wall_seconds() const { return wall_now() - wall0_; }

double SlowdownClock::cpu_seconds() const { return cpu_now() - cpu0_; }

double SlowdownClock::slowdown() const {
    const double cpu = cpu_now() - cpu0_, wall = wall_now() - wall0_;
    if (cpu < 0.02) return 1.0;
    return std::clamp(wall * this_threads() / cpu, 1.0, 100.0);
}

double serial_slowdown(double slowdown) { return std::max(1.0, slowdown / this_threads()); }

double slowdown_from_environment() {
    const char* v = std::getenv("BRDFBAKE_SLOWDOWN");
    if (!v || !*v) return -1.0;
    char* end = nullptr;
    const double x = std::strtod(v, &end);
    if (end == v || *end != '\0' || !(x >= 1.0 && x <= 1000.0))
        throw Error(std::string("BRDFBAKE_SLOWDOWN='") + v +
                    "' is not a number from 1 to 1000 (how much slower than on idle cores the machine runs; unset "
                    "it to let plan measure)");
    return x;
}

double builtin_rate(const std::string& kind, const std::string& model_name) {
    const TableKind* k = find_table_kind(kind);
    double model_cost = 1.0;  // the registry's ModelTraits::sample_cost
    for (const ModelTraits& m : model_registry())
        if (model_name == m.name) model_cost = m.sample_cost;
    return builtin_figures::kSamplesPerSecondPerCore * this_threads() / ((k ? k->sample_cost : 1.0) * model_cost);
}

void CalibratedLine::add(double size, double seconds) {
    if (!(std::isfinite(size) && size >= 0) || !positive_finite(seconds)) return;
    auto same = [&](const std::pair<double, double>& r) { return std::fabs(r.first - size) <= 0.01 * size; };
    // At most kRunsPerSize of one size (the latest), so that repeated small bakes do not push out
    // the one large run that says what the rate is; beyond kMeanOf runs the oldest goes, never
    // the largest size's.
    if (std::count_if(runs.begin(), runs.end(), same) >= kRunsPerSize) runs.erase(std::find_if(runs.begin(), runs.end(), same));
    runs.emplace_back(size, seconds);
    if (runs.size() > size_t(kMeanOf)) {
        double largest = 0;
        for (const auto& r : runs) largest = std::max(largest, r.first);
        for (auto it = runs.begin(); it != runs.end(); ++it)
            if (it->first < largest) {
                runs.erase(it);
                break;
            }
    }
}

double CalibratedLine::slope(double b0) const {
    // Least squares of seconds = a + b size over the runs (Gauss's normal equations).
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, x_max = 0, x_min = 1e300;
    for (const auto& [x, y] : runs) {
        n += 1;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        x_max = std::max(x_max, x);
        x_min = std::min(x_min, x);
    }
    if (n < 2 || !(x_max > 1.5 * x_min)) return -1;  // one size: no slope
    const double det = n * sxx - sx * sx;
    double b = det > 0 ? (n * sxy - sx * sy) / det : -1;
    double a = (sy - b * sx) / n;
    if (a < 0) b = sxy / sxx;  // through the origin
    if (!(b > b0 / 20 && b < b0 * 20)) return -1;  // noise, not a slope
    return b;
}

double CalibratedLine::seconds(double size, double a0, double b0) const {
    if (runs.empty()) return a0 + b0 * size;
    const double b = slope(b0);
    double n = 0, sx = 0, sy = 0;
    for (const auto& [x, y] : runs) {
        n += 1;
        sx += x;
        sy += y;
    }
    if (b > 0) return std::max(0.0, (sy - b * sx) / n) + b * size;
    // The default line, scaled to pass through the runs' mean.
    const double at_mean = a0 + b0 * sx / n;
    return at_mean > 0 ? (a0 + b0 * size) * (sy / n) / at_mean : a0 + b0 * size;
}

double table_seconds(const Calibration* c, const std::string& kind, const std::string& model_name,
                     const std::string& precision, double samples) {
    const double a0 = builtin_figures::kSecondsPerTable;
    double b0 = 1.0 / builtin_rate(kind, model_name);
    if (!c || !c->applies()) return a0 + b0 * samples;
    const auto it = c->tables.find(calibration_rate_key(kind, model_name, precision));
    if (it != c->tables.end() && !it->second.runs.empty()) return it->second.seconds(samples, a0, b0);
    // This machine's speed against the built-in rates, from every kind with a fitted slope.
    double logs = 0;
    int n = 0;
    for (const auto& [key, line] : c->tables) {
        std::istringstream words(key);
        std::string k_name, m_name, p_name;
        words >> k_name >> m_name >> p_name;
        if (p_name != precision || !find_table_kind(k_name)) continue;
        const double k_b0 = 1.0 / builtin_rate(k_name, m_name), b = line.slope(k_b0);
        if (b > 0) {
            logs += std::log(k_b0 / b);
            ++n;
        }
    }
    if (n > 0) b0 /= std::exp(logs / n);
    return a0 + b0 * samples;
}

double preview_seconds(const Calibration* c, double texels) {
    const double a0 = builtin_figures::kSecondsPerPreview, b0 = builtin_figures::kSecondsPerPreviewTexel;
    if (!c || !c->applies()) return a0 + b0 * texels;
    return c->previews.seconds(texels, a0, b0);
}

std::string calibration_rate_key(const std::string& kind, const std::string& model_name, const std::string& precision) {
    return kind + " " + model_name + " " + precision;
}

std::string calibration_path() {
    if (const char* p = std::getenv("BRDFBAKE_CALIBRATION"); p && *p) return std::string(p) == "off" ? "" : p;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x == '/') return std::string(x) + "/brdfbake/calibration.json";
    if (const char* h = std::getenv("HOME"); h && *h == '/') return std::string(h) + "/.cache/brdfbake/calibration.json";
    return {};
}

Calibration read_calibration(const std::string& path) {
    Calibration c;
    c.path = path;
    if (path.empty()) return c;
    struct stat st{};
    if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) {
        c.host = this_host();
        c.hardware_threads = this_threads();
        return c;  // none yet: the first bake writes it
    }
    std::string text;
    try {
        text = read_input_file(path, "calibration file", kMaxFileBytes);
    } catch (const Error& e) {  // a folder, a device, too large, unreadable: never written to
        Calibration ignored;
        ignored.path = path;
        ignored.writable = false;
        ignored.warning = std::string(e.what()) + "; the estimates use the built-in figures, and bakes do not record "
                          "into it (set BRDFBAKE_CALIBRATION to another path or to off)";
        return ignored;
    }
    json j;
    try {
        j = json::parse(text);
        parse(j, c);
    } catch (const std::exception& e) {
        // A file of this format (another version, a bad value) is this program's: the next bake
        // replaces it. Any other file is left alone (the variable may name it by mistake).
        const bool ours = j.is_object() && j.value("format", json()) == kFormat;
        Calibration ignored;
        ignored.path = path;
        ignored.writable = ours;
        ignored.host = this_host();
        ignored.hardware_threads = this_threads();
        std::string why = e.what();
        if (dynamic_cast<const json::parse_error*>(&e)) why = "it is not valid JSON";
        else if (dynamic_cast<const json::exception*>(&e)) why = "a value of the wrong type";
        ignored.warning = "calibration file '" + path + "' ignored: " + why + "; the estimates use the built-in figures" +
                          (ours ? " and the next bake replaces it"
                                : ", and bakes do not record into it (remove it, or set BRDFBAKE_CALIBRATION to "
                                  "another path or to off)");
        return ignored;
    }
    if (c.host != this_host() || c.hardware_threads != this_threads()) {
        // Another machine's figures (a shared home folder): this machine starts afresh.
        Calibration fresh;
        fresh.path = path;
        fresh.host = this_host();
        fresh.hardware_threads = this_threads();
        return fresh;
    }
    return c;
}

void add_bake_timings(Calibration& c, const BakeTimings& t) {
    c.host = this_host();
    c.hardware_threads = this_threads();
    ++c.bakes;
    // Idle-core seconds: what the bake measured over how much slower than idle it ran.
    const double s = std::isfinite(t.slowdown) && t.slowdown >= 1 ? t.slowdown : 1.0;
    for (const auto& r : t.tables)
        if (r.samples > 0)
            c.tables[calibration_rate_key(r.kind, r.model_name, r.precision)].add(double(r.samples), r.compute_seconds / s);
    const double serial = serial_slowdown(s);  // previews and builds run on one thread
    for (const auto& [texels, seconds] : t.previews) c.previews.add(texels, seconds / serial);
    if (t.programs > 0 && t.build_seconds > 0) c.build_seconds_per_program.add(t.build_seconds / t.programs / serial);
    if (t.report_checks > 0 && t.report_seconds > 0) c.report_check_seconds.add(t.report_seconds / t.report_checks / s);
}

std::string write_calibration(const Calibration& c) {
    if (c.path.empty() || !c.writable) return {};
    json j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    j["host"] = c.host;
    j["hardware_threads"] = c.hardware_threads;
    j["bakes"] = c.bakes;
    j["updated"] = utc_now();
    j["tables"] = json::object();
    for (const auto& [key, line] : c.tables)
        if (!line.runs.empty()) j["tables"][key] = json_of(line);
    if (!c.previews.runs.empty()) j["previews"] = json_of(c.previews);
    if (c.build_seconds_per_program.known()) j["kernel_build_seconds"] = json_of(c.build_seconds_per_program);
    if (c.report_check_seconds.known()) j["report_check_seconds"] = json_of(c.report_check_seconds);
    make_parent(c.path);
    try {
        write_file_atomically(c.path, j.dump(2) + "\n");
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

}  // namespace brdfbake

#include "scene/calibration.h"

#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "brdfbake/table_kinds.h"

namespace brdfbake {

namespace {

using json = nlohmann::json;

constexpr const char* kFormat = "brdfbake-calibration";
constexpr int kVersion = 1;
/// Measurements a running mean keeps (older ones fade out).
constexpr int kMeanOf = 8;

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
        for (const auto& [key, f] : j["tables"].items()) {
            if (!f.is_object()) throw std::runtime_error("'tables': '" + key + "' is not an object");
            TableFigures& t = c.tables[key];
            if (f.contains("samples_per_second")) t.samples_per_second = figure_of(f["samples_per_second"], key);
            if (f.contains("fixed_seconds")) t.fixed_seconds = figure_of(f["fixed_seconds"], key);
        }
    }
    const std::pair<const char*, CalibratedFigure*> singles[] = {{"preview_seconds", &c.preview_seconds},
                                                                 {"kernel_build_seconds", &c.build_seconds_per_program},
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

double model_sample_cost(const std::string& model_name) {
    // Measured on the same tables: sheen's 32x27 albedo at 16384 samples, 7.0e6 samples/s against
    // GGX's 2.2e8 (the Charlie distribution's sampling is uniform and its visibility term costly).
    static const std::map<std::string, double> costs = {{"sheen", 32.0}};
    const auto it = costs.find(model_name);
    return it == costs.end() ? 1.0 : it->second;
}

TableCost table_cost(const Calibration* c, const std::string& kind, const std::string& model_name,
                     const std::string& precision) {
    const TableKind* k = find_table_kind(kind);
    const double cost = (k ? k->sample_cost : 1.0) * model_sample_cost(model_name);
    TableCost out;
    out.samples_per_second = builtin_figures::kSamplesPerSecondPerCore * this_threads() / cost;
    out.fixed_seconds = builtin_figures::kSecondsPerTable;
    if (!c || !c->applies()) return out;
    // This machine's GGX albedo rate from every measured rate of the precision.
    double logs = 0;
    int n = 0;
    for (const auto& [key, f] : c->tables) {
        std::istringstream words(key);
        std::string k_name, m_name, p_name;
        words >> k_name >> m_name >> p_name;
        const TableKind* kk = find_table_kind(k_name);
        if (!kk || p_name != precision || !f.samples_per_second.known()) continue;
        logs += std::log(f.samples_per_second.value * kk->sample_cost * model_sample_cost(m_name));
        ++n;
    }
    if (n > 0) out.samples_per_second = std::exp(logs / n) / cost;
    const auto it = c->tables.find(calibration_rate_key(kind, model_name, precision));
    if (it == c->tables.end()) return out;
    if (it->second.samples_per_second.known()) out.samples_per_second = it->second.samples_per_second.value;
    if (it->second.fixed_seconds.known()) out.fixed_seconds = it->second.fixed_seconds.value;
    out.calibrated = true;
    return out;
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
    std::ifstream in(path);
    if (!in) {
        c.host = this_host();
        c.hardware_threads = this_threads();
        return c;  // none yet: the first bake writes it
    }
    std::stringstream text;
    text << in.rdbuf();
    try {
        parse(json::parse(text.str()), c);
    } catch (const std::exception& e) {
        Calibration ignored;
        ignored.path = path;
        ignored.writable = false;
        std::string why = e.what();
        if (dynamic_cast<const json::parse_error*>(&e)) why = "it is not valid JSON";
        else if (dynamic_cast<const json::exception*>(&e)) why = "a value of the wrong type";
        ignored.warning = "calibration file '" + path + "' ignored: " + why +
                          "; the estimates use the built-in figures, and bakes do not record into it (remove it, or "
                          "set BRDFBAKE_CALIBRATION to another path or to off)";
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
    for (const auto& r : t.tables) {
        if (!(r.compute_seconds > 0) || r.samples == 0) continue;
        const TableCost now = table_cost(&c, r.kind, r.model_name, r.precision);
        TableFigures& f = c.tables[calibration_rate_key(r.kind, r.model_name, r.precision)];
        const double integrating = double(r.samples) / now.samples_per_second;
        if (integrating >= now.fixed_seconds) {
            // The samples dominate: the rate of what the fixed part leaves (a tenth at least).
            f.samples_per_second.add(double(r.samples) / std::max(r.compute_seconds - now.fixed_seconds, 0.1 * r.compute_seconds));
        } else {
            f.fixed_seconds.add(std::max(r.compute_seconds - integrating, 1e-3));
        }
    }
    for (double p : t.previews) c.preview_seconds.add(p);
    if (t.programs > 0 && t.build_seconds > 0) c.build_seconds_per_program.add(t.build_seconds / t.programs);
    if (t.report_checks > 0 && t.report_seconds > 0) c.report_check_seconds.add(t.report_seconds / t.report_checks);
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
    for (const auto& [key, f] : c.tables) {
        json t = json::object();
        if (f.samples_per_second.known()) t["samples_per_second"] = json_of(f.samples_per_second);
        if (f.fixed_seconds.known()) t["fixed_seconds"] = json_of(f.fixed_seconds);
        if (!t.empty()) j["tables"][key] = t;
    }
    if (c.preview_seconds.known()) j["preview_seconds"] = json_of(c.preview_seconds);
    if (c.build_seconds_per_program.known()) j["kernel_build_seconds"] = json_of(c.build_seconds_per_program);
    if (c.report_check_seconds.known()) j["report_check_seconds"] = json_of(c.report_check_seconds);
    make_parent(c.path);
    const std::string tmp = c.path + ".tmp-" + std::to_string(::getpid());
    const std::string text = j.dump(2) + "\n";
    FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) return "cannot write '" + tmp + "': " + std::strerror(errno);
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok || std::rename(tmp.c_str(), c.path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        return "cannot write '" + c.path + "': " + why;
    }
    return {};
}

}  // namespace brdfbake

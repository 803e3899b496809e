// The plan as text (brdfbake plan --format table) and as JSON (--format json).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

#include "brdfbake/spec.h"
#include "scene/scene.h"
#include "scene/scene_text.h"

namespace brdfbake {

namespace {

using scene_text::join;

/// The table's registry entry.
const TableKind& kind_of(const PlannedTable& t) { return t.kind ? *t.kind : table_kind(t.request.kind); }

std::string human_bytes(double b) {
    char s[32];
    if (b < 1024) std::snprintf(s, sizeof s, "%.0f B", b);
    else if (b < 1024 * 1024) std::snprintf(s, sizeof s, "%.1f KiB", b / 1024);
    else if (b < 1024.0 * 1024 * 1024) std::snprintf(s, sizeof s, "%.1f MiB", b / 1024 / 1024);
    else std::snprintf(s, sizeof s, "%.2f GiB", b / 1024 / 1024 / 1024);
    return s;
}

std::string human_count(double n) {
    char s[32];
    if (n < 1e4) std::snprintf(s, sizeof s, "%.0f", n);
    else if (n < 1e9) std::snprintf(s, sizeof s, "%.1f M", n / 1e6);
    else std::snprintf(s, sizeof s, "%.2f G", n / 1e9);
    return s;
}

std::string human_seconds(double t) {
    char s[32];
    if (t < 0.1) std::snprintf(s, sizeof s, "%.2f s", t);
    else if (t < 120) std::snprintf(s, sizeof s, "%.1f s", t);
    else if (t < 7200) std::snprintf(s, sizeof s, "%.1f min", t / 60);
    else std::snprintf(s, sizeof s, "%.1f h", t / 3600);
    return s;
}

std::string short_num(double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%.4g", v);
    return s;
}

std::string alpha_axis_name(const std::string& map) { return map == "roughness" ? "roughness" : "alpha"; }

std::string size_text(const PlannedTable& t) {
    std::string s = std::to_string(t.request.width) + "x" + std::to_string(t.request.height);
    if (kind_of(t).eta_axis) s += "x" + std::to_string(t.depth);
    return s;
}

/// Where the texel centres sit against the scene's ranges, exactly: on the extremes, or (where an
/// axis stops at alpha 0 or eta 1, or the scene's alpha is below the floor) at which parameter.
std::string centres_text(const PlannedTable& t) {
    if (!t.layout.empty()) return "the full axes of " + t.layout;
    const bool eta_exact = !t.eta || (t.eta_lo_exact && t.eta_hi_exact);
    const bool single = t.alpha.lo == t.alpha.hi && (!t.eta || t.eta->lo == t.eta->hi);
    if (t.alpha_lo_exact && t.alpha_hi_exact && eta_exact)
        return single ? "one texel centred on each value" : "the first and last texel centres sit on the scene's extremes";
    std::string s = "texel centres at alpha " + short_num(t.alpha_centres.lo) +
                    (t.alpha_centres.lo == t.alpha_centres.hi ? "" : ".." + short_num(t.alpha_centres.hi));
    if (t.eta)
        s += ", eta " + short_num(t.eta_centres.lo) +
             (t.eta_centres.lo == t.eta_centres.hi ? "" : ".." + short_num(t.eta_centres.hi));
    std::vector<std::string> why;
    if (!t.alpha_lo_exact)
        why.push_back("alpha from " + short_num(t.alpha.lo) + " up to the first centre is read at it (the axis starts at 0 "
                      "and centres never hold alpha below the floor 1e-4)");
    if (!t.alpha_hi_exact)
        why.push_back("alpha from the last centre up to " + short_num(t.alpha.hi) +
                      " is read at it (the axis stops at the model's largest alpha)");
    if (t.eta && !t.eta_lo_exact)
        why.push_back("eta from " + short_num(t.eta->lo) + " up to the first centre is read at it (the axis starts at 1)");
    if (t.eta && !t.eta_hi_exact)
        why.push_back("eta from the last centre up to " + short_num(t.eta->hi) + " is read at it (the axis stops at 100)");
    return s + "; " + join(why, "; ");
}

}  // namespace

std::string plan_text(const Plan& p) {
    std::ostringstream o;
    size_t n_mat = p.no_table.size();
    std::set<std::string> served;
    for (const auto& t : p.tables)
        for (const auto& m : t.materials) served.insert(m);
    n_mat += served.size();
    std::vector<std::string> all_models = model_names();
    o << "plan for " << p.scene << " (" << p.source << "): " << n_mat << " material" << (n_mat == 1 ? "" : "s") << ", "
      << p.tables.size() << " table" << (p.tables.size() == 1 ? "" : "s");
    if (!p.models.empty())
        o << "; kernels built for " << join(p.models) << " only (" << p.models.size() << " of " << all_models.size()
          << " models)";
    o << "\n";
    double total_s = 0, total_samples = 0, peak_mem = 0, disk = 0;
    for (const auto& t : p.tables) {
        const LutRequest& r = t.request;
        const TableKind& kind = kind_of(t);
        o << "\n  " << t.file << "   " << r.kind << ", " << r.model << ", Fresnel ";
        if (!kind.plan_fresnel.empty()) o << kind.plan_fresnel;
        else o << r.fresnel << (r.wavelength_nm > 0 ? " at " + short_num(r.wavelength_nm) + " nm" : "");
        o << "\n";
        o << "      axes      ";
        const std::string an = alpha_axis_name(r.alpha_map);
        const std::string alpha_axis = an + " " + short_num(r.alpha_lo) + ".." + short_num(r.alpha_hi) + " (" +
                                       std::to_string(kind.one_dimensional ? r.width : r.height) + ")";
        bool measured = false;  // a measured model's table has no roughness axis (kind_albedo.cpp)
        for (const ModelTraits& m : model_registry())
            if (m.name == parse_spec(r.model).name) measured = m.measured;
        if (measured) o << (kind.one_dimensional ? "one texel" : "mu 0..1 (" + std::to_string(r.width) + ", " + r.mu_map + ")")
                        << "; no roughness axis (measured)";
        else if (kind.one_dimensional) o << alpha_axis;
        else o << "mu 0..1 (" << r.width << ", " << r.mu_map << ") x " << alpha_axis;
        if (kind.id == TableKindId::ThinFilm)
            o << " x thickness_nm " << short_num(r.thickness_lo) << ".." << short_num(r.thickness_hi) << " (" << t.depth << ")";
        else if (kind.eta_axis)
            o << " x eta " << short_num(t.eta_lo) << ".." << short_num(t.eta_hi) << " (" << t.depth << ")";
        auto range = [](Interval v) {
            return v.lo == v.hi ? short_num(v.lo) : short_num(v.lo) + ".." + short_num(v.hi);
        };
        if (!measured) {
            o << "\n      scene     alpha " << range(t.alpha);
            if (t.eta) o << ", eta " << range(*t.eta);
            o << " (" << centres_text(t) << ")";
        }
        o << "\n";
        o << "      serves    " << join(t.serves) << "\n";
        o << "      estimate  " << size_text(t) << ", " << human_count(double(t.samples_total)) << " samples ("
          << r.samples << " per cell), " << human_seconds(t.est_seconds) << ", memory "
          << human_bytes(double(t.est_memory)) << ", file " << human_bytes(double(t.file_bytes)) << "\n";
        if (!t.unavailable.empty()) o << "      NOT AVAILABLE " << t.unavailable << "\n";
        total_s += t.est_seconds;
        total_samples += double(t.samples_total);
        peak_mem = std::max(peak_mem, double(t.est_memory));
        disk += double(t.file_bytes);
    }
    o << "\nmaterials:\n";
    for (const auto& m : p.materials) {
        if (m.lobes.empty()) continue;
        o << "  " << m.name << ":";
        for (const auto& l : m.lobes) {
            o << " " << l.role << " (" << l.model_name << ", alpha " << short_num(l.alpha.lo)
              << (l.alpha.lo == l.alpha.hi ? "" : ".." + short_num(l.alpha.hi));
            if (l.eta) o << ", eta " << short_num(l.eta->lo) << (l.eta->lo == l.eta->hi ? "" : ".." + short_num(l.eta->hi));
            o << ", Fresnel " << l.fresnel << ")";
            if (&l != &m.lobes.back()) o << ";";
        }
        o << "\n";
        for (const auto& n : m.notes) o << "      " << n << "\n";
    }
    if (!p.no_table.empty()) {
        o << "\nno table needed:\n";
        for (const auto& m : p.no_table) o << "  " << m << "\n";
    }
    if (!p.warnings.empty()) {
        o << "\nwarnings:\n";
        for (const auto& w : grouped_warnings(p.warnings)) o << "  warning: " << w << "\n";
    }
    o << "\ntotal: " << p.tables.size() << " table" << (p.tables.size() == 1 ? "" : "s") << ", " << human_count(total_samples) << " samples, about "
      << human_seconds(total_s + p.build_seconds + p.startup_seconds + p.report_seconds) << " (" << human_seconds(total_s)
      << " integrating at " << human_count(p.samples_per_second) << " samples/s and writing each table and its preview: "
      << p.throughput_basis << "; " << human_seconds(p.startup_seconds) << " start-up; "
      << human_seconds(p.build_seconds) << " for " << p.programs << " kernel build" << (p.programs == 1 ? "" : "s")
      << (p.cold_builds ? ", PoCL's kernel cache is cold: compiled this once" : ", cached by PoCL")
      << "; " << human_seconds(p.report_seconds) << " for the report's "
      << p.report_checks << " lobe check" << (p.report_checks == 1 ? "" : "s") << ", skipped by --no-report), peak memory " << human_bytes(peak_mem) << ", " << human_bytes(disk)
      << " on disk\n";
    return o.str();
}

std::string plan_json(const Plan& p) {
    nlohmann::ordered_json j;
    j["command"] = "plan";
    j["scene"] = p.scene;
    j["source"] = p.source;
    j["models"] = p.models;
    j["all_models"] = model_names();
    j["tables"] = nlohmann::ordered_json::array();
    double total_s = 0, total_samples = 0;
    for (const auto& t : p.tables) {
        const LutRequest& r = t.request;
        const TableKind& kind = kind_of(t);
        nlohmann::ordered_json a = nlohmann::ordered_json::array();
        if (!kind.one_dimensional) a.push_back({{"name", "mu"}, {"mapping", r.mu_map}, {"lo", 0.0}, {"hi", 1.0}, {"size", r.width}});
        a.push_back({{"name", alpha_axis_name(r.alpha_map)},
                     {"mapping", r.alpha_map == "roughness" ? "alpha = r^2" : "alpha = v"},
                     {"lo", r.alpha_lo},
                     {"hi", r.alpha_hi},
                     {"size", kind.one_dimensional ? r.width : r.height}});
        if (kind.id == TableKindId::ThinFilm)
            a.push_back({{"name", "thickness_nm"}, {"mapping", "thickness_nm = w"}, {"lo", r.thickness_lo},
                         {"hi", r.thickness_hi}, {"size", t.depth}});
        else if (kind.eta_axis)
            a.push_back({{"name", "eta"}, {"mapping", "eta = e"}, {"lo", t.eta_lo}, {"hi", t.eta_hi}, {"size", t.depth}});
        nlohmann::ordered_json e = {{"file", t.file},
                  {"kind", r.kind},
                  {"model", r.model},
                  {"fresnel", r.fresnel},
                  {"axes", a},
                  {"size", size_text(t)},
                  {"alpha_range", {t.alpha.lo, t.alpha.hi}},
                  {"samples_per_cell", r.samples},
                  {"precision", precision_name(r.precision)},
                  {"cells", t.cells},
                  {"samples_total", t.samples_total},
                  {"estimated_seconds", t.est_seconds},
                  {"estimated_memory_bytes", t.est_memory},
                  {"estimated_file_bytes", t.file_bytes},
                  {"serves", t.serves},
                  {"materials", t.materials},
                  {"request_hash", t.hash},
                  {"available", t.unavailable.empty()}};
        if (r.wavelength_nm > 0) e["wavelength_nm"] = r.wavelength_nm;
        if (t.eta) e["eta_range"] = {t.eta->lo, t.eta->hi};
        // The parameters at the first and last texel centres, and whether they are the scene's.
        e["texel_centres"] = {{"alpha", {t.alpha_centres.lo, t.alpha_centres.hi}},
                              {"alpha_on_scene_extremes", t.alpha_lo_exact && t.alpha_hi_exact}};
        if (t.eta) {
            e["texel_centres"]["eta"] = {t.eta_centres.lo, t.eta_centres.hi};
            e["texel_centres"]["eta_on_scene_extremes"] = t.eta_lo_exact && t.eta_hi_exact;
        }
        e["centres_note"] = centres_text(t);
        if (!t.layout.empty()) e["layout"] = t.layout;
        if (!t.unavailable.empty()) e["unavailable"] = t.unavailable;
        j["tables"].push_back(e);
        total_s += t.est_seconds;
        total_samples += double(t.samples_total);
    }
    j["materials"] = nlohmann::ordered_json::array();
    for (const auto& m : p.materials) {
        nlohmann::ordered_json lobes = nlohmann::ordered_json::array();
        for (const auto& l : m.lobes) {
            nlohmann::ordered_json x = {{"role", l.role}, {"model", l.model}, {"fresnel", l.fresnel},
                                        {"alpha_range", {l.alpha.lo, l.alpha.hi}}, {"kinds", kind_names(l.kinds)}};
            if (l.eta) x["eta_range"] = {l.eta->lo, l.eta->hi};
            lobes.push_back(x);
        }
        j["materials"].push_back({{"name", m.name}, {"lobes", lobes}, {"notes", m.notes}});
    }
    j["no_table"] = p.no_table;
    j["warnings"] = p.warnings;
    j["estimate"] = {{"seconds", total_s + p.build_seconds + p.startup_seconds + p.report_seconds},
                     {"startup_seconds", p.startup_seconds},
                     {"report_seconds", p.report_seconds},
                     {"report_checks", p.report_checks},
                     {"integration_seconds", total_s},
                     {"kernel_programs", p.programs},
                     {"kernel_build_seconds", p.build_seconds},
                     {"kernel_cache_cold", p.cold_builds},
                     {"slowdown", p.slowdown},
                     {"samples", total_samples},
                     {"samples_per_second", p.samples_per_second},
                     {"basis", p.throughput_basis}};
    return j.dump(2) + "\n";
}

}  // namespace brdfbake
#include "plot/bake_report.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "brdfbake/brdf/microfacet.h"
#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"
#include "models/merl_file.h"
#include "scene/bake_index.h"
#include "scene/scene.h"
#include "plot/plot.h"

namespace brdfbake {

namespace {

namespace fs = std::filesystem;
using Json = BakeIndexJson;

std::string html(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

/// A table's preview as the report shows it: the picture, and when a full-size picture of every
/// slice lies beside it (a deep 3D table), the picture as a thumbnail linking to it.
std::string preview_html(const std::string& picture, const std::string& full, const std::string& file) {
    const std::string img = "<img src=\"" + html(picture) + "\" alt=\"preview of " + html(file) + "\">";
    if (full.empty()) return "<p>" + img + "</p>\n";
    return "<p><a href=\"" + html(full) + "\">" + img + "</a><br><a href=\"" + html(full) +
           "\">full-size picture</a></p>\n";
}

/// A number as a person writes it: whole numbers in full (16384, not 1.638e+04), others to four
/// significant digits, in exponent form only when very small or very large.
std::string number(double v) {
    char b[32];
    if (v == std::floor(v) && std::fabs(v) < 1e15)
        std::snprintf(b, sizeof b, "%.0f", v);
    else
        std::snprintf(b, sizeof b, "%.4g", v);
    return b;
}

std::string text_of(const Json& j) {
    if (j.is_string()) return j.get<std::string>();
    if (j.is_boolean()) return j.get<bool>() ? "yes" : "no";
    if (j.is_number()) return number(j.get<double>());
    if (j.is_array()) {
        std::string out;
        for (const Json& x : j) out += (out.empty() ? "" : ", ") + text_of(x);
        return out;
    }
    return j.dump();
}

/// A setting's value in words; an empty one says what it means.
std::string setting_text(const std::string& key, const Json& value) {
    const bool empty = value.is_null() || (value.is_array() && value.empty()) ||
                       (value.is_string() && value.get<std::string>().empty());
    if (!empty) return text_of(value);
    if (key == "tables") return "each lobe's default kinds";
    return "none";
}

/// The spec of `model` at roughness alpha: the swept parameter set by its key.
std::string at_alpha(const std::string& model, double alpha) {
    const size_t colon = model.find(':');
    return colon == std::string::npos ? model + ":alpha=" + number(alpha)
                                      : model.substr(0, colon + 1) + "alpha=" + number(alpha) + "," + model.substr(colon + 1);
}

/// One lobe's check at one roughness: "PASS" or "VIOLATION" and the report's lines.
struct Verdict {
    std::string spec, fresnel, text;
    bool passed = true, ran = false;
};

Verdict check_lobe(Engine& engine, const std::string& model, const std::string& fresnel, double alpha,
                   const CheckOptions& options) {
    Verdict v;
    v.fresnel = fresnel;
    // A range that starts below the microfacet floor (glTF's roughness 0) is checked at the floor,
    // where a table clamps its texels (include/brdfbake/brdf/microfacet.h, BB_ALPHA_MIN).
    std::string note;
    if (alpha < BB_ALPHA_MIN) {
        note = "The range starts at alpha = " + number(alpha) + ", below the smallest alpha the models take (" +
               number(BB_ALPHA_MIN) + ", where the table clamps its texels): checked there.\n";
        alpha = BB_ALPHA_MIN;
    }
    v.spec = at_alpha(model, alpha);
    try {
        ModelConfig m;
        try {
            m = resolve_model(v.spec);
        } catch (const Error&) {
            // A model without a roughness key named alpha: checked as the scene specifies it (a
            // measured file's tables per colour, channel=rgb: checked in luminance, channel=y).
            v.spec = merl_rgb_spec(model) ? merl_channel_spec(model, "y") : model;
            m = resolve_model(v.spec);
            note.clear();
        }
        FresnelConfig f = resolve_fresnel("none");
        if (m.uses_fresnel) {
            try {
                f = resolve_fresnel(fresnel);
            } catch (const Error&) {
                try {
                    f = resolve_fresnel(fresnel, 550.0);  // a measured metal (n,k by wavelength): at 550 nm
                    v.fresnel += " at 550 nm";
                } catch (const Error&) {
                    v.fresnel = "none: " + fresnel + " varies with the material, so the lobe is checked without it "
                                "(a Fresnel factor of at most 1 only lowers the energy)";
                }
            }
        }
        const CheckReport r = run_check(engine, m, f, options);
        v.text = note + check_report_text(r);
        v.passed = r.passed();
        v.ran = true;
    } catch (const Error& e) {
        v.text = note + "not checked: " + e.what();
    }
    return v;
}

const char* const kStyle =
    "body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}"
    "h1{font-size:1.6em}h2{font-size:1.25em;margin-top:2em;border-bottom:1px solid #ccc}"
    "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:.2em .6em;text-align:left;"
    "vertical-align:top}th{background:#f3f3f3}img{max-width:100%;border:1px solid #ddd}"
    "pre{background:#f7f7f7;padding:.5em;overflow-x:auto;font-size:.85em}"
    ".pass{color:#176b2c;font-weight:bold}.fail{color:#a4161a;font-weight:bold}.note{color:#666}";

/// A failed bake: why, and the tables of its plan that the index does not list.
void write_failure(std::ostream& o, const Json& index, const BakeReportOptions& options) {
    std::string missing;
    for (const std::string& f : options.planned_tables) {
        bool listed = false;
        for (const Json& e : index["tables"]) listed = listed || e.value("file", std::string()) == f;
        if (!listed) missing += (missing.empty() ? "" : ", ") + f;
    }
    o << "<p class=\"fail\">This bake failed: " << html(options.failure) << "</p>\n";
    if (!missing.empty())
        o << "<p>Not written: " << html(missing) << ". Run <code>brdfbake bake</code> again once the cause is "
             "fixed; the tables below are complete and are kept.</p>\n";
}

}  // namespace

BakeReportOptions::BakeReportOptions() {
    // A quick look, not the full `check`: half its directions and a quarter of its samples.
    check.directions = 24;
    check.samples = 1 << 14;
    check.resolution = 16;
    check.phi_resolution = 16;
}

BakeReportSummary write_bake_report(Engine& engine, const std::string& folder, const BakeReportOptions& options) {
    const Json index = read_bake_index(folder);
    BakeReportSummary summary;

    // Every lobe of every material, checked once per (model, Fresnel, roughness end).
    std::map<std::string, Verdict> verdicts;
    std::map<std::string, std::vector<std::string>> lobes_of_table;  // file -> verdict keys
    if (index.contains("materials") && options.checks)
        for (const Json& mat : index["materials"]) {
            if (!mat.contains("lobes")) continue;
            for (const Json& lobe : mat["lobes"]) {
                const std::string model = lobe.value("model", ""), fresnel = lobe.value("fresnel", "none");
                if (model.empty()) continue;
                std::vector<double> alphas;
                if (lobe.contains("alpha_range") && lobe["alpha_range"].size() == 2) {
                    alphas.push_back(lobe["alpha_range"][0].get<double>());
                    if (lobe["alpha_range"][1].get<double>() != alphas[0]) alphas.push_back(lobe["alpha_range"][1].get<double>());
                }
                for (double a : alphas) {
                    const std::string key = model + "|" + fresnel + "|" + number(a);
                    if (!verdicts.count(key)) {
                        verdicts[key] = check_lobe(engine, model, fresnel, a, options.check);
                        summary.lobes_checked += verdicts[key].ran;
                        summary.lobes_failed += verdicts[key].ran && !verdicts[key].passed;
                    }
                    if (mat.contains("tables"))
                        for (const Json& file : mat["tables"]) {
                            auto& keys = lobes_of_table[file.get<std::string>()];
                            if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
                        }
                }
            }
        }

    std::ostringstream o;
    const std::string scene = index.value("scene", std::string("(scene)"));
    o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>brdfbake: "
      << html(fs::path(scene).filename().string()) << "</title><style>" << kStyle << "</style></head><body>\n";
    o << "<h1>Bake report: " << html(fs::path(scene).filename().string()) << "</h1>\n";
    o << "<p>Scene <code>" << html(scene) << "</code>, baked by " << html(index.value("tool", std::string("brdfbake")))
      << "; " << index["tables"].size() << " tables. The numbers come from <code>index.json</code> beside this page.</p>\n";
    if (!options.failure.empty()) write_failure(o, index, options);
    if (index.contains("settings")) {
        o << "<table><tr><th>setting</th><th>value</th></tr>\n";
        std::map<std::string, const Json*> settings;  // in the order of their names
        for (const auto& kv : index["settings"].items()) settings[kv.key()] = &kv.value();
        for (const auto& kv : settings)
            o << "<tr><td>" << html(kv.first) << "</td><td>" << html(setting_text(kv.first, *kv.second))
              << "</td></tr>\n";
        o << "</table>\n";
    }
    if (index.contains("warnings") && !index["warnings"].empty()) {
        o << "<h2>Warnings</h2><ul>\n";
        std::vector<std::string> warnings;
        for (const Json& w : index["warnings"]) warnings.push_back(text_of(w));
        for (const std::string& w : grouped_warnings(warnings)) o << "<li>" << html(w) << "</li>\n";
        o << "</ul>\n";
    }
    if (index.contains("materials")) {
        o << "<h2>Materials</h2><table><tr><th>material</th><th>tables</th><th>notes</th></tr>\n";
        for (const Json& mat : index["materials"]) {
            o << "<tr><td>" << html(mat.value("name", std::string())) << "</td><td>";
            if (mat.contains("tables"))
                for (const Json& f : mat["tables"])
                    o << "<a href=\"#" << html(f.get<std::string>()) << "\">" << html(f.get<std::string>()) << "</a> ";
            o << "</td><td>";
            if (mat.contains("notes"))
                for (const Json& n : mat["notes"]) o << html(text_of(n)) << "<br>";
            o << "</td></tr>\n";
        }
        o << "</table>\n";
    }
    for (const Json& entry : index["tables"]) {
        const std::string file = entry.value("file", std::string());
        ++summary.tables;
        o << "<h2 id=\"" << html(file) << "\">" << html(file) << "</h2>\n";
        const bool present = !file.empty() && fs::exists(fs::path(folder) / file);
        if (!present) o << "<p class=\"fail\">Missing: the index lists this table but the folder has no such file.</p>\n";
        o << "<p>" << html(entry.value("kind", std::string())) << ": " << html(entry.value("quantity", std::string()))
          << "</p>\n<table>";
        for (const char* key : {"model", "fresnel", "size", "layout", "precision", "samples_per_cell", "max_error"})
            if (entry.contains(key))
                o << "<tr><th>" << key << "</th><td>" << html(text_of(entry[key])) << "</td></tr>";
        if (entry.contains("serves")) {
            o << "<tr><th>serves</th><td>";
            for (const Json& s : entry["serves"]) o << html(text_of(s)) << "<br>";
            o << "</td></tr>";
        }
        if (entry.contains("axes"))
            for (const Json& a : entry["axes"])
                o << "<tr><th>axis " << html(a.value("name", std::string())) << "</th><td>" << a.value("size", 0)
                  << " texels over [" << html(text_of(a["lo"])) << ", " << html(text_of(a["hi"])) << "], "
                  << html(a.value("mapping", std::string())) << "</td></tr>";
        if (entry.contains("attributes") && entry["attributes"].contains("method"))
            o << "<tr><th>method</th><td>" << html(text_of(entry["attributes"]["method"])) << "</td></tr>";
        o << "</table>\n";
        // The bake's preview, or one drawn from the file itself (what a renderer will load).
        const std::string own = entry.value("preview", std::string());
        const std::string own_full = entry.value("preview_full", std::string());
        if (!own.empty() && fs::exists(fs::path(folder) / own)) {
            o << preview_html(own, fs::exists(fs::path(folder) / own_full) ? own_full : "", file);
            ++summary.previews;
        } else if (options.draw_missing_previews && present) {
            const std::string picture = "report/" + file + ".png";
            try {
                const Table t = read_table((fs::path(folder) / file).string());
                std::error_code ec;
                fs::create_directories(fs::path(folder) / "report", ec);
                if (ec) throw Error("cannot create '" + (fs::path(folder) / "report").string() + "': " + ec.message());
                const std::string full = write_table_preview(t, (fs::path(folder) / picture).string());
                o << preview_html(picture, full.empty() ? "" : "report/" + fs::path(full).filename().string(), file);
                ++summary.previews;
            } catch (const Error& e) {
                o << "<p class=\"note\">No preview: " << html(e.what()) << "</p>\n";
            }
        } else if (present) {
            o << "<p class=\"note\">No preview (baked with --no-previews).</p>\n";
        }
        if (lobes_of_table.count(file)) {
            o << "<h3>Check of the lobes it tabulates</h3>\n";
            for (const std::string& key : lobes_of_table[file]) {
                const Verdict& v = verdicts[key];
                o << "<p><code>" << html(v.spec) << "</code>, Fresnel <code>" << html(v.fresnel) << "</code>: "
                  << (v.ran ? (v.passed ? "<span class=\"pass\">PASS</span>" : "<span class=\"fail\">VIOLATION</span>")
                            : "<span class=\"note\">not checked</span>")
                  << "</p><pre>" << html(v.text) << "</pre>\n";
            }
        }
    }
    if (options.checks)
        o << "<p class=\"note\">Checks: white furnace over " << options.check.directions << " directions, "
          << options.check.samples << " samples each; reciprocity over " << options.check.resolution << "&times;"
          << options.check.resolution << "&times;" << options.check.phi_resolution
          << " direction pairs; at both ends of each lobe's roughness range. <code>brdfbake check</code> runs the "
             "full check of one lobe.</p>\n";
    o << "</body></html>\n";
    write_file_atomically((fs::path(folder) / "index.html").string(), o.str());
    return summary;
}

}  // namespace brdfbake

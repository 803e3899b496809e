#include "models/nk_data.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "brdfbake/error.h"
#include "engine/embedded_sources.h"
#include "models/input_file.h"
#include "models/key_reader.h"

namespace brdfbake {

namespace {

const char kPresetPrefix[] = "nk/";

/// Rows of "wavelength value [value]" from a tabulated block, each with `columns` numbers.
std::vector<std::vector<double>> parse_rows(const std::string& data, size_t columns, const std::string& where) {
    std::vector<std::vector<double>> rows;
    std::istringstream lines(data);
    std::string line;
    int line_no = 0;
    while (std::getline(lines, line)) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream fields(line);
        std::vector<double> row;
        std::string field;
        while (fields >> field) {
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(field.c_str(), &end);
            if (end != field.c_str() + field.size() || !std::isfinite(v) || errno == ERANGE)
                throw Error(where + ", data row " + std::to_string(line_no) + ": '" + field + "' is not a finite number");
            row.push_back(v);
        }
        if (rows.size() == kMaxNkRows)
            throw Error(where + ": more than " + std::to_string(kMaxNkRows) + " data rows");
        if (row.size() != columns)
            throw Error(where + ", data row " + std::to_string(line_no) + ": expected " + std::to_string(columns) +
                        " numbers (wavelength in um, then " + (columns == 3 ? "n and k" : "the value") + "), got " +
                        std::to_string(row.size()));
        rows.push_back(std::move(row));
    }
    if (rows.empty()) throw Error(where + ": the data block has no rows");
    for (size_t i = 0; i < rows.size(); ++i) {
        if (!(rows[i][0] > 0.0))
            throw Error(where + ", data row " + std::to_string(i + 1) + ": wavelength must be positive");
        if (i > 0 && !(rows[i][0] > rows[i - 1][0]))
            throw Error(where + ", data row " + std::to_string(i + 1) + ": wavelengths must increase strictly");
    }
    return rows;
}

void check_values(const std::vector<double>& v, bool is_n, const std::string& where) {
    for (size_t i = 0; i < v.size(); ++i) {
        if (is_n ? !(v[i] > 0.0 && v[i] <= kMaxOpticalConstant) : !(v[i] >= 0.0 && v[i] <= kMaxOpticalConstant))
            throw Error(where + ", data row " + std::to_string(i + 1) + ": " +
                        (is_n ? "n must lie in (0, " : "k must lie in [0, ") + format_number(kMaxOpticalConstant) +
                        "] (got " + format_number(v[i]) + ")");
    }
}

/// Linear interpolation of (x, y) at x0, which lies in [x.front(), x.back()].
double lerp_table(const std::vector<double>& x, const std::vector<double>& y, double x0) {
    if (x.size() == 1) return y[0];
    auto hi = std::upper_bound(x.begin(), x.end(), x0);
    size_t j = size_t(hi - x.begin());
    if (j == 0) j = 1;
    if (j >= x.size()) j = x.size() - 1;
    const double t = (x0 - x[j - 1]) / (x[j] - x[j - 1]);
    return y[j - 1] + t * (y[j] - y[j - 1]);
}

}  // namespace

double NkTable::min_nm() const {
    const double lo = n_um.empty() ? 0.0 : n_um.front();
    return 1e3 * (k_um.empty() ? lo : std::max(lo, k_um.front()));
}

double NkTable::max_nm() const {
    const double hi = n_um.empty() ? 0.0 : n_um.back();
    return 1e3 * (k_um.empty() ? hi : std::min(hi, k_um.back()));
}

NkTable parse_nk_yaml(const std::string& text, const std::string& source) {
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw Error("n,k file '" + source + "' is not valid YAML: " + e.what());
    }
    NkTable table;
    table.source = source;
    try {
        if (!root.IsMap() || !root["DATA"] || !root["DATA"].IsSequence())
            throw Error("n,k file '" + source +
                        "' has no DATA list (expected the refractiveindex.info layout: DATA: - type: tabulated nk)");
        if (root["REFERENCES"] && root["REFERENCES"].IsScalar()) table.references = root["REFERENCES"].as<std::string>();
        std::vector<std::string> skipped;
        for (const YAML::Node& block : root["DATA"]) {
            if (!block.IsMap() || !block["type"] || !block["type"].IsScalar())
                throw Error("n,k file '" + source + "': a DATA entry has no type");
            const std::string type = block["type"].as<std::string>();
            const bool nk = type == "tabulated nk", only_n = type == "tabulated n", only_k = type == "tabulated k";
            if (!nk && !only_n && !only_k) {
                skipped.push_back(type);
                continue;
            }
            if (!block["data"] || !block["data"].IsScalar())
                throw Error("n,k file '" + source + "': the '" + type + "' entry has no data block");
            const std::string where = "n,k file '" + source + "' (" + type + ")";
            const auto rows = parse_rows(block["data"].as<std::string>(), nk ? 3 : 2, where);
            if ((nk || only_n) && !table.n_um.empty())
                throw Error("n,k file '" + source + "' gives n twice");
            if ((nk || only_k) && !table.k_um.empty())
                throw Error("n,k file '" + source + "' gives k twice");
            for (const auto& r : rows) {
                if (nk || only_n) {
                    table.n_um.push_back(r[0]);
                    table.n.push_back(r[1]);
                }
                if (nk) {
                    table.k_um.push_back(r[0]);
                    table.k.push_back(r[2]);
                }
                if (only_k) {
                    table.k_um.push_back(r[0]);
                    table.k.push_back(r[1]);
                }
            }
            check_values(table.n, true, where);
            check_values(table.k, false, where);
        }
        if (table.n_um.empty()) {
            std::string what = skipped.empty() ? std::string("no tabulated data") : "only '" + skipped.front() + "' data";
            throw Error("n,k file '" + source + "' has " + what +
                        "; brdfbake reads the types 'tabulated nk', 'tabulated n' and 'tabulated k'");
        }
    } catch (const YAML::Exception& e) {
        throw Error("n,k file '" + source + "': " + e.what());
    }
    return table;
}

NkTable load_nk_file(const std::string& path) {
    return parse_nk_yaml(read_input_file(path, "n,k file", kMaxNkFileBytes), path);
}

std::vector<std::string> nk_preset_names() {
    std::vector<std::string> names;
    const size_t plen = std::strlen(kPresetPrefix);
    for (const auto& key : embedded_source_names()) {
        if (key.compare(0, plen, kPresetPrefix) != 0) continue;
        const size_t dash = key.find('-', plen);
        if (dash == std::string::npos) continue;
        names.push_back(key.substr(plen, dash - plen));
    }
    return names;
}

NkTable load_nk_preset(const std::string& symbol) {
    const std::string prefix = std::string(kPresetPrefix) + symbol + "-";
    for (const auto& key : embedded_source_names())
        if (key.compare(0, prefix.size(), prefix) == 0) {
            NkTable t = parse_nk_yaml(embedded_source(key), key.substr(std::strlen(kPresetPrefix)));
            return t;
        }
    std::string known;
    for (const auto& n : nk_preset_names()) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown metal '" + symbol + "'; known: " + known + " (or nk:FILE.yml for your own data)");
}

NkValue interpolate_nk(const NkTable& table, double wavelength_nm) {
    const double lo = table.min_nm(), hi = table.max_nm();
    // The table's ends converted to nm carry a rounding error; accept the ends themselves.
    const double slack = 1e-12 * hi;
    if (!(wavelength_nm >= lo - slack && wavelength_nm <= hi + slack))
        throw Error("--wavelength " + format_number(wavelength_nm) + " nm is outside the range of '" + table.source +
                    "' (" + format_number(lo) + " to " + format_number(hi) + " nm)");
    const double um = std::min(std::max(wavelength_nm * 1e-3, 1e-3 * lo), 1e-3 * hi);
    NkValue v;
    v.n = lerp_table(table.n_um, table.n, um);
    v.k = table.k_um.empty() ? 0.0 : lerp_table(table.k_um, table.k, um);
    return v;
}

}  // namespace brdfbake

#include "models/sheen_ltc_table.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>

#include "brdfbake/error.h"
#include "engine/embedded_sources.h"
#include "models/csv_text.h"
#include "models/input_file.h"

namespace brdfbake {

const char* const kSheenLtcBuiltin = "builtin";

namespace {

/// The embedded default table (data/sheen_ltc/, CMakeLists.txt embeds it as sheen_ltc/<file>).
constexpr const char* kBuiltinSource = "sheen_ltc/sheen_ltc_cycles.csv";
/// A table file's size limit: a 1024 x 1024 table's CSV is about 100 MB.
constexpr std::uintmax_t kMaxBytes = std::uintmax_t(256) << 20;

struct Store {
    std::mutex mutex;
    std::vector<double> data;
    std::map<std::string, SheenLtcTablePlace> places;
};

Store& store() {
    static Store s;
    return s;
}

/// Reads the table's text into the layout of brdf/sheen_ltc.h; `fail` throws with the file's name.
std::vector<double> parse_table(const std::string& text, int& nx, int& ny,
                                const std::function<void(const std::string&)>& fail) {
    CsvText t(text);
    const auto said = [&](const std::string& key) { return t.said(key); };
    std::vector<std::vector<std::string>> rows;
    for (std::vector<std::string> cells; t.next_row(cells);) rows.push_back(cells);
    if (said("kind") != "sheen-ltc") fail("not a sheen-ltc table (its '# kind:' line; write one with brdfbake lut sheen-ltc -o FILE.csv)");
    const std::string xm = said("x_mapping");  // linear, perhaps with the floor the walks ran at ("mu = max(u, 0.01)")
    if (said("x_axis") != "mu" || (xm != "mu = u" && xm.rfind("mu = max(u, ", 0) != 0))
        fail("its x axis is '" + said("x_axis") + "' (" + said("x_mapping") + "); the model reads mu = u (lut sheen-ltc --mu-map linear)");
    const std::string y = said("y_axis");
    if (y != "roughness" && y != "alpha") fail("its y axis is '" + y + "', not roughness or alpha");
    if (!said("z_size").empty() && said("z_size") != "1") fail("it has a z axis; a sheen-ltc table is 2D");
    nx = std::atoi(said("x_size").c_str());
    ny = std::atoi(said("y_size").c_str());
    if (nx < 2 || ny < 2) fail("it has " + said("x_size") + " x " + said("y_size") + " texels; bilinear lookup needs at least 2 x 2");
    const auto column = [&](const std::string& name) {
        const int i = t.column(name);
        if (i < 0) fail("it has no column '" + name + "'");
        return size_t(i);
    };
    const size_t cx = column("mu"), cy = column(y), ca = column("a"), cb = column("b"), cr = column("R");
    if (rows.size() != size_t(nx) * size_t(ny))
        fail("it has " + std::to_string(rows.size()) + " rows for " + std::to_string(nx) + " x " + std::to_string(ny) + " texels");
    std::vector<double> out(size_t(nx + ny) + 3 * size_t(nx) * size_t(ny));
    for (size_t k = 0; k < rows.size(); ++k) {
        const auto& row = rows[k];
        if (row.size() != t.columns().size()) fail("row " + std::to_string(k + 1) + " has " + std::to_string(row.size()) + " fields");
        const auto number = [&](size_t c) {
            errno = 0;
            char* end = nullptr;
            const double v = std::strtod(row[c].c_str(), &end);
            if (end == row[c].c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
                fail("row " + std::to_string(k + 1) + ": '" + row[c] + "' in column '" + t.columns()[c] + "' is not a finite number");
            return v;
        };
        const size_t i = k % size_t(nx), j = k / size_t(nx), plane = size_t(nx + ny), n = size_t(nx) * size_t(ny);
        const double a = number(ca), r = number(cr);
        if (!(a > 0.0)) fail("row " + std::to_string(k + 1) + ": a = " + row[ca] + "; an LTC needs a > 0");
        if (r < 0.0 || r > 1.0) fail("row " + std::to_string(k + 1) + ": R = " + row[cr] + " is not a reflectance in [0, 1]");
        out[plane + k] = a;
        out[plane + n + k] = number(cb);
        out[plane + 2 * n + k] = r;
        if (j == 0) out[i] = number(cx);
        if (i == 0) out[size_t(nx) + j] = y == "alpha" ? std::sqrt(std::max(0.0, number(cy))) : number(cy);
    }
    for (int a = 0; a < 2; ++a) {
        const size_t first = a == 0 ? 0 : size_t(nx), n = size_t(a == 0 ? nx : ny);
        for (size_t k = 1; k < n; ++k)
            if (!(out[first + k] > out[first + k - 1]))
                fail(std::string("its ") + (a == 0 ? "mu" : "roughness") + " nodes do not increase (the texels' order of lut sheen-ltc)");
    }
    return out;
}

}  // namespace

SheenLtcTablePlace sheen_ltc_table(const std::string& file) {
    Store& s = store();
    std::lock_guard<std::mutex> lock(s.mutex);
    const auto known = s.places.find(file);
    if (known != s.places.end()) return known->second;
    std::string text;
    if (file == kSheenLtcBuiltin) {
        const char* builtin = embedded_source(kBuiltinSource);
        if (!builtin) throw Error(std::string("internal error: no embedded ") + kBuiltinSource);
        text = builtin;
    } else {
        text = read_input_file(file, "sheen-ltc table", kMaxBytes);
    }
    SheenLtcTablePlace place;
    const std::vector<double> t = parse_table(text, place.nx, place.ny, [&](const std::string& why) {
        throw Error("model 'sheen-ltc': table '" + file + "': " + why);
    });
    place.offset = s.data.size();
    s.data.insert(s.data.end(), t.begin(), t.end());
    s.places[file] = place;
    return place;
}

std::vector<double> sheen_ltc_model_data() {
    Store& s = store();
    std::lock_guard<std::mutex> lock(s.mutex);
    return s.data;
}

}  // namespace brdfbake

const double* bb_sheen_ltc_host_data(void) {
    brdfbake::Store& s = brdfbake::store();
    std::lock_guard<std::mutex> lock(s.mutex);
    return s.data.data();
}

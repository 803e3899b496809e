// The LTC sheen's tables (brdf/sheen_ltc.h): (a, b, R) per (mu, roughness) as `brdfbake lut
// sheen-ltc` writes them in CSV, read and checked once per process and file, and joined in the
// process's store, the model data of a sheen-ltc launch. The default table is data/sheen_ltc/'s,
// embedded at build time (its command in data/sheen_ltc/README.md).
#pragma once

#include <string>
#include <vector>

namespace brdfbake {

/// A table's place in the store: the model's parameter slots BB_SHEEN_LTC_OFFSET, _NX, _NY.
struct SheenLtcTablePlace {
    std::size_t offset = 0;
    int nx = 0, ny = 0;
};

/// The name of the embedded default table (what sheen-ltc without table= reads).
extern const char* const kSheenLtcBuiltin;

/// The table of `file` (a CSV written by `lut sheen-ltc`, or kSheenLtcBuiltin), read and checked
/// once per process. Throws Error with one line naming the file and what is wrong: not a
/// sheen-ltc table, an x axis other than mu = u, a y axis other than roughness or alpha, fewer than
/// 2 nodes on an axis, nodes not increasing, a missing channel, a value not finite, a <= 0, R
/// outside [0, 1].
SheenLtcTablePlace sheen_ltc_table(const std::string& file);

/// Every table of the store, one after the other (brdf/sheen_ltc.h's layout).
std::vector<double> sheen_ltc_model_data();

}  // namespace brdfbake

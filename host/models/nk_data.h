// Tabulated optical constants n(lambda), k(lambda) in the refractiveindex.info YAML layout, with
// linear interpolation in wavelength. Presets (metal:Al, ...) are the files of data/nk/, embedded
// into the binary under the keys "nk/<file>".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brdfbake {

/// One table of a material: n and k, each over its own wavelength grid (micrometres, strictly
/// increasing). A "tabulated nk" block fills both with the same grid; "tabulated n" and
/// "tabulated k" blocks fill one each. A material with n data only has k = 0 (a dielectric).
struct NkTable {
    std::string source;  // file name or preset key, for messages
    std::string references;  // the file's REFERENCES text, if any
    std::vector<double> n_um, n;
    std::vector<double> k_um, k;

    /// The wavelength range (nm) where both n and k are defined.
    double min_nm() const;
    double max_nm() const;
};

/// Limits on what an n,k file may hold, the same bounds as the `conductor:` spec's keys: larger
/// values are not optical constants of any material and make the Fresnel equations overflow.
constexpr double kMaxOpticalConstant = 1e3;             // n in (0, 1e3], k in [0, 1e3]
constexpr std::size_t kMaxNkRows = 100000;              // rows per data block
constexpr std::uintmax_t kMaxNkFileBytes = 16u << 20;   // a refractiveindex.info file is < 1 MiB

struct NkValue {
    double n = 1.0;
    double k = 0.0;
};

/// Parses the YAML text of a refractiveindex.info material file. `source` names it in errors.
/// Throws Error on malformed YAML, a missing DATA block, formula (non-tabulated) data, rows that
/// are not numbers, wavelengths that do not increase, n outside (0, 1e3], k outside [0, 1e3] or
/// more than kMaxNkRows rows in a block.
NkTable parse_nk_yaml(const std::string& text, const std::string& source);

/// Reads and parses a file; throws Error if it is not a regular file, is larger than
/// kMaxNkFileBytes or cannot be read.
NkTable load_nk_file(const std::string& path);

/// The embedded preset for a metal symbol ("Al", "Au", "Ag", "Cu"): the file data/nk/<symbol>-*.yml.
/// Throws Error naming the known presets for an unknown symbol.
NkTable load_nk_preset(const std::string& symbol);

/// Symbols of the embedded presets, e.g. {"Ag", "Al", "Au", "Cu"}.
std::vector<std::string> nk_preset_names();

/// n and k at `wavelength_nm`, linear in wavelength between the two neighbouring rows.
/// Throws Error if the wavelength lies outside the table's range.
NkValue interpolate_nk(const NkTable& table, double wavelength_nm);

}  // namespace brdfbake

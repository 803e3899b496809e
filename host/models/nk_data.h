// Tabulated optical constants n(lambda), k(lambda) in the refractiveindex.info YAML layout, with
// linear interpolation in wavelength. Presets (metal:Al, ...) are the files of data/nk/, embedded
// into the binary under the keys "nk/<file>".
#pragma once

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

struct NkValue {
    double n = 1.0;
    double k = 0.0;
};

/// Parses the YAML text of a refractiveindex.info material file. `source` names it in errors.
/// Throws Error on malformed YAML, a missing DATA block, formula (non-tabulated) data, rows that
/// are not numbers, wavelengths that do not increase, n <= 0 or k < 0.
NkTable parse_nk_yaml(const std::string& text, const std::string& source);

/// Reads and parses a file; throws Error if it cannot be read.
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

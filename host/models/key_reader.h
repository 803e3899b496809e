// Reads the keys of a parsed spec one by one, with range checks, and complains about leftovers.
// Used by the model and Fresnel registries.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "brdfbake/spec.h"

namespace brdfbake {

/// A closed or half-open interval for a numeric key.
struct Range {
    double lo;
    double hi;
    bool lo_open = false;  // lo itself is excluded (e.g. alpha > 0)
};

class KeyReader {
public:
    KeyReader(const Spec& spec, std::string kind);  // kind: "model" or "Fresnel", for messages

    /// The value of `key`, or `fallback` when absent; checked against `range`.
    double number(const std::string& key, double fallback, Range range);
    /// The value of `key` if present; checked against `range`.
    std::optional<double> optional_number(const std::string& key, Range range);
    /// The value of a required key. A missing one is reported by finish(), after any unknown key
    /// (`ggx:alpah=0.5` names `alpah`, not the missing alpha); meanwhile a value inside `range`.
    double required_number(const std::string& key, Range range, const std::string& hint = "");
    /// One of `choices`, or `fallback` when absent.
    std::string choice(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& choices);
    /// A string value if present.
    std::optional<std::string> optional_string(const std::string& key);
    bool has(const std::string& key) const;
    /// Throws if a key was given that no call above consumed (naming the nearest key asked for),
    /// then if a required key was missing.
    void finish() const;

    const std::string& name() const { return spec_.name; }

private:
    const std::string* find(const std::string& key);
    std::string where(const std::string& key) const;

    Spec spec_;
    std::string kind_;
    std::vector<bool> used_;
    mutable std::vector<std::string> asked_;  // every key asked for, in order: the valid keys
    std::string missing_;                      // the first required key's message, for finish()
};

/// The name of `known` nearest to `given` by edit distance (optimal string alignment: a swap of
/// two neighbouring letters is one edit), when near enough to be a likely typo (at most a third of
/// its letters, at least one); empty otherwise.
std::string nearest_name(const std::string& given, const std::vector<std::string>& known);
/// "; did you mean 'NAME'?" with the nearest_name, or empty.
std::string did_you_mean(const std::string& given, const std::vector<std::string>& known);
/// "unknown WHAT 'GIVEN'; did you mean 'NAME'? Known: LIST" (the hint only when one is near;
/// `known_label` is the list's label, e.g. "known models").
std::string unknown_name_message(const std::string& what, const std::string& given, const std::vector<std::string>& known,
                                 const std::string& known_label, const std::string& list);

/// Shortest decimal text that reads back as the same double (for canonical specs).
std::string format_number(double v);

}  // namespace brdfbake

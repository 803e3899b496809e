#include "models/key_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "brdfbake/error.h"

namespace brdfbake {

KeyReader::KeyReader(const Spec& spec, std::string kind)
    : spec_(spec), kind_(std::move(kind)), used_(spec.keys.size(), false) {}

bool KeyReader::has(const std::string& key) const {
    if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) asked_.push_back(key);
    for (const auto& kv : spec_.keys)
        if (kv.first == key) return true;
    return false;
}

const std::string* KeyReader::find(const std::string& key) {
    if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) asked_.push_back(key);
    for (size_t i = 0; i < spec_.keys.size(); ++i)
        if (spec_.keys[i].first == key) {
            used_[i] = true;
            return &spec_.keys[i].second;
        }
    return nullptr;
}

std::string KeyReader::where(const std::string& key) const {
    return kind_ + " '" + spec_.name + "', key '" + key + "'";
}

std::optional<double> KeyReader::optional_number(const std::string& key, Range range) {
    const std::string* text = find(key);
    if (!text) return std::nullopt;
    double v = parse_number(*text, where(key));
    bool below = range.lo_open ? !(v > range.lo) : !(v >= range.lo);
    if (below || v > range.hi) {
        std::ostringstream msg;
        msg << where(key) << ": " << *text << " is out of range; expected " << format_number(range.lo)
            << (range.lo_open ? " < " : " <= ") << key << " <= " << format_number(range.hi);
        throw Error(msg.str());
    }
    return v;
}

double KeyReader::number(const std::string& key, double fallback, Range range) {
    return optional_number(key, range).value_or(fallback);
}

double KeyReader::required_number(const std::string& key, Range range, const std::string& hint) {
    auto v = optional_number(key, range);
    if (v) return *v;
    if (missing_.empty())
        missing_ = kind_ + " '" + spec_.name + "' needs " + key + "=VALUE" + (hint.empty() ? "" : " (" + hint + ")");
    return range.lo_open ? range.lo + 0.5 * (range.hi - range.lo) : range.lo;
}

std::optional<std::string> KeyReader::optional_string(const std::string& key) {
    const std::string* text = find(key);
    if (!text) return std::nullopt;
    return *text;
}

std::string KeyReader::choice(const std::string& key, const std::string& fallback,
                              const std::vector<std::string>& choices) {
    const std::string* text = find(key);
    if (!text) return fallback;
    for (const auto& c : choices)
        if (c == *text) return c;
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    throw Error(where(key) + ": unknown value '" + *text + "'; expected one of " + list);
}

void KeyReader::finish() const {
    for (size_t i = 0; i < spec_.keys.size(); ++i) {
        if (used_[i]) continue;
        const std::string& key = spec_.keys[i].first;
        std::string message = kind_ + " '" + spec_.name + "' has no key '" + key + "'";
        const std::string hint = did_you_mean(key, asked_);
        if (!hint.empty()) throw Error(message + hint);
        std::string list;
        for (const auto& k : asked_) list += (list.empty() ? "" : ", ") + k;
        throw Error(message + (list.empty() ? "; it takes no keys" : "; its keys: " + list));
    }
    if (!missing_.empty()) throw Error(missing_);
}

namespace {
/// Optimal string alignment distance, case-insensitive.
size_t edit_distance(const std::string& a, const std::string& b) {
    auto same = [&](size_t i, size_t j) { return std::tolower((unsigned char)a[i]) == std::tolower((unsigned char)b[j]); };
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (same(i - 1, j - 1) ? 0 : 1)});
            if (i > 1 && j > 1 && same(i - 1, j - 2) && same(i - 2, j - 1)) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}
}  // namespace

std::string nearest_name(const std::string& given, const std::vector<std::string>& known) {
    std::string best;
    size_t best_distance = std::max<size_t>(1, given.size() / 3) + 1;
    for (const auto& name : known) {
        const size_t d = edit_distance(given, name);
        if (d < best_distance) best = name, best_distance = d;
    }
    return best;
}

std::string did_you_mean(const std::string& given, const std::vector<std::string>& known) {
    const std::string near = nearest_name(given, known);
    return near.empty() ? "" : "; did you mean '" + near + "'?";
}

std::string unknown_name_message(const std::string& what, const std::string& given, const std::vector<std::string>& known,
                                 const std::string& known_label, const std::string& list) {
    const std::string hint = did_you_mean(given, known);
    std::string label = known_label;
    if (!hint.empty() && !label.empty()) label[0] = char(std::toupper((unsigned char)label[0]));
    return "unknown " + what + " '" + given + "'" + (hint.empty() ? "; " : hint + " ") + label + ": " + list;
}

std::string format_number(double v) {
    char buf[32];
    for (int prec = 1; prec <= 17; ++prec) {
        std::snprintf(buf, sizeof buf, "%.*g", prec, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

}  // namespace brdfbake

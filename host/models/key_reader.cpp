#include "models/key_reader.h"

#include <cmath>
#include <sstream>

#include "brdfbake/error.h"

namespace brdfbake {

KeyReader::KeyReader(const Spec& spec, std::string kind)
    : spec_(spec), kind_(std::move(kind)), used_(spec.keys.size(), false) {}

bool KeyReader::has(const std::string& key) const {
    for (const auto& kv : spec_.keys)
        if (kv.first == key) return true;
    return false;
}

const std::string* KeyReader::find(const std::string& key) {
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
    if (!v)
        throw Error(kind_ + " '" + spec_.name + "' needs " + key + "=VALUE" +
                    (hint.empty() ? "" : " (" + hint + ")"));
    return *v;
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
    for (size_t i = 0; i < spec_.keys.size(); ++i)
        if (!used_[i])
            throw Error(kind_ + " '" + spec_.name + "' has no key '" + spec_.keys[i].first + "'");
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

// Strict JSON parsing for scene files and glTF (json_read.h).
#include "scene/json_read.h"

#include <set>
#include <vector>

#include "brdfbake/error.h"

namespace brdfbake {
namespace scene_json {
namespace {

using json = nlohmann::json;

std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

/// One open object or array while parsing: its keys so far (objects), the key being read, and
/// the index of the next element (arrays). The path to it is the stack's keys and indices, put
/// together only for a message (a copy per frame would cost the square of the depth).
struct Frame {
    bool array = false;
    std::set<std::string> keys;
    std::string key;
    std::size_t index = 0;
};

/// The first pass over a document: nlohmann-json's SAX events, checked for the bounds (before
/// anything is built) and for duplicate keys. Building the document is the second pass, without a
/// callback (nlohmann-json 3.11's callback parser rescans an array at the end of each object in
/// it: the square of the number of materials).
class Checker : public nlohmann::json_sax<json> {
public:
    std::string bound, error;  // past a bound; the parse error
    bool duplicate = false;
    std::string dup_key, dup_path;
    json::json_pointer dup_ptr;

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return open(false); }
    bool start_array(std::size_t) override { return open(true); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }
    bool key(string_t& k) override {
        Frame& f = stack_.back();
        f.key = k;
        if (!f.keys.insert(f.key).second && !duplicate) {
            duplicate = true;
            dup_key = f.key;
            // The path of the object: each enclosing frame's step into its child.
            for (size_t i = 0; i + 1 < stack_.size(); ++i) {
                const Frame& p = stack_[i];
                dup_path += p.array ? "[" + std::to_string(p.index) + "]" : (i == 0 ? "" : ".") + p.key;
                dup_ptr = p.array ? dup_ptr / p.index : dup_ptr / p.key;
            }
        }
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
        error = e.what();
        return false;
    }

private:
    bool open(bool array) {
        if (stack_.size() >= kMaxJsonDepth) {
            bound = "arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) + " levels";
            return false;
        }
        stack_.emplace_back();
        stack_.back().array = array;
        return true;
    }
    bool close() {
        stack_.pop_back();
        return value();
    }
    bool value() {
        if (++values_ > kMaxJsonValues) {
            bound = "more than " + std::to_string(kMaxJsonValues) + " values (numbers, strings, arrays, objects)";
            return false;
        }
        if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
        return true;
    }

    std::vector<Frame> stack_;
    std::size_t values_ = 0;
};

}  // namespace

json parse_strict(const std::string& text, const std::string& label) {
    Checker check;
    json::sax_parse(text, &check);
    if (!check.bound.empty())
        throw Error(label + ": " + check.bound + "; brdfbake reads no deeper or larger documents (README, Limits)");
    if (!check.error.empty()) {
        std::string what = check.error;
        const size_t p = what.find("] ");
        if (what.rfind("[json.exception", 0) == 0 && p != std::string::npos) what = what.substr(p + 2);
        throw Error(label + " is not valid JSON: " + one_line(what));
    }
    const json j = json::parse(text);
    if (check.duplicate) {
        // The nearest enclosing object with a "name" names the material (or node, or texture).
        std::string named;
        json::json_pointer ptr = check.dup_ptr;
        while (true) {
            if (j.contains(ptr)) {
                const json& o = j.at(ptr);
                if (o.is_object() && o.contains("name") && o["name"].is_string()) {
                    named = o["name"].get<std::string>();
                    break;
                }
            }
            if (ptr.empty()) break;
            ptr = ptr.parent_pointer();
        }
        throw Error(label + ": key '" + check.dup_key + "' is given twice in " +
                    (check.dup_path.empty() ? std::string("the top-level object") : check.dup_path) +
                    (named.empty() ? "" : " ('" + named + "')") + "; give each key once");
    }
    return j;
}

}  // namespace scene_json
}  // namespace brdfbake

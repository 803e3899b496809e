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

/// One open object or array while parsing: its keys so far (objects), the key being read, the
/// index of the next element (arrays), and how it is reached from its parent.
struct Frame {
    bool array = false;
    std::set<std::string> keys;
    std::string key;
    std::size_t index = 0;
    std::string step;        // ".name" or "[i]" (empty at the root)
    json::json_pointer ptr;  // the same as a JSON pointer
};

}  // namespace

json parse_strict(const std::string& text, const std::string& label) {
    std::vector<Frame> stack;
    std::string dup_key, dup_path;
    json::json_pointer dup_ptr;
    bool duplicate = false;
    auto child_started = [&](bool array) {
        Frame f;
        f.array = array;
        if (!stack.empty()) {
            const Frame& p = stack.back();
            f.step = p.array ? "[" + std::to_string(p.index) + "]" : (p.step.empty() && stack.size() == 1 ? "" : ".") + p.key;
            f.ptr = p.array ? p.ptr / p.index : p.ptr / p.key;
        }
        stack.push_back(std::move(f));
    };
    auto element_done = [&] {
        if (!stack.empty() && stack.back().array) ++stack.back().index;
    };
    const json::parser_callback_t cb = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start: child_started(false); break;
            case json::parse_event_t::array_start: child_started(true); break;
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                stack.pop_back();
                element_done();
                break;
            case json::parse_event_t::key:
                if (!stack.empty()) {
                    Frame& f = stack.back();
                    f.key = parsed.get<std::string>();
                    if (!f.keys.insert(f.key).second && !duplicate) {
                        duplicate = true;
                        dup_key = f.key;
                        for (const Frame& x : stack) dup_path += x.step;
                        dup_ptr = f.ptr;
                    }
                }
                break;
            case json::parse_event_t::value: element_done(); break;
        }
        return true;
    };
    json j;
    try {
        j = json::parse(text, cb);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        const size_t p = what.find("] ");
        if (what.rfind("[json.exception", 0) == 0 && p != std::string::npos) what = what.substr(p + 2);
        throw Error(label + " is not valid JSON: " + one_line(what));
    }
    if (duplicate) {
        // The nearest enclosing object with a "name" names the material (or node, or texture).
        std::string named;
        json::json_pointer ptr = dup_ptr;
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
        throw Error(label + ": key '" + dup_key + "' is given twice in " +
                    (dup_path.empty() ? std::string("the top-level object") : dup_path) +
                    (named.empty() ? "" : " ('" + named + "')") + "; give each key once");
    }
    return j;
}

}  // namespace scene_json
}  // namespace brdfbake

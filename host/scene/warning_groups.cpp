// grouped_warnings (scene.h): one line per warning that several materials share.
#include <map>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace brdfbake {

std::vector<std::string> grouped_warnings(const std::vector<std::string>& warnings) {
    const std::string prefix = "material '", separator = "': ";
    struct Group {
        size_t first;                     // where the group's line goes
        std::vector<std::string> materials;
    };
    std::map<std::string, Group> groups;  // the warning without its material -> materials
    std::vector<std::string> lines;       // ungrouped lines, and a placeholder per group
    std::vector<std::string> rest_at;     // the group key of each line ("" for a plain line)
    for (const std::string& w : warnings) {
        const size_t end = w.find(separator, prefix.size());
        if (w.compare(0, prefix.size(), prefix) != 0 || end == std::string::npos || end < prefix.size()) {
            lines.push_back(w);
            rest_at.emplace_back();
            continue;
        }
        const std::string material = w.substr(prefix.size(), end - prefix.size());
        const std::string rest = w.substr(end + separator.size());
        auto it = groups.find(rest);
        if (it == groups.end()) {
            groups[rest] = Group{lines.size(), {material}};
            lines.push_back(w);
            rest_at.push_back(rest);
        } else {
            it->second.materials.push_back(material);
        }
    }
    for (size_t i = 0; i < lines.size(); ++i) {
        if (rest_at[i].empty()) continue;
        const Group& g = groups[rest_at[i]];
        if (g.materials.size() < 2) continue;
        std::string names;
        for (const std::string& m : g.materials) names += (names.empty() ? "" : ", ") + m;
        lines[i] = rest_at[i] + " (" + std::to_string(g.materials.size()) + " materials: " + names + ")";
    }
    return lines;
}

}  // namespace brdfbake

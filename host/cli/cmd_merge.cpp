// `brdfbake merge PARTS... -o TABLE`: joins the part files of `brdfbake lut ... --shard K/N` into
// the table, written as the unsharded command would write it (docs/cluster.md).
#include <cstdio>
#include <cstring>
#include <set>

#include "brdfbake/error.h"
#include "brdfbake/version.h"
#include "cli/cli.h"
#include "integrate/distributed_compute.h"
#include "io/part_file.h"

namespace brdfbake {
namespace {

struct MergeOptions {
    std::vector<std::string> parts;
    std::string output;
};

// Options whose value is the next word (or follows '='), and flags, that a shard's command drops.
const std::set<std::string> kDroppedWithValue = {"--shard", "-o", "--output", "--device", "--max-memory"};
const std::set<std::string> kDroppedFlags = {"-v", "--verbose", "-q", "--quiet"};

int run_merge(const MergeOptions& o, const GlobalOptions&) {
    std::vector<PartFile> parts;
    for (const std::string& path : o.parts) parts.push_back(read_part_file(path));
    const PartFile& first = parts.front();
    const std::string& first_path = o.parts.front();
    std::vector<std::string> by_shard(size_t(first.shards));
    ShardRecords records;
    for (size_t i = 0; i < parts.size(); ++i) {
        const PartFile& p = parts[i];
        const std::string& path = o.parts[i];
        if (p.version != first.version || p.source != first.source)
            throw Error("'" + path + "' and '" + first_path + "' were written by different versions of brdfbake (" +
                        p.version + " " + p.source + ", " + first.version + " " + first.source + ")");
        if (p.command != first.command)
            throw Error("'" + path + "' and '" + first_path + "' are shards of different commands");
        if (p.shards != first.shards)
            throw Error("'" + path + "' is one of " + std::to_string(p.shards) + " shards, '" + first_path +
                        "' one of " + std::to_string(first.shards));
        std::string& seen = by_shard[size_t(p.shard)];
        if (!seen.empty())
            throw Error("'" + path + "' and '" + seen + "' are both shard " + std::to_string(p.shard) + " of " +
                        std::to_string(p.shards));
        seen = path;
        // Each part's text indices are its own: renumber them into the merged list.
        for (const auto& [key, bytes] : p.cells) {
            std::string packed = bytes;
            const size_t at = sizeof(std::uint64_t) + sizeof(unsigned);  // where the text index sits
            std::uint32_t text = 0;
            if (packed.size() < at + sizeof text) throw Error("'" + path + "' holds a truncated record");
            std::memcpy(&text, packed.data() + at, sizeof text);
            if (text >= p.texts.size()) throw Error("'" + path + "' refers to a method text it does not hold");
            std::uint32_t merged = 0;
            while (merged < records.texts.size() && records.texts[merged] != p.texts[text]) ++merged;
            if (merged == records.texts.size()) records.texts.push_back(p.texts[text]);
            std::memcpy(packed.data() + at, &merged, sizeof merged);
            records.cells[key] = packed;
        }
    }
    std::string missing;
    for (size_t k = 0; k < by_shard.size(); ++k)
        if (by_shard[k].empty()) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    if (!missing.empty())
        throw Error("shard" + std::string(missing.find(',') == std::string::npos ? " " : "s ") + missing + " of " +
                    std::to_string(first.shards) + " missing (give every part file of the table)");
    if (first.version != BRDFBAKE_VERSION || first.source != source_digest())
        throw Error("the part files were written by another version of brdfbake (" + first.version + " " +
                    first.source + "; this is " + BRDFBAKE_VERSION + " " + source_digest() + ")");

    begin_replay(std::move(records));
    std::vector<std::string> command = first.command;
    command.push_back("-o");
    command.push_back(o.output);
    return run_command_line(command);
}

}  // namespace

std::vector<std::string> shard_command(const std::vector<std::string>& words) {
    std::vector<std::string> out;
    for (size_t i = 0; i < words.size(); ++i) {
        const std::string& w = words[i];
        const std::string name = w.substr(0, w.find('='));
        if (kDroppedFlags.count(w)) continue;
        if (kDroppedWithValue.count(name)) {
            if (name == w) ++i;  // the value is the next word
            continue;
        }
        if (w.size() > 2 && w.compare(0, 2, "-o") == 0 && w[2] != '-') continue;  // -oPATH
        out.push_back(w);
    }
    return out;
}

void add_merge_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<MergeOptions>(
        app, "merge",
        "join the part files of `brdfbake lut ... --shard K/N` into the table (as the unsharded command writes it)",
        global, action, run_merge);
    cmd->add_option("parts", o->parts, "the part files, every shard once, in any order")->required();
    cmd->add_option("-o,--output", o->output, "the table (its extension picks the format, as for lut)")->required();
}

}  // namespace brdfbake

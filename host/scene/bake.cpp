#include "scene/bake.h"

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <regex>
#include <set>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/output.h"
#include "brdfbake/progress.h"
#include "engine/distributed.h"
#include "scene/bake_folder.h"
#include "scene/bake_index.h"

namespace brdfbake {

namespace {

using Clock = std::chrono::steady_clock;
using json = BakeIndexJson;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string join_path(const std::string& dir, const std::string& file) {
    return dir.empty() || dir.back() == '/' ? dir + file : dir + "/" + file;
}

bool file_exists(const std::string& path) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

void log_line(const std::string& text) { progress_message("brdfbake: " + text); }

/// The staging folder of this bake: tables are written there under their own names (a C header's
/// symbol comes from its name), then renamed into the folder as their index entry commits.
std::string staging_name() { return ".brdfbake-staging-" + std::to_string(::getpid()); }

/// Removes `path`, a folder of plain files, and the files in it.
void remove_folder(const std::string& path) {
    if (DIR* d = ::opendir(path.c_str())) {
        while (const dirent* e = ::readdir(d))
            if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0)
                ::unlink(join_path(path, e->d_name).c_str());
        ::closedir(d);
    }
    ::rmdir(path.c_str());
}

/// What killed bakes left in the folder (the lock is held: no other bake writes here): their
/// staging folders, the temporary files of tables, index and previews (".NAME.tmp-PID"), and the
/// report's of processes that are gone (`brdfbake report` takes no lock).
void remove_leftovers(const std::string& folder, const Plan& plan) {
    static const std::regex temporary(R"(^\.(.+)\.tmp-([0-9]+)$)");
    static const std::regex staging(R"(^\.brdfbake-staging-([0-9]+)$)");
    const long self = long(::getpid());
    std::set<std::string> ours = {"index.json", "index.html"};
    for (const auto& t : plan.tables) ours.insert(t.file);
    auto sweep = [&](const std::string& dir, bool all_names, bool only_dead) {
        DIR* d = ::opendir(dir.c_str());
        if (!d) return;
        while (const dirent* e = ::readdir(d)) {
            std::cmatch m;
            const std::string path = join_path(dir, e->d_name);
            if (dir == folder && std::regex_match(e->d_name, m, staging)) {
                if (std::strtol(m[1].str().c_str(), nullptr, 10) != self) remove_folder(path);
                continue;
            }
            if (!std::regex_match(e->d_name, m, temporary) || !(all_names || ours.count(m[1].str()))) continue;
            const long pid = std::strtol(m[2].str().c_str(), nullptr, 10);
            if (pid == self || (only_dead && (::kill(pid_t(pid), 0) == 0 || errno != ESRCH))) continue;
            struct stat st {};
            if (::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::unlink(path.c_str());
        }
        ::closedir(d);
    };
    sweep(folder, false, false);
    sweep(join_path(folder, "previews"), true, false);
    sweep(join_path(folder, "report"), true, true);
}

std::string materials_of(const PlannedTable& t) {
    std::string s;
    for (const auto& m : t.materials) s += (s.empty() ? "" : ", ") + m;
    return s;
}

/// The index a bake starts from: the plan's, listing each table of the old index that is still
/// in the plan and whose file is the one the old entry describes (its content hash). `fresh[i]`:
/// the table is up to date (also the same request hash, unless --force).
json starting_index(const Plan& plan, const BakeOptions& o, const json& old_index, std::vector<bool>& fresh) {
    json index = new_bake_index(plan);
    const bool same_hash_algorithm =
        old_index.is_object() && old_index.value("content_hash_algorithm", "") == kContentHashAlgorithm;
    // For each table with an old entry: its file is absent ('a'), the one the entry describes
    // ('1'), or another ('2'). The writer rank looks, every rank takes its answer (the ranks take
    // the same path through the bake).
    std::string described(plan.tables.size(), 'a');
    if (dist::is_writer())
        for (size_t i = 0; i < plan.tables.size(); ++i) {
            const json* e = bake_index_entry(old_index, plan.tables[i].file);
            const std::string path = join_path(o.output, plan.tables[i].file);
            if (e && file_exists(path))
                described[i] =
                    same_hash_algorithm && e->value("content_hash", "") == content_hash_of_file(path) ? '1' : '2';
        }
    described = dist::exchange(described)[0];
    fresh.assign(plan.tables.size(), false);
    for (size_t i = 0; i < plan.tables.size(); ++i) {
        const PlannedTable& t = plan.tables[i];
        const json* e = bake_index_entry(old_index, t.file);
        const std::string path = join_path(o.output, t.file);
        if (!e) continue;
        const bool same_request = e->value("request_hash", "") == t.hash;
        if (described[i] == 'a') continue;  // the entry goes with its file
        if (described[i] == '2') {
            // Another file than the entry describes (replaced behind the index's back, or a bake
            // killed between the two renames of a commit): recomputed; the entry stays until its
            // replacement commits, so that no file in the folder is without one.
            if (same_request && dist::is_writer())
                log_line(path + " is not the table index.json describes (content hash differs); recomputing it");
            bake_index_set_table(index, plan, *e);
            continue;
        }
        json entry = *e;
        if (same_request && !o.force) {
            fresh[i] = true;
            entry["materials"] = t.materials;  // which materials it serves may have changed
            entry["serves"] = t.serves;
        }
        // A table still to compute keeps its old entry until it is replaced: the entry describes
        // the file that is there.
        bake_index_set_table(index, plan, entry);
    }
    return index;
}

/// A bake's progress counts estimated idle-core microseconds (at least one per stage).
std::uint64_t progress_units(double idle_seconds) { return std::max<std::uint64_t>(1, std::uint64_t(idle_seconds * 1e6)); }

/// The tables' CPU seconds from which their own measured slowdown replaces the plan's (the least
/// a SlowdownClock measures).
constexpr double kMeasuredCpuSeconds = 0.02;

/// Computes one table, in tiles where its kind allows, advancing `stage` from `done` by `units`.
Table compute_planned(Engine& engine, const PlannedTable& t, const LutRequest& r, ProgressStage& stage,
                      std::uint64_t done, const std::string& step, std::uint64_t units) {
    const TableKind& kind = *t.kind;
    if (!kind.tileable) {
        stage.update(done, step, units);
        return compute_lut(engine, r);
    }
    const std::vector<LutRequest> tiles = bake_tiles(kind, r, 16);
    const int n = kind.one_dimensional ? r.width : r.height;
    std::vector<Table> parts;
    int rows = 0;
    for (const auto& tile : tiles) {
        const int tile_rows = kind.one_dimensional ? tile.width : tile.height;
        const std::uint64_t before = units * std::uint64_t(rows) / std::uint64_t(n);
        const std::uint64_t after = units * std::uint64_t(rows + tile_rows) / std::uint64_t(n);
        stage.update(done + before, step, after - before);
        parts.push_back(compute_lut(engine, tile));
        rows += tile_rows;
    }
    return stitch_tiles(kind, r, parts);
}

/// The state a bake carries from table to table.
struct Baking {
    const Plan& plan;
    const BakeOptions& o;
    BakeFolder& folder;
    json index;
    std::string staging;  // the staging folder (writer rank only)
    BakeTimings* timings = nullptr;  // where the stages' times go
};

/// Writes a computed table and its preview, and commits it with its index entry: the table is
/// staged under its own name and its content hash taken, then the index that lists it replaces
/// the old one and the table is renamed into the folder (two renames back to back).
/// `started`: when the table's computation began (its entry records the seconds until it is written).
/// `show(step)`: the bake's progress says what runs now (the preview is a step of its own).
double commit_table(Baking& b, const PlannedTable& t, const LutRequest& r, const Table& table, Clock::time_point started,
                    const std::function<void(const std::string&)>& show) {
    std::string preview, full;
    if (b.o.write_preview) {
        ::mkdir(join_path(b.o.output, "previews").c_str(), 0755);
        preview = "previews/" + t.file + ".png";
        show("drawing its preview " + preview);
        const auto p0 = Clock::now();
        {
            // The summary and a deep 3D table's full-size picture land together or not at all.
            OutputGroup together;
            full = b.o.write_preview(table, join_path(b.o.output, preview));
            together.commit();
        }
        if (!full.empty()) full = "previews/" + full.substr(full.find_last_of('/') + 1);
        if (b.timings)
            b.timings->previews.emplace_back(double(table.width()) * table.height() * table.depth(), since(p0));
        show("writing it");
        b.folder.commit();
    }
    const std::string staged = join_path(b.staging, t.file), path = join_path(b.o.output, t.file);
    write_table(table, dist::is_writer() ? staged : path, t.half);
    // Every rank writes the same index: the writer's content hash is shared.
    const std::string hash = dist::exchange(dist::is_writer() ? content_hash_of_file(staged) : "")[0];
    const double seconds = since(started);
    const json before = b.index;
    bake_index_set_table(b.index, b.plan, bake_index_table_entry(t, r, table, hash, preview, full, seconds));
    b.folder.commit();
    // The index first: a table is never in the folder without the entry that describes it.
    write_bake_index(b.o.output, b.index);
    if (dist::is_writer() && std::rename(staged.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        ::unlink(staged.c_str());
        // The entry goes again (this rank alone: not a collective step), best effort.
        b.index = before;
        const std::string index_path = bake_index_path(b.o.output), back = index_path + ".restore";
        if (FILE* f = std::fopen(back.c_str(), "w")) {
            const std::string text = bake_index_text(b.index);
            const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
            if (std::fclose(f) == 0 && ok) std::rename(back.c_str(), index_path.c_str());
            else std::remove(back.c_str());
        }
        throw Error("cannot write '" + path + "': " + why);
    }
    return seconds;
}

/// Removes the staging folder when the bake ends, however it ends.
struct StagingFolder {
    std::string path;
    ~StagingFolder() {
        if (!path.empty()) remove_folder(path);
    }
};

}  // namespace

std::vector<LutRequest> bake_tiles(const TableKind& kind, const LutRequest& r, int max_tiles) {
    const bool along_x = kind.one_dimensional;
    const int n = along_x ? r.width : r.height;
    const int tiles = std::max(1, std::min(n, max_tiles));
    std::vector<LutRequest> out;
    for (int k = 0; k < tiles; ++k) {
        const int j0 = n * k / tiles, j1 = n * (k + 1) / tiles;
        LutRequest t = r;
        t.alpha_lo = r.alpha_lo + (r.alpha_hi - r.alpha_lo) * j0 / n;
        t.alpha_hi = k + 1 == tiles ? r.alpha_hi : r.alpha_lo + (r.alpha_hi - r.alpha_lo) * j1 / n;
        (along_x ? t.width : t.height) = j1 - j0;
        out.push_back(t);
    }
    return out;
}

Table stitch_tiles(const TableKind& kind, const LutRequest& r, std::vector<Table>& parts) {
    Table t = std::move(parts.front());
    const bool along_x = kind.one_dimensional;
    Axis& axis = along_x ? t.x : t.y;
    for (size_t k = 1; k < parts.size(); ++k) {
        const Table& p = parts[k];
        const Axis& a = along_x ? p.x : p.y;
        axis.coordinate.insert(axis.coordinate.end(), a.coordinate.begin(), a.coordinate.end());
        axis.parameter.insert(axis.parameter.end(), a.parameter.begin(), a.parameter.end());
        for (size_t c = 0; c < t.values.size(); ++c)
            t.values[c].insert(t.values[c].end(), p.values[c].begin(), p.values[c].end());
        t.error.insert(t.error.end(), p.error.begin(), p.error.end());
        for (const auto& kv : p.attributes)
            if (!t.attributes.count(kv.first)) t.attributes.insert(kv);  // e.g. the alpha floor note
    }
    axis.lo = r.alpha_lo;
    axis.hi = r.alpha_hi;
    axis.size = int(axis.coordinate.size());
    return t;
}

BakeResult bake_plan(const Plan& plan, const BakeOptions& o,
                     const std::function<std::unique_ptr<Engine>()>& make_engine) {
    // Everything is checked before the device is touched or a file is written.
    const auto t0 = Clock::now();
    if (o.output.empty()) throw Error("-o: give an output folder");
    for (const auto& t : plan.tables)
        if (!t.unavailable.empty())
            throw Error("cannot bake '" + t.file + "' (for " + materials_of(t) + "): " + t.unavailable);
    for (const auto& w : grouped_warnings(plan.warnings)) log_line("warning: " + w);

    // The folder is locked from here on: the index read below is still the index when this bake
    // writes it, and another bake into the folder waits (docs/scenes.md, "Bake folders").
    BakeFolder folder(o.output, o.lock_timeout);
    if (dist::is_writer()) remove_leftovers(o.output, plan);
    json old_index;
    const bool had_index = bake_index_exists(o.output);
    if (had_index) {
        try {
            old_index = read_bake_index(o.output);
        } catch (const Error& e) {
            log_line(std::string("warning: ") + e.what() + "; every table is recomputed");
        }
    }
    std::vector<bool> fresh;
    Baking b{plan, o, folder, starting_index(plan, o, old_index, fresh), {}};
    std::uint64_t work = 0;  // the progress' units: idle-core microseconds, so that its time left holds across kinds
    int to_compute = 0;
    for (size_t i = 0; i < plan.tables.size(); ++i)
        if (!fresh[i]) {
            work += progress_units(plan.tables[i].idle_compute_seconds) + progress_units(plan.tables[i].idle_preview_seconds);
            ++to_compute;
        }

    // Tables of an earlier bake that the plan no longer has: reported, left in place.
    if (old_index.is_object())
        for (const auto& e : old_index["tables"]) {
            const std::string f = e.value("file", "");
            if (!f.empty() && std::none_of(plan.tables.begin(), plan.tables.end(),
                                           [&](const PlannedTable& t) { return t.file == f; }))
                log_line(join_path(o.output, f) + " is no longer in the plan; left in place, dropped from the index");
        }

    BakeResult result;
    result.tables = plan.tables.size();
    result.index_path = bake_index_path(o.output);
    // The index agrees with the folder from the start (a table removed or replaced since the last
    // bake is no longer listed).
    if (had_index || to_compute == 0)
        if (write_bake_index(o.output, b.index)) folder.commit();
    if (to_compute == 0) {
        result.seconds = since(t0);
        if (o.finish) o.finish(nullptr, {});
        return result;
    }

    StagingFolder staging;
    if (dist::is_writer()) {
        b.staging = staging.path = join_path(o.output, staging_name());
        if (::mkdir(b.staging.c_str(), 0755) != 0)
            throw Error("cannot write into '" + o.output + "': " + b.staging + ": " + std::strerror(errno));
    }
    std::unique_ptr<Engine> engine = make_engine();
    b.timings = &result.timings;
    std::set<std::string> programs;  // the kernel programs the tables built
    try {
        ProgressStage stage("bake of " + std::to_string(to_compute) + " table" + (to_compute == 1 ? "" : "s") +
                                " into " + o.output,
                            work);
        std::uint64_t done = 0;
        int n = 0;
        double wall_sum = 0, idle_sum = 0, cpu_sum = 0;  // the tables' integration: wall, idle-core and CPU seconds
        for (size_t i = 0; i < plan.tables.size(); ++i) {
            if (fresh[i]) continue;
            const PlannedTable& t = plan.tables[i];
            // The plan's slowdown until the tables have measured their own (calibration.h).
            const double slowdown = cpu_sum >= kMeasuredCpuSeconds ? wall_sum / idle_sum : plan.slowdown;
            const std::uint64_t compute_units = progress_units(t.idle_compute_seconds),
                                units = compute_units + progress_units(t.idle_preview_seconds);
            const auto t1 = Clock::now();
            LutRequest r = t.request;
            apply_eta_axis(t, r);
            char detail[160];
            std::snprintf(detail, sizeof detail, "%s table %dx%d%s, %llu samples per cell (estimate %.3g s)",
                          r.kind.c_str(), r.width, r.height, t.kind->eta_axis ? ("x" + std::to_string(t.depth)).c_str() : "",
                          static_cast<unsigned long long>(r.samples), table_estimate(t, slowdown));
            const std::string step = "[" + std::to_string(++n) + "/" + std::to_string(to_compute) + "] " + t.file;
            log_line(step + ": computing " + detail);
            const double built = engine->build_seconds();
            const SlowdownClock clock;  // how much of the cores the integration had (calibration.h)
            const Table table = compute_planned(*engine, t, r, stage, done, step, compute_units);
            wall_sum += clock.wall_seconds();
            idle_sum += clock.wall_seconds() / clock.slowdown();
            cpu_sum += clock.cpu_seconds();
            result.timings.tables.push_back({r.kind, t.request.model.substr(0, t.request.model.find(':')),
                                             precision_name(r.precision), t.samples_total,
                                             since(t1) - (engine->build_seconds() - built)});
            for (const std::string& p : t.kind->kernel_programs(r)) programs.insert(p);
            check_finite(table);
            // The table is computed: its units count as done while it is drawn and written.
            const double seconds = commit_table(b, t, r, table, t1, [&](const std::string& what) {
                stage.update(done + compute_units, step + ": " + what);
            });
            done += units;
            stage.update(done);
            result.max_error = std::max(result.max_error, table.max_error());
            ++result.computed;
            char msg[256];
            std::snprintf(msg, sizeof msg, "wrote %s in %.2f s, max error %.2e", join_path(o.output, t.file).c_str(),
                          seconds, table.max_error());
            log_line(step.substr(0, step.find(' ')) + " " + msg);
        }
        if (idle_sum > 0) result.timings.slowdown = wall_sum / idle_sum;
    } catch (const Error& e) {
        // The report shows the failure beside what was written (when the folder has an index: a
        // bake that wrote nothing into a new folder leaves none); the error goes on to the caller.
        if (o.finish && (had_index || result.computed > 0)) {
            try {
                o.finish(engine.get(), e.what());
            } catch (const Error& report) {
                log_line(std::string("warning: no report of the failed bake: ") + report.what());
            }
        }
        throw;
    }
    result.build_seconds = engine->build_seconds();
    result.timings.programs = int(programs.size());
    result.timings.build_seconds = result.build_seconds;
    result.seconds = since(t0);
    const auto f0 = Clock::now();
    if (o.finish) o.finish(engine.get(), {});
    result.timings.report_seconds = since(f0);
    return result;
}

}  // namespace brdfbake

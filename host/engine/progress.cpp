#include "brdfbake/progress.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <vector>

namespace brdfbake {

namespace {

using Clock = std::chrono::steady_clock;

struct Frame {
    std::uint64_t id = 0;
    std::string what, unit, done_word;
    std::uint64_t total = 0, done = 0, step_units = 0;
    bool estimable = true;
    std::string step;
    std::string launch;            // the last launch reported inside the step
    std::string pass;              // its pass, "pass 1 of 2: E" (empty: none)
    double launch_fraction = -1.0; // of the whole of its passes (the bar)
    double launch_shown = -1.0;    // of the launch itself (its percentage in words)
    bool new_pass = false;         // a pass began and its first launch has not reported yet
    /// The passes open when a stage began inside a pass (pass k of n, outermost first): its
    /// fraction is placed in theirs, so one bar runs across all the passes.
    std::vector<std::pair<size_t, size_t>> passes;
    Clock::time_point start, step_start;
};

std::atomic<ProgressSink*> g_sink{nullptr};
std::mutex g_mutex;
// Per thread: the open stages, outermost first (stages nest within the thread that runs the
// work; two threads computing at once, as the Python module allows, each have their own).
thread_local std::vector<Frame> g_frames;
thread_local Frame g_loose;  // a launch reporting outside any stage
thread_local bool g_loose_open = false;
std::uint64_t g_next_id = 1;

/// An open ProgressPasses: its names, the pass running (0: none yet), and how many stages were
/// open when it began (a stage opened within a pass carries the pass's label; launches do when
/// no such stage is open).
struct Passes {
    std::vector<std::string> names;
    size_t current = 0;
    size_t depth = 0;
};
thread_local std::vector<Passes> g_passes;

/// "pass 2 of 3: B", or empty outside a pass.
std::string pass_label() {
    std::string label;
    for (const Passes& p : g_passes) {
        if (p.current == 0 || p.names.empty()) continue;
        const size_t n = std::max(p.names.size(), p.current);
        label += (label.empty() ? "" : "; ") + ("pass " + std::to_string(p.current) + " of " + std::to_string(n) + ": " +
                                               p.names[std::min(p.current, p.names.size()) - 1]);
    }
    return label;
}

/// The passes running now, (pass k, of n), outermost first.
std::vector<std::pair<size_t, size_t>> passes_now() {
    std::vector<std::pair<size_t, size_t>> now;
    for (const Passes& p : g_passes)
        if (p.current > 0 && !p.names.empty()) now.emplace_back(p.current, std::max(p.names.size(), p.current));
    return now;
}

/// A fraction `f` of the innermost pass of `passes` as the fraction of all of them.
double across_passes(double f, const std::vector<std::pair<size_t, size_t>>& passes) {
    for (auto p = passes.rbegin(); p != passes.rend(); ++p) f = (double(p->first - 1) + f) / double(p->second);
    return f;
}

/// A launch's fraction `f` of its pass as the fraction of all the open passes.
double pass_fraction(double f) { return across_passes(f, passes_now()); }

/// The label is the launch's while no stage was opened inside the innermost pass.
bool launches_labelled() { return !g_passes.empty() && g_frames.size() <= g_passes.back().depth; }
int g_silenced = 0;  // open ProgressSilence objects

double seconds_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

std::string percent(double f) {
    char s[16];
    std::snprintf(s, sizeof s, " %.0f%%", 100.0 * f);
    return s;
}

/// What frame i runs now, its fraction, and when it began: its own step and launch, or, for an
/// enclosing frame, the frame inside it in words.
struct Step {
    std::string text;
    double fraction = -1.0;  // of the frame's step, across the passes it runs in (the bar)
    double shown = -1.0;     // of what runs itself (the percentage in words)
    Clock::time_point start;
};

double frame_fraction(const Frame& f, const Step& s) {
    if (f.total == 0) return s.fraction >= 0 ? s.fraction : 0.0;
    double d = double(f.done);
    if (s.fraction >= 0 && f.step_units > 0) d += s.fraction * double(f.step_units);
    return std::min(1.0, d / double(f.total));
}

std::string counts(const Frame& f) {
    if (f.unit.empty() || f.total == 0) return {};
    return std::to_string(f.done) + " of " + std::to_string(f.total) + " " + f.unit +
           (f.done_word.empty() ? "" : " " + f.done_word);
}

Step step_of(size_t i) {
    const Frame& f = g_frames[i];
    Step s;
    s.start = f.step_start;
    if (i + 1 == g_frames.size()) {
        s.text = f.step.empty() ? f.launch : f.pass.empty() ? f.step : f.step + ": " + f.pass;
        s.fraction = f.launch_fraction;
        s.shown = f.launch_shown;
        return s;
    }
    const Frame& c = g_frames[i + 1];
    const Step inner = step_of(i + 1);
    std::string text = c.what;
    const std::string n = counts(c);
    if (!n.empty()) text += " (" + n + ")";
    if (!inner.text.empty()) text += ": " + inner.text + (inner.shown >= 0 ? percent(inner.shown) : "");
    s.text = f.step.empty() ? text : f.step + "; " + text;
    s.shown = frame_fraction(c, inner);
    s.fraction = across_passes(s.shown, c.passes);
    s.start = c.start;
    return s;
}

ProgressState state_of(const Frame& f, const Step& s, bool finished) {
    const Clock::time_point now = Clock::now();
    ProgressState st;
    st.stage_id = f.id;
    st.what = f.what;
    st.done = finished && f.unit.empty() ? f.total : f.done;
    st.total = f.total;
    st.unit = f.unit;
    st.done_word = f.done_word;
    st.step = finished ? std::string() : s.text;  // an ended stage is shown by its name alone
    st.step_fraction = finished ? -1.0 : s.shown;
    st.fraction = finished ? 1.0 : frame_fraction(f, s);
    st.elapsed = seconds_between(f.start, now);
    st.finished = finished;
    if (!finished) {
        if (f.estimable && st.fraction > 0.0) {
            st.seconds_left = st.elapsed * (1.0 / st.fraction - 1.0);
        } else if (s.fraction > 0.0) {
            st.seconds_left = seconds_between(s.start, now) * (1.0 / s.fraction - 1.0);
            st.left_is_step = true;
        }
    }
    return st;
}

void publish(bool finished, bool milestone = false) {
    ProgressSink* sink = g_sink.load();
    // A stage's end always reaches the sink (one shown before a silence began must not stay drawn).
    if (!sink || g_frames.empty() || (g_silenced > 0 && !finished)) return;
    ProgressState st = state_of(g_frames.front(), step_of(0), finished);
    st.milestone = milestone;
    sink->update(st);
}

}  // namespace

void set_progress_sink(ProgressSink* sink) { g_sink.store(sink); }

ProgressStage::ProgressStage(std::string what, std::uint64_t total, std::string unit, std::string done_word,
                             bool estimable) {
    std::lock_guard<std::mutex> lock(g_mutex);
    Frame f;
    f.id = g_next_id++;
    const std::string label = launches_labelled() ? pass_label() : std::string();
    f.what = label.empty() ? std::move(what) : label + ": " + what;
    if (!label.empty()) f.passes = passes_now();
    f.total = total;
    f.unit = std::move(unit);
    f.done_word = std::move(done_word);
    f.estimable = estimable;
    f.start = f.step_start = Clock::now();
    g_frames.push_back(std::move(f));
    depth_ = g_frames.size();
    publish(false);
}

ProgressStage::~ProgressStage() {
    try {
        std::lock_guard<std::mutex> lock(g_mutex);
        if (g_frames.size() != depth_) return;  // stages close in the order they opened
        if (depth_ == 1) publish(true);
        // A counted inner stage's end ("4096 of 4096 cells certified") is shown once in a log.
        else if (g_frames.back().total > 0) publish(false, true);
        g_frames.pop_back();
        if (!g_frames.empty()) {
            g_frames.back().launch.clear();
            g_frames.back().pass.clear();
            g_frames.back().launch_fraction = g_frames.back().launch_shown = -1.0;
            publish(false);
        }
    } catch (...) {  // a sink that throws must not end the program from a destructor
    }
}

void ProgressStage::update(std::uint64_t done, const std::string& step, std::uint64_t step_units) {
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_frames.size() < depth_) return;
    Frame& f = g_frames[depth_ - 1];
    f.done = std::min(done, f.total ? f.total : done);
    if (step != f.step || step_units != f.step_units) f.step_start = Clock::now();
    const bool new_step = step != f.step;
    f.step = step;
    f.step_units = step_units;
    f.launch.clear();
    f.pass.clear();
    f.launch_fraction = f.launch_shown = -1.0;
    publish(false, new_step && !step.empty());
}

ProgressSilence::ProgressSilence() {
    std::lock_guard<std::mutex> lock(g_mutex);
    ++g_silenced;
}

ProgressSilence::~ProgressSilence() {
    std::lock_guard<std::mutex> lock(g_mutex);
    --g_silenced;
}

void report_progress(const std::string& what, std::uint64_t done, std::uint64_t total) {
    if (!g_sink.load()) return;
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_silenced > 0) return;
    const double raw = total ? std::min(1.0, double(done) / double(total)) : 1.0;
    const std::string label = launches_labelled() ? pass_label() : std::string();
    if (!g_frames.empty()) {
        Frame& f = g_frames.back();
        f.launch = label.empty() ? what : label + ": " + what;
        f.pass = label;
        f.launch_fraction = label.empty() ? raw : pass_fraction(raw);
        f.launch_shown = raw;
        const bool new_pass = f.new_pass;
        f.new_pass = false;
        publish(false, new_pass);
        return;
    }
    const std::string what_shown = label.empty() ? what : label + ": " + what;
    // A launch outside any stage is a stage of its own, counted in the launch's units.
    if (!g_loose_open || what_shown != g_loose.what || done < g_loose.done) {
        g_loose = Frame();
        g_loose.id = g_next_id++;
        g_loose.what = what_shown;
        g_loose.start = g_loose.step_start = Clock::now();
        g_loose_open = true;
    }
    g_loose.total = total;
    g_loose.done = done;
    const bool finished = done >= total;
    ProgressState st = state_of(g_loose, Step{}, finished);
    st.closes = false;
    if (ProgressSink* sink = g_sink.load()) sink->update(st);
    if (finished) g_loose_open = false;
}

ProgressPasses::ProgressPasses(std::vector<std::string> names) {
    std::lock_guard<std::mutex> lock(g_mutex);
    g_passes.push_back({std::move(names), 0, g_frames.size()});
}

ProgressPasses::~ProgressPasses() {
    std::lock_guard<std::mutex> lock(g_mutex);
    if (!g_passes.empty()) g_passes.pop_back();
}

void progress_next_pass() {
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_passes.empty()) return;
    ++g_passes.back().current;
    // The frame the passes run in shows the new pass at once (its launch is the last pass's).
    if (!g_frames.empty() && launches_labelled()) {
        Frame& f = g_frames.back();
        f.launch = f.pass = pass_label();
        f.launch_fraction = pass_fraction(0.0);
        f.launch_shown = 0.0;
        f.new_pass = true;  // its first launch is written at once in a log
        publish(false);
    }
}

void progress_message(const std::string& line) {
    if (ProgressSink* sink = g_sink.load()) {
        sink->message(line);
        return;
    }
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
}

std::string progress_duration(double seconds) {
    char s[48];
    const long t = std::lround(std::max(0.0, seconds));
    if (seconds < 9.95)
        std::snprintf(s, sizeof s, "%.1f s", std::max(0.0, seconds));
    else if (t < 60)
        std::snprintf(s, sizeof s, "%ld s", t);
    else if (t < 3600)
        std::snprintf(s, sizeof s, "%ld min %ld s", t / 60, t % 60);
    else
        std::snprintf(s, sizeof s, "%ld h %ld min", t / 3600, (t % 3600) / 60);
    return s;
}

}  // namespace brdfbake

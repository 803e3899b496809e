// The command line's progress display (brdfbake/progress.h): on a terminal a bar on stderr that
// redraws in place (done, rate, time left), also while a long launch reports nothing (a ticker
// thread redraws the clock); otherwise a plain line at least every 5 s while a stage runs, at
// each further tenth after at least a second, and at once when a new pass or step begins. A stage
// that ends within a second prints nothing, so short runs stay quiet (BRDFBAKE_PROGRESS_DELAY
// sets that second).
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

#include "cli/cli.h"

namespace brdfbake {

namespace {

using Clock = std::chrono::steady_clock;

/// How long a launch reporting outside any stage is ticked after its last report.
constexpr double kLooseTickSeconds = 60.0;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// "2.3e+03 cells/s" style rates, readable whatever the size.
std::string rate_text(double per_second, const std::string& unit) {
    char s[64];
    if (per_second >= 100)
        std::snprintf(s, sizeof s, "%.0f %s/s", per_second, unit.c_str());
    else
        std::snprintf(s, sizeof s, "%.3g %s/s", per_second, unit.c_str());
    return s;
}

/// The percentage shown: 100 only when the stage ended.
double percent(const ProgressState& s) { return s.finished ? 100.0 : std::min(99.0, std::floor(100.0 * s.fraction)); }

/// The state in words, without the percentage: what runs ("rough dielectric of 4096 cells to
/// tolerance 0.0001"), the detail ("820 of 2048 cells certified, 68 cells/s; round 3: ... 35%")
/// and the clock ("12 s, about 5.0 s left in this step").
struct Words {
    std::string what, counts, rate, step, clock;
    /// The detail: counts, rate and step, each if there is one.
    std::string detail(bool with_rate = true) const {
        std::string d = counts;
        if (with_rate && !rate.empty()) d += ", " + rate;
        if (!step.empty()) d += (d.empty() ? "" : "; ") + step;
        return d;
    }
    std::string text() const { return detail().empty() ? what : what + ": " + detail(); }
};

Words describe(const ProgressState& s, double elapsed, double left) {
    Words w;
    w.what = s.what;
    if (!s.unit.empty() && s.total > 0) {
        w.counts = std::to_string(s.done) + " of " + std::to_string(s.total) + " " + s.unit +
                   (s.done_word.empty() ? "" : " " + s.done_word);
        if (s.done > 0 && elapsed > 0.5) w.rate = rate_text(double(s.done) / elapsed, s.unit);
    }
    if (!s.step.empty()) {
        w.step = s.step;
        if (s.step_fraction >= 0) {
            char p[16];
            std::snprintf(p, sizeof p, " %.0f%%", 100 * s.step_fraction);
            w.step += p;
        }
    }
    w.clock = progress_duration(elapsed);
    // A step's estimate ends with its launch; a finished launch says nothing of the step's rest.
    const bool step_left = s.left_is_step && s.step_fraction < 0.999;
    if (left >= 0 && !s.finished && (!s.left_is_step || step_left))
        w.clock += ", about " + progress_duration(left) + " left" + (s.left_is_step ? " in this step" : "");
    return w;
}

class StderrProgress : public ProgressSink {
public:
    StderrProgress() : tty_(::isatty(2) != 0) {
        // BRDFBAKE_PROGRESS_DELAY=S: show stages that run longer than S seconds (default 1).
        if (const char* d = std::getenv("BRDFBAKE_PROGRESS_DELAY")) {
            char* end = nullptr;
            const double v = std::strtod(d, &end);
            if (end != d && *end == '\0' && v >= 0 && v < 1e6) delay_ = v;
        }
    }

    ~StderrProgress() override {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        if (ticker_.joinable()) ticker_.join();
    }

    void update(const ProgressState& s) override {
        std::lock_guard<std::mutex> lock(mutex_);
        if (s.stage_id != state_.stage_id) {
            shown_ = false;
            milestone_ = false;
            last_tenth_ = -1;
        }
        state_ = s;
        milestone_ = milestone_ || s.milestone;
        received_ = Clock::now();
        if (s.finished) {
            if (shown_) {
                if (tty_)
                    std::fputs("\r\033[K", stderr);
                else
                    line();
                std::fflush(stderr);
            }
            shown_ = false;
            active_ = false;
            return;
        }
        active_ = true;
        // A stage may go quiet for a long launch: a ticker keeps the clock moving (on a
        // terminal) and the lines coming (in a log, at least every 5 s).
        if (!ticker_.joinable()) ticker_ = std::thread([this] { tick(); });
        draw(false);
    }

    void message(const std::string& text) override {
        std::lock_guard<std::mutex> lock(mutex_);
        const bool bar_shown = tty_ && shown_ && active_;
        std::fprintf(stderr, "%s%s\n", bar_shown ? "\r\033[K" : "", text.c_str());
        if (bar_shown) bar(state_.elapsed + since(received_), since(received_));
        std::fflush(stderr);
    }

private:
    void tick() {
        std::unique_lock<std::mutex> lock(mutex_);
        while (!stop_) {
            wake_.wait_for(lock, std::chrono::milliseconds(250));
            // A launch outside any stage may stop without its last report (an error unwinds
            // it): it is ticked for a minute after its last report, longer than a slice takes.
            if (!stop_ && active_ && (state_.closes || since(received_) < kLooseTickSeconds)) draw(true);
        }
    }

    /// Draws the state (mutex held); `ticking`: no new report, only the clock moved.
    void draw(bool ticking) {
        const double moved = since(received_);
        const double elapsed = state_.elapsed + moved;
        if (!shown_ && elapsed < delay_) return;  // quick stages say nothing
        if (tty_) {
            if (shown_ && since(last_draw_) < (ticking ? 0.5 : 0.1)) return;
            bar(elapsed, moved);
        } else {
            const int tenth = int(std::floor(state_.fraction * 10));
            const double quiet = since(last_draw_);
            // A new pass or step (the preview) is written at once: a log names every one.
            if (shown_ && quiet < 5.0 && !(tenth > last_tenth_ && quiet >= 1.0) && !milestone_) return;
            last_tenth_ = tenth;
            milestone_ = false;
            line();
        }
        std::fflush(stderr);
        last_draw_ = Clock::now();
        shown_ = true;
    }

    double left_now(double moved) const {
        return state_.seconds_left < 0 ? -1.0 : std::max(0.0, state_.seconds_left - moved);
    }

    void bar(double elapsed, double moved) {
        const Words w = describe(state_, elapsed, left_now(moved));
        const int width = 24, filled = int(state_.fraction * width + 0.5);
        char head[64];
        std::snprintf(head, sizeof head, "[%s%s] %3.0f%%  ", std::string(size_t(filled), '#').c_str(),
                      std::string(size_t(width - filled), '.').c_str(), percent(state_));
        const std::string tail = "  " + w.clock;
        std::string all = head + w.text() + tail;
        // One terminal line (a line that wraps cannot be redrawn in place): where the whole does
        // not fit, the stage's name goes first, then the rate, then the rest is cut.
        struct winsize ws {};
        if (::ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 8 && all.size() >= ws.ws_col) {
            const size_t keep = size_t(ws.ws_col) - 1;
            std::string body = w.detail().empty() ? w.what : w.detail();
            if (std::string(head).size() + body.size() + tail.size() > keep && !w.detail(false).empty())
                body = w.detail(false);
            all = head + body + tail;
            if (all.size() > keep)
                all = std::string(head).size() + tail.size() + 20 < keep
                          ? std::string(head) + body.substr(0, keep - std::string(head).size() - tail.size() - 3) + "..." + tail
                          : all.substr(0, keep);
        }
        std::fprintf(stderr, "\r\033[K%s", all.c_str());
    }

    void line() {
        const double moved = state_.finished ? 0.0 : since(received_);
        const Words w = describe(state_, state_.elapsed + moved, left_now(moved));
        std::fprintf(stderr, "brdfbake: %3.0f%% of %s (%s)\n", percent(state_), w.text().c_str(), w.clock.c_str());
    }

    const bool tty_;
    double delay_ = 1.0;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::thread ticker_;
    bool stop_ = false;
    bool active_ = false;
    bool shown_ = false;
    bool milestone_ = false;  // a new step or pass not yet written to the log
    int last_tenth_ = -1;
    ProgressState state_;
    Clock::time_point received_, last_draw_;
};

}  // namespace

ProgressSink& stderr_progress() {
    static StderrProgress sink;
    return sink;
}

}  // namespace brdfbake

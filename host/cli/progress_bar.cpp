// The command line's progress display (brdfbake/progress.h): on a terminal a bar on stderr that
// redraws in place (done, rate, time left); otherwise a plain line every few seconds. A stage
// that ends within a second prints nothing, so short runs stay quiet.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "cli/cli.h"

namespace brdfbake {

namespace {

class StderrProgress : public ProgressSink {
public:
    StderrProgress() : tty_(::isatty(2) != 0) {}

    void update(const std::string& what, std::uint64_t done, std::uint64_t total) override {
        const auto now = std::chrono::steady_clock::now();
        if (what != stage_ || done == 0 || done < done_) {
            stage_ = what;
            start_ = now;
            shown_ = false;
            last_ = now;
        }
        done_ = done;
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        const bool finished = done >= total;
        if (!shown_ && (elapsed < 1.0 || finished)) return;  // quick stages say nothing
        const double since = std::chrono::duration<double>(now - last_).count();
        if (shown_ && !finished && since < (tty_ ? 0.1 : 5.0)) return;
        last_ = now;
        const double fraction = total ? double(done) / double(total) : 1.0;
        char left[64] = "";
        if (fraction > 0 && !finished) std::snprintf(left, sizeof left, ", about %.0f s left", elapsed * (1 / fraction - 1));
        if (tty_) {
            const int width = 24, filled = int(fraction * width + 0.5);
            std::fprintf(stderr, "\r\033[K[%s%s] %3.0f%%  %s  %.1f s%s", std::string(size_t(filled), '#').c_str(),
                         std::string(size_t(width - filled), '.').c_str(), 100 * fraction, stage_.c_str(), elapsed, left);
            if (finished) std::fprintf(stderr, "\r\033[K");
        } else {
            std::fprintf(stderr, "brdfbake: %3.0f%% of %s (%.1f s%s)\n", 100 * fraction, stage_.c_str(), elapsed, left);
        }
        std::fflush(stderr);
        shown_ = true;
    }

private:
    bool tty_;
    std::string stage_;
    std::uint64_t done_ = 0;
    std::chrono::steady_clock::time_point start_, last_;
    bool shown_ = false;
};

}  // namespace

ProgressSink& stderr_progress() {
    static StderrProgress sink;
    return sink;
}

}  // namespace brdfbake

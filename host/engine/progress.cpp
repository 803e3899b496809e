#include "brdfbake/progress.h"

#include <atomic>

namespace brdfbake {

namespace {
std::atomic<ProgressSink*> g_sink{nullptr};
}  // namespace

void set_progress_sink(ProgressSink* sink) { g_sink.store(sink); }

void report_progress(const std::string& what, std::uint64_t done, std::uint64_t total) {
    if (ProgressSink* s = g_sink.load()) s->update(what, done, total);
}

}  // namespace brdfbake

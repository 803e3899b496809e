#include "brdfbake/cancel.h"

#include <atomic>

namespace brdfbake {

namespace {
std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "request_cancel must be async-signal-safe");
}  // namespace

void request_cancel() { g_cancel.store(true); }
void clear_cancel() { g_cancel.store(false); }
void throw_if_cancelled() {
    if (g_cancel.load()) throw Cancelled();
}

}  // namespace brdfbake

// Stopping a long computation from outside (Ctrl-C in the Python module): a process-wide flag
// that the integration drivers read before every kernel launch. A launch already running
// finishes; the next one does not start, and the computation throws Cancelled.
#pragma once

#include "brdfbake/error.h"

namespace brdfbake {

class Cancelled : public Error {
public:
    Cancelled() : Error("interrupted") {}
};

/// Asks the running computation to stop at its next kernel launch (async-signal-safe).
void request_cancel();
/// Clears the request; a front end calls it before starting a computation.
void clear_cancel();
/// Throws Cancelled if a stop was requested.
void throw_if_cancelled();

}  // namespace brdfbake

// Progress of long computations: the integration drivers report how much of a kernel launch is
// done to a process-wide sink, which a front end installs (the command line draws a bar on a
// terminal, plain lines otherwise; nothing with --quiet). Without a sink, reports cost nothing.
#pragma once

#include <cstdint>
#include <string>

namespace brdfbake {

class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    /// `done` of `total` units of the stage `what` are finished (done == total: the stage ended).
    virtual void update(const std::string& what, std::uint64_t done, std::uint64_t total) = 0;
};

/// Installs the sink (nullptr: none). The caller keeps it alive while computations run.
void set_progress_sink(ProgressSink* sink);

/// Reports to the installed sink, if any.
void report_progress(const std::string& what, std::uint64_t done, std::uint64_t total);

}  // namespace brdfbake

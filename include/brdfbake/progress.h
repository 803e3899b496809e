// Progress of long computations. The integration drivers and the commands open stages (a
// tolerance refinement: cells certified of cells total over its rounds; a check: its scans) and
// the kernel launches report how far they are; everything goes to a process-wide sink, which a
// front end installs (the command line draws a bar on a terminal, plain lines otherwise, nothing
// with --quiet). Without a sink, reports cost next to nothing. Reports never change a number.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brdfbake {

/// What a sink is shown: the outermost open stage, with what runs inside it folded into `step`.
struct ProgressState {
    std::uint64_t stage_id = 0;   // new for every stage (a sink starts its clock at a new one)
    std::string what;             // the stage: "rough dielectric of 4096 cells to tolerance 0.0001"
    std::uint64_t done = 0;       // units of the stage finished
    std::uint64_t total = 0;      // units of the stage; 0: not counted
    std::string unit;             // the units' name, e.g. "cells"; empty: no counts or rate shown
    std::string done_word;        // what "done" means for them, e.g. "certified"; may be empty
    std::string step;             // the part running now (a round, a launch, a nested stage); may be empty
    double step_fraction = -1.0;  // how far the step is, 0 to 1, when it reports it; else -1
    double fraction = 0.0;        // of the whole stage, 0 to 1 (the bar)
    double elapsed = 0.0;         // seconds since the stage began
    double seconds_left = -1.0;   // an estimate, or -1 when there is none
    bool left_is_step = false;    // seconds_left is for the step only (the stage's rest is unknown)
    bool finished = false;        // the stage ended (the last report of a stage)
    /// The stage reports its end even when an error unwinds it (a ProgressStage); a launch
    /// reporting outside any stage may stop without a last report.
    bool closes = true;
    /// A new step or pass began ("pass 2 of 2: B", "drawing its preview"): a log shows it at once.
    bool milestone = false;
};

class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    /// A stage changed (at most once per report; the sink decides what to draw and when).
    virtual void update(const ProgressState& state) = 0;
    /// A line of a log written while stages run (a terminal's bar is cleared for it and redrawn).
    virtual void message(const std::string& line) = 0;
};

/// Installs the sink (nullptr: none). The caller keeps it alive while computations run.
void set_progress_sink(ProgressSink* sink);

/// A stage of work made of several launches or steps, open while the object lives. Stages
/// nest: an inner stage, and the launches' report_progress, become the step of the stage that
/// encloses them, so the display stays on the outermost one. Stages nest per thread.
class ProgressStage {
public:
    /// `total` units named `unit` (empty: the stage counts no units). `estimable`: the stage's
    /// fraction grows with its work, so a time left follows from it (not so for a refinement,
    /// whose later rounds' cost is unknown: then the time left is the current step's).
    ProgressStage(std::string what, std::uint64_t total, std::string unit = {}, std::string done_word = {},
                  bool estimable = true);
    ~ProgressStage();  // reports the stage finished
    ProgressStage(const ProgressStage&) = delete;
    ProgressStage& operator=(const ProgressStage&) = delete;

    /// `done` units are finished and `step` runs now; when it finishes it will have added
    /// `step_units` units (0: unknown), which places a launch's fraction in the stage's.
    void update(std::uint64_t done, const std::string& step = {}, std::uint64_t step_units = 0);

private:
    std::size_t depth_;
};

/// While one lives, no stage or launch is shown (the stages still nest): for a front end that
/// draws its own progress over many computations, so that two displays do not draw over each
/// other (`bake` needs none: it is one stage). progress_message still writes.
class ProgressSilence {
public:
    ProgressSilence();
    ~ProgressSilence();
    ProgressSilence(const ProgressSilence&) = delete;
    ProgressSilence& operator=(const ProgressSilence&) = delete;
};

/// The passes of a computation that integrates its cells several times, one after the other (a
/// split-sum table's E and B, a conductor's R, G and B): while one lives, what runs is shown as
/// "pass k of n: NAME", and a launch's fraction as its pass's share of the whole. next() begins
/// the next pass (the first call the first); calls beyond `names` count on with the last name.
/// Per thread, like the stages; a ProgressPasses inside another's pass adds to its label.
class ProgressPasses {
public:
    explicit ProgressPasses(std::vector<std::string> names);
    ~ProgressPasses();
    ProgressPasses(const ProgressPasses&) = delete;
    ProgressPasses& operator=(const ProgressPasses&) = delete;
};

/// Begins the next pass of this thread's innermost ProgressPasses; nothing when none is open.
void progress_next_pass();

/// A launch's report: `done` of `total` units of `what` are finished (done == total: it ended).
/// Inside a stage it is that stage's step; outside any, a stage of its own.
void report_progress(const std::string& what, std::uint64_t done, std::uint64_t total);

/// Writes one line (without its newline) to stderr through the sink, so that it does not run
/// into a progress bar; without a sink, straight to stderr.
void progress_message(const std::string& line);

/// "12 s", "3 min 5 s", "1 h 2 min": a duration for progress and estimates.
std::string progress_duration(double seconds);

}  // namespace brdfbake

// The command line: each command registers itself on the CLI11 app and sets the action that
// main() runs after parsing.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/progress.h"

namespace brdfbake {

/// Checks a picture path before any work: it must end in .png or .svg (else Error naming
/// `option`) and be writable where prepare_output would write it. Empty: nothing to check.
void check_plot_output(const std::string& path, const std::string& option);
/// Checks a text output path (-o of albedo, fresnel, check ...) before any work; empty or "-"
/// is standard output.
void check_text_output(const std::string& path);

/// Checks that an option's value is a finite number > 0 (for options whose 0 means "not given":
/// given, 0 is refused rather than silently taken for the default).
extern const CLI::Validator kPositive;
/// A finite number of 0 or more (e.g. a time limit whose 0 means "at once").
extern const CLI::Validator kNonNegative;

/// Lets every integer option of `app` and its commands (CLI11 type INT or UINT) take exact
/// integers written as 1e6, 2^20 or 1<<20 besides plain digits; anything else (1.5e0, abc) is
/// refused with "OPTION: must be an integer ...". main() installs it once, for every command.
void accept_integer_forms(CLI::App& app);
/// Reads an integer as accept_integer_forms does: the value's plain decimal text, or throws
/// Error("`what`: must be an integer ...").
std::string integer_text(const std::string& text, const std::string& what);

/// The first word of `arguments` that looks like an option (-x, --name, --name=value) and that
/// neither the command `arguments` name nor the program knows: "unknown option '--mdoel' of
/// `brdfbake lut`; did you mean '--model'?", or empty. main() asks it when CLI11's parse fails, as
/// CLI11 reports a missing required option before an unknown one.
std::string unknown_option_message(CLI::App& app, const std::vector<std::string>& arguments);

/// Options that every command shares.
struct GlobalOptions {
    std::string device;  // device selector (see choose_device); empty: $BRDFBAKE_DEVICE or PoCL
    bool verbose = false;
};

/// --samples, --method, --tolerance and --max-samples, shared by the integrating commands.
struct MethodOptions {
    std::int64_t samples = 1 << 18;
    std::string method = "auto";
    double tolerance = 0.0;
    std::int64_t max_samples = std::int64_t(1) << 26;
};
/// Adds the MethodOptions to `cmd`; `per` names what the samples are spent on ("texel").
void add_method_options(CLI::App* cmd, MethodOptions& o, const std::string& per);

/// The options as a MethodChoice (choose_method, brdfbake/albedo.h).
MethodChoice resolve_method_choice(const MethodOptions& o);

/// The help text of --fresnel: the Fresnel spec forms of the Fresnel registry.
std::string fresnel_spec_help();

/// --precision float|double (the kernels' arithmetic), described by `description`.
void add_precision_option(CLI::App* cmd, std::string& precision, const std::string& description = "kernel arithmetic");
/// --colour-space srgb|acescg (default srgb): the colour of a spectral Fresnel term.
void add_colour_space_option(CLI::App* cmd, std::string& colour_space, const std::string& description);
/// --format, one of `formats` ("table", "json", "csv").
void add_format_option(CLI::App* cmd, std::string& format, const std::vector<std::string>& formats);

/// What main() runs once the command line is parsed; returns the exit status.
using Action = std::function<int()>;

/// Adds the subcommand `name` with a fresh set of options (`initial`), which the caller
/// registers on the returned subcommand; once the command line is parsed main() runs
/// run(options, global).
template <typename Options, typename Run>
std::pair<CLI::App*, std::shared_ptr<Options>> add_command(CLI::App& app, const std::string& name,
                                                           const std::string& description, const GlobalOptions& global,
                                                           Action& action, Run run, Options initial = Options()) {
    auto options = std::make_shared<Options>(std::move(initial));
    CLI::App* cmd = app.add_subcommand(name, description);
    cmd->callback([options, &global, &action, run] { action = [options, &global, run] { return run(*options, global); }; });
    return {cmd, options};
}

/// The progress display on stderr (a bar on a terminal, lines otherwise) that main() installs
/// unless --quiet is given.
ProgressSink& stderr_progress();

void add_albedo_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_devices_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_fresnel_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_lut_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_check_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_reciprocity_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_furnace_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_plan_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_bake_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_bench_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_show_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_lobe_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_report_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_merge_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_compensation_command(CLI::App& app, const GlobalOptions& global, Action& action);
void add_fit_command(CLI::App& app, const GlobalOptions& global, Action& action);

/// Parses and runs one command line (the words after the program's name), as main() does: the
/// status it exits with; errors printed as one `brdfbake: error:` line (by rank 0 of an MPI job).
/// `brdfbake merge` runs the shards' command through it.
int run_command_line(const std::vector<std::string>& arguments);
/// The words of the command line being run (after the program's name).
const std::vector<std::string>& command_line();
/// A shard's command as its part file records it: `words` less --shard, -o/--output and the
/// options that do not change a table (--device, --max-memory, -v, -q), so that shards run on
/// different machines belong together; merge runs it with its own -o.
std::vector<std::string> shard_command(const std::vector<std::string>& words);

}  // namespace brdfbake

// brdfbake: integrate BRDFs in OpenCL kernels and emit lookup tables and plots.
// Library code throws brdfbake::Error; this is the one place that turns errors into exit codes.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "brdfbake/version.h"
#include "cli/cli.h"
#include "cli/mpi_world.h"
#include "engine/distributed.h"

namespace brdfbake {
namespace {
std::vector<std::string> g_command_line;

/// In an MPI job every rank must run one command: each rank's command line, less the options
/// that do not change results (shard_command: -o, --device, --max-memory, -v, -q), is compared
/// with rank 0's before any work; a rank given, say, another --samples would mix its results
/// into the table. Throws Error on every rank, naming the first word that differs.
void check_ranks_run_one_command(const std::vector<std::string>& arguments) {
    if (!dist::active()) return;
    const std::vector<std::string> mine = shard_command(arguments);
    std::string packed;
    for (const std::string& w : mine) packed += w + '\0';
    const std::vector<std::string> all = dist::exchange(packed);
    auto unpack = [](const std::string& text) {
        std::vector<std::string> words;
        for (size_t at = 0, end; (end = text.find('\0', at)) != std::string::npos; at = end + 1)
            words.push_back(text.substr(at, end - at));
        return words;
    };
    const std::vector<std::string> first = unpack(all[0]);
    for (size_t r = 1; r < all.size(); ++r) {
        if (all[r] == all[0]) continue;
        const std::vector<std::string> other = unpack(all[r]);
        size_t k = 0;
        while (k < first.size() && k < other.size() && first[k] == other[k]) ++k;
        auto word = [](const std::vector<std::string>& w, size_t k) {
            return k < w.size() ? "'" + w[k] + "'" : std::string("the end of the command");
        };
        throw Error("the ranks of an MPI job must run one command: rank " + std::to_string(r) + " of " +
                    std::to_string(all.size()) + " has " + word(other, k) + " where rank 0 has " + word(first, k) +
                    " (word " + std::to_string(k + 1) + ")");
    }
}
/// What a command printed is its result: a full disk or a closed pipe must not pass as success
/// (stdout is buffered, so a failed write shows at the flush, or at an earlier write whose errno
/// the caller kept: `errno_kept`). Throws Error.
void flush_standard_output(bool errno_kept = false) {
    std::cout.flush();
    if (!errno_kept) errno = 0;
    if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
        const int err = errno;
        throw Error(std::string("cannot write standard output") +
                    (err ? std::string(": ") + std::strerror(err) : std::string()));
    }
}
}  // namespace

const std::vector<std::string>& command_line() { return g_command_line; }

int run_command_line(const std::vector<std::string>& arguments) {
    g_command_line = arguments;
    std::vector<std::string> words{"brdfbake"};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv_words;
    for (std::string& w : words) argv_words.push_back(w.data());
    const int argc = int(argv_words.size());
    char** argv = argv_words.data();
    // In an MPI job the ranks agree at the end, so that a rank that fails after the others'
    // last step still ends the job (engine/distributed.h); only rank 0 prints the error.
    auto fail = [](const Error& e) {
        const Error job = dist::report_failure(e);
        if (dist::is_writer()) std::cerr << "brdfbake: error: " << job.what() << "\n";
        return job.exit_code();
    };
    CLI::App app{"brdfbake " BRDFBAKE_VERSION
                 ": integrate BRDFs in OpenCL kernels (PoCL by default) and write lookup tables and plots"};
    app.require_subcommand(1);
    app.fallthrough();  // global options may follow the command: `brdfbake albedo ... --device 0:0`
    app.set_version_flag("--version", BRDFBAKE_VERSION);
    GlobalOptions global;
    app.add_option("--device", global.device,
                   "OpenCL device: P:D, N (index in `brdfbake devices`), cpu or gpu; default "
                   "$BRDFBAKE_DEVICE, else PoCL")
        ->envname("BRDFBAKE_DEVICE");
    app.add_flag("-v,--verbose", global.verbose, "print the device, kernel builds and timings to stderr");
    bool quiet = false;
    app.add_flag("-q,--quiet", quiet, "no progress display on stderr");
    std::string max_memory;
    app.add_option("--max-memory", max_memory,
                   "refuse work that would take more memory than this (e.g. 8G, 512M); default "
                   "$BRDFBAKE_MAX_MEMORY, else half the physical memory")
        ->envname("BRDFBAKE_MAX_MEMORY");

    Action action;
    add_albedo_command(app, global, action);
    add_devices_command(app, global, action);
    add_fresnel_command(app, global, action);
    add_lut_command(app, global, action);
    add_check_command(app, global, action);
    add_reciprocity_command(app, global, action);
    add_furnace_command(app, global, action);
    add_plan_command(app, global, action);
    add_bake_command(app, global, action);
    add_show_command(app, global, action);
    add_lobe_command(app, global, action);
    add_report_command(app, global, action);
    add_bench_command(app, global, action);
    add_merge_command(app, global, action);
    add_compensation_command(app, global, action);
    add_fit_command(app, global, action);
    accept_integer_forms(app);

    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
    // No arguments: a short usage, not the whole help, and the status of bad input.
    if (argc < 2)
        return fail(Error("no command given; usage: brdfbake COMMAND [OPTIONS] with COMMAND one of " + names +
                          " (brdfbake --help, brdfbake COMMAND --help)"));
    // A first word that is neither an option nor a command gets its own message.
    if (argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == argv[1];
        if (!known) return fail(Error(std::string("unknown command '") + argv[1] + "'; commands: " + names));
    }

    // --help and --version print their answer, which must reach standard output like any result.
    auto answer = [&](const std::string& text) {
        errno = 0;
        std::cout << text;
        try {
            flush_standard_output(true);
        } catch (const Error& e) {
            return fail(e);
        }
        return int(kExitOk);
    };
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        return answer(app.help());
    } catch (const CLI::CallForAllHelp&) {
        return answer(app.help("", CLI::AppFormatMode::All));
    } catch (const CLI::CallForVersion&) {
        return answer(std::string("brdfbake ") + BRDFBAKE_VERSION + "\n");
    } catch (const CLI::ParseError& e) {
        // A mistyped option first: CLI11 would report the required option it hid ("--mdoel":
        // "--model is required").
        const std::string unknown = unknown_option_message(app, arguments);
        if (!unknown.empty()) return fail(Error(unknown));
        // One line: CLI11's message (some span lines) and where the usage is.
        std::string message = e.what();
        for (char& c : message)
            if (c == '\n') c = ' ';
        while (!message.empty() && message.back() == ' ') message.pop_back();
        std::string where = "brdfbake --help";
        for (const CLI::App* sub : app.get_subcommands())
            where = "brdfbake " + sub->get_name() + " --help";
        return fail(Error(message + " (see " + where + ")"));
    }

    try {
        if (!max_memory.empty()) {
            try {
                set_memory_limit(parse_memory_size(max_memory));
            } catch (const Error& e) {
                throw Error(std::string("--max-memory (or BRDFBAKE_MAX_MEMORY): ") + e.what());
            }
        }
        check_ranks_run_one_command(arguments);
        if (!quiet && dist::is_writer()) set_progress_sink(&stderr_progress());
        const int status = action ? action() : kExitError;
        flush_standard_output();
        dist::agree();
        return status;
    } catch (...) {
        return fail(dist::describe_failure(std::current_exception()));
    }
}

}  // namespace brdfbake

int main(int argc, char** argv) {
    using namespace brdfbake;
    // An MPI rank (mpirun, srun) joins its job here; a plain run is the one process it always was.
    // Ranks other than 0 print nothing: their results and errors reach rank 0, which prints.
    // A reader that closes the pipe early (`brdfbake show T | head -1`) makes the next write fail
    // with EPIPE, reported as "cannot write standard output" with exit status 2 (the README's
    // promise), instead of a silent death by SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    MpiSession mpi;
    if (!dist::is_writer()) {
        if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr)) return kExitError;
    }
    return run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}

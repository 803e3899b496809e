// brdfbake: integrate BRDFs in OpenCL kernels and emit lookup tables and plots.
// Library code throws brdfbake::Error; this is the one place that turns errors into exit codes.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/memory_limit.h"
#include "brdfbake/version.h"
#include "cli/cli.h"

int main(int argc, char** argv) {
    using namespace brdfbake;
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

    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
    // No arguments: a short usage, not the whole help, and the status of bad input.
    if (argc < 2) {
        std::cerr << "brdfbake: error: no command given; usage: brdfbake COMMAND [OPTIONS] with COMMAND one of " << names
                  << " (brdfbake --help, brdfbake COMMAND --help)\n";
        return kExitError;
    }
    // A first word that is neither an option nor a command gets its own message.
    if (argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == argv[1];
        if (!known) {
            std::cerr << "brdfbake: error: unknown command '" << argv[1] << "'; commands: " << names << "\n";
            return kExitError;
        }
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return kExitOk;
    } catch (const CLI::CallForAllHelp&) {
        std::cout << app.help("", CLI::AppFormatMode::All);
        return kExitOk;
    } catch (const CLI::CallForVersion&) {
        std::cout << "brdfbake " << BRDFBAKE_VERSION << "\n";
        return kExitOk;
    } catch (const CLI::ParseError& e) {
        // One line: CLI11's message (some span lines) and where the usage is.
        std::string message = e.what();
        for (char& c : message)
            if (c == '\n') c = ' ';
        while (!message.empty() && message.back() == ' ') message.pop_back();
        std::string where = "brdfbake --help";
        for (const CLI::App* sub : app.get_subcommands())
            where = "brdfbake " + sub->get_name() + " --help";
        std::cerr << "brdfbake: error: " << message << " (see " << where << ")\n";
        return kExitError;
    }

    try {
        if (!max_memory.empty()) {
            try {
                set_memory_limit(parse_memory_size(max_memory));
            } catch (const Error& e) {
                throw Error(std::string("--max-memory (or BRDFBAKE_MAX_MEMORY): ") + e.what());
            }
        }
        if (!quiet) set_progress_sink(&stderr_progress());
        const int status = action ? action() : kExitError;
        // What a command printed is its result: a full disk or a closed pipe must not pass as
        // success (stdout is buffered, so a failed write shows at the flush).
        std::cout.flush();
        errno = 0;
        if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
            const int err = errno;
            std::cerr << "brdfbake: error: cannot write standard output"
                      << (err ? std::string(": ") + std::strerror(err) : std::string()) << "\n";
            return kExitError;
        }
        return status;
    } catch (const Error& e) {
        std::cerr << "brdfbake: error: " << e.what() << "\n";
        return e.exit_code();
    } catch (const cl::Error& e) {
        std::cerr << "brdfbake: error: OpenCL call " << e.what() << " failed: " << cl_error_name(e.err()) << "\n";
        return kExitError;
    } catch (const std::bad_alloc&) {
        std::cerr << "brdfbake: error: out of host memory (try a smaller table or fewer samples)\n";
        return kExitError;
    } catch (const std::exception& e) {
        std::cerr << "brdfbake: error: " << e.what() << "\n";
        return kExitError;
    }
}

// brdfbake: integrate BRDFs in OpenCL kernels and emit lookup tables and plots.
// Library code throws brdfbake::Error; this is the one place that turns errors into exit codes.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "brdfbake/engine.h"
#include "brdfbake/error.h"
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
    add_bench_command(app, global, action);

    // A first word that is neither an option nor a command gets its own message.
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        std::string names;
        for (const CLI::App* sub : app.get_subcommands({})) {
            known = known || sub->get_name() == argv[1];
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
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
        std::cerr << "brdfbake: error: " << e.what() << "\n";
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::RequiredError) && argc < 2)
            std::cerr << app.help();
        else
            std::cerr << "Run with --help for usage.\n";
        return kExitError;
    }

    try {
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

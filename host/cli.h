// The command line: each command registers itself on the CLI11 app and sets the action that
// main() runs after parsing.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace brdfbake {

/// Options that every command shares.
struct GlobalOptions {
    std::string device;  // device selector (see choose_device); empty: $BRDFBAKE_DEVICE or PoCL
    bool verbose = false;
};

/// What main() runs once the command line is parsed; returns the exit status.
using Action = std::function<int()>;

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

}  // namespace brdfbake

// The command line: each command registers itself on the CLI11 app and sets the action that
// main() runs after parsing.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <string>

#include "brdfbake/albedo.h"

namespace brdfbake {

/// Options that every command shares.
struct GlobalOptions {
    std::string device;  // device selector (see choose_device); empty: $BRDFBAKE_DEVICE or PoCL
    bool verbose = false;
};

/// --samples, --method, --tolerance and --max-samples, shared by the integrating commands.
void add_method_options(CLI::App* cmd, std::int64_t& samples, std::string& method, double& tolerance,
                        std::int64_t& max_samples, const std::string& per);

/// The method and tolerance the options ask for: "auto" with a sample count is the default
/// method (importance sampling); with a tolerance, auto lets the engine choose per cell.
struct MethodChoice {
    Method method = Method::Importance;
    ToleranceRequest tolerance;  // tolerance.tolerance == 0: a fixed sample count
};
MethodChoice resolve_method_choice(const std::string& method, double tolerance, std::int64_t max_samples);

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

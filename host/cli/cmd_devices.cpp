// `brdfbake devices`: the OpenCL devices the ICD loader sees, with the facts brdfbake uses.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/output.h"
#include "cli/cli.h"

namespace brdfbake {
namespace {

int run_devices(const std::string& format_text, const GlobalOptions& g) {
    const Format format = parse_format(format_text);
    const std::vector<DeviceInfo> all = list_devices();
    const DeviceInfo chosen = choose_device(g.device);
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& d : all)
            j.push_back({{"id", std::to_string(d.platform_index) + ":" + std::to_string(d.device_index)},
                         {"platform", d.platform},
                         {"name", d.name},
                         {"vendor", d.vendor},
                         {"version", d.version},
                         {"driver", d.driver},
                         {"type", d.type},
                         {"compute_units", d.compute_units},
                         {"max_clock_mhz", d.max_clock_mhz},
                         {"fp64", d.fp64},
                         {"global_mem_bytes", d.global_mem},
                         {"max_alloc_bytes", d.max_alloc},
                         {"max_work_group", d.max_work_group},
                         {"default", d.platform_index == chosen.platform_index &&
                                         d.device_index == chosen.device_index}});
        out << nlohmann::json{{"devices", j}}.dump(2) << "\n";
    } else {
        char line[512];
        for (const auto& d : all) {
            const bool is_default =
                d.platform_index == chosen.platform_index && d.device_index == chosen.device_index;
            std::snprintf(line, sizeof line,
                          "%s %d:%d  %s\n      platform: %s\n      type: %s, compute units: %u, clock: %u MHz, "
                          "fp64: %s\n      memory: %.1f GiB (largest allocation %.1f GiB), max work-group: %zu\n"
                          "      %s, driver %s\n",
                          is_default ? "*" : " ", d.platform_index, d.device_index, d.name.c_str(),
                          d.platform.c_str(), d.type.c_str(), d.compute_units, d.max_clock_mhz,
                          d.fp64 ? "yes" : "no", double(d.global_mem) / (1 << 30), double(d.max_alloc) / (1 << 30),
                          d.max_work_group, d.version.c_str(), d.driver.c_str());
            out << line;
        }
        out << "(* the device brdfbake uses; choose another with --device P:D or BRDFBAKE_DEVICE)\n";
    }
    emit("", out.str());
    return kExitOk;
}

}  // namespace

void add_devices_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, format] =
        add_command<std::string>(app, "devices", "list OpenCL platforms and devices with their facts", global, action,
                                 run_devices, std::string("table"));
    cmd->add_option("--format", *format, "output format: table or json")
        ->check(CLI::IsMember({"table", "json"}))
        ->capture_default_str();
}

}  // namespace brdfbake

// cmd_devices.cpp - `clrt devices`: every platform and device.
#include <cstdio>

#include "cli_common.hpp"
#include "device.hpp"

namespace clrt {

void add_devices_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("devices", "List OpenCL platforms and devices");
  cmd->callback([] {
    auto devs = list_devices();
    std::printf("%-5s %-28s %-52s %-6s %-18s %4s %5s\n", "index", "platform", "device", "type", "OpenCL C", "CUs", "fp64");
    for (const auto& d : devs)
      std::printf("%-5d %-28.28s %-52.52s %-6s %-18.18s %4u %5s\n", d.index, d.platform_name.c_str(), d.name.c_str(),
                  d.type.c_str(), d.c_version.c_str(), d.compute_units, d.fp64 ? "yes" : "no");
  });
}

}  // namespace clrt

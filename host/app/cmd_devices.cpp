// cmd_devices.cpp - `clrt devices [--check]`: every platform and device, and
// optionally a check that each renders correctly.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "app/compare_report.hpp"
#include "app/devices_report.hpp"
#include "app/options.hpp"
#include "app/report_header.hpp"
#include "cl/device.hpp"
#include "cl/launch_timing.hpp"
#include "eval/device_check.hpp"
#include "render/precision.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"

namespace clrt {

namespace {

// "15.6 GiB", "512 MiB".
std::string memory_text(cl_ulong bytes) {
  char buf[32];
  if (bytes >= (cl_ulong(1) << 30))
    std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(cl_ulong(1) << 30));
  else
    std::snprintf(buf, sizeof buf, "%.0f MiB", double(bytes) / double(cl_ulong(1) << 20));
  return buf;
}

}  // namespace

void add_devices_command(CLI::App& app) {
  auto check = std::make_shared<bool>(false);
  auto precision = std::make_shared<std::string>("robust");
  auto as_json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("devices", "List OpenCL platforms and devices");
  cmd->add_flag("--check", *check, "Self-test each device: build, render 160x120, compare with the reference");
  cmd->add_option("--precision", *precision, "Precision variant for --check")->capture_default_str();
  cmd->add_flag("--json", *as_json, "Print one JSON object: the report header and every device (and its check)");
  cmd->callback([check, precision, as_json] {
    if (*as_json) {
      int failed = 0;
      std::printf("%s\n", json_text(devices_json(*check, *precision, &failed)).c_str());
      if (failed) throw CheckFailure(std::to_string(failed) + " device(s) failed the self-test");
      return;
    }
    KernelConfig cfg;
    cfg.precision = parse_precision(*precision);
    auto devs = list_devices();
    const size_t chosen = default_device(devs);
    // The first column stays the global index (tests/every_device.sh reads it).
    std::printf("%-5s %-5s %-28s %-52s %-6s %-18s %4s %5s %9s  %s\n", "index", "P:D", "platform", "device", "type",
                "OpenCL C", "CUs", "fp64", "memory", "driver");
    int failed = 0;
    for (const auto& d : devs) {
      const std::string index = std::to_string(d.index) + (size_t(d.index) == chosen ? "*" : "");
      std::printf("%-5s %-5s %-28.28s %-52.52s %-6s %-18.18s %4u %5s %9s  %.24s\n", index.c_str(),
                  platform_device_id(d).c_str(), d.platform_name.c_str(), d.name.c_str(), d.type.c_str(),
                  d.c_version.c_str(), d.compute_units, d.fp64 ? "yes" : "no", memory_text(d.global_mem).c_str(),
                  d.driver.c_str());
      if (!*check) continue;
      DeviceCheckResult r = check_device(d, cfg);
      if (!r.error.empty())
        std::printf("      check: FAIL (%s)\n", r.error.c_str());
      else
        std::printf(
            "      check: %s  %zu px off by > 1 of %zu (%.4f%%), max abs %d, PSNR %s dB, NaN %zu; build %.0f ms, "
            "kernel %.2f ms%s\n",
            r.pass ? "PASS" : "FAIL", r.cmp.off_by_gt1, r.cmp.pixels, r.cmp.percent_off_by_gt1(), r.cmp.max_abs_8bit,
            format_psnr(r.cmp.psnr_8bit).c_str(), r.cmp.nan_inf, r.build_ms, r.kernel_ms,
            time_source_note(r.host_timed_launches, r.launches).c_str());
      failed += !r.pass;
    }
    std::printf(
        "* default device (the first GPU, else the first device); --device takes an index, P:D (platform P, its "
        "device D) or a name/type substring\n");
    if (failed) throw CheckFailure(std::to_string(failed) + " device(s) failed the self-test");
  });
}

}  // namespace clrt

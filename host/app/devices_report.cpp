// devices_report.cpp - every device, and its self-test, as JSON.
#include "app/devices_report.hpp"

#include "app/compare_report.hpp"
#include "app/report_header.hpp"
#include "cl/device.hpp"
#include "cl/launch_timing.hpp"
#include "eval/device_check.hpp"
#include "render/precision.hpp"
#include "util/error.hpp"

namespace clrt {

nlohmann::ordered_json devices_json(bool check, const std::string& precision, int* failed, const CancelFn& cancel) {
  KernelConfig cfg;
  cfg.precision = parse_precision(precision);
  const auto devs = list_devices();
  const size_t chosen = default_device(devs);
  std::vector<std::string> names;
  for (const auto& d : devs) names.push_back(d.name);
  nlohmann::ordered_json out = header_json(report_header(names));
  nlohmann::ordered_json arr = nlohmann::ordered_json::array();
  int failures = 0;
  for (const auto& d : devs) {
    nlohmann::ordered_json j = {{"index", d.index},
                                {"platform_device", platform_device_id(d)},
                                {"default", size_t(d.index) == chosen},
                                {"platform", d.platform_name},
                                {"name", d.name},
                                {"vendor", d.vendor},
                                {"type", d.type},
                                {"opencl_version", d.version},
                                {"opencl_c_version", d.c_version},
                                {"driver_version", d.driver},
                                {"compute_units", d.compute_units},
                                {"clock_mhz", d.clock_mhz},
                                {"fp64", d.fp64},
                                {"global_memory_bytes", d.global_mem},
                                {"max_alloc_bytes", d.max_alloc},
                                {"max_work_group_size", d.max_work_group}};
    if (check) {
      if (cancel && cancel()) throw Cancelled("devices check cancelled");
      DeviceCheckResult r = check_device(d, cfg);
      nlohmann::ordered_json c = {{"precision", precision}, {"pass", r.pass}};
      if (!r.error.empty()) {
        c["error"] = r.error;
      } else {
        c.update(nlohmann::ordered_json{{"build_ms", r.build_ms},
                                        {"kernel_ms", r.kernel_ms},
                                        {"kernel_time_source", time_source(r.host_timed_launches, r.launches)}});
        c.update(comparison_json(r.cmp));
      }
      j["check"] = c;
      failures += !r.pass;
    }
    arr.push_back(j);
  }
  out["devices"] = arr;
  if (failed) *failed = failures;
  return out;
}

}  // namespace clrt

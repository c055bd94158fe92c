// report_header.cpp - version, timestamp and driver of every report.
#include "app/report_header.hpp"

#include <ctime>

#include "cl/device.hpp"
#include "scene/scene_json.hpp"

#ifndef CLRT_VERSION
#define CLRT_VERSION "unknown"
#endif

namespace clrt {

std::string clrt_version() {
  return CLRT_VERSION;
}

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

ReportHeader report_header(const std::vector<std::string>& device_names) {
  ReportHeader h{clrt_version(), utc_timestamp(), ""};
  std::vector<DeviceInfo> all;
  try {
    all = list_devices();
  } catch (const std::exception&) {
    return h;  // no OpenCL platform: no driver to name
  }
  std::vector<std::string> drivers;
  for (const auto& d : all) {
    bool used = false;
    for (const auto& n : device_names) used |= !d.name.empty() && n.find(d.name) != std::string::npos;
    if (!used) continue;
    bool seen = false;
    for (const auto& s : drivers) seen |= s == d.driver;
    if (!seen) drivers.push_back(d.driver);
  }
  for (size_t k = 0; k < drivers.size(); ++k) h.device_driver += (k ? "; " : "") + drivers[k];
  return h;
}

ReportHeader report_header(const std::string& device_names) {
  return report_header(std::vector<std::string>{device_names});
}

nlohmann::ordered_json header_json(const ReportHeader& h) {
  return {
      {"clrt_version", h.clrt_version},
      {"timestamp_utc", h.timestamp_utc},
      {"device_driver", h.device_driver.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(h.device_driver)}};
}

nlohmann::ordered_json overrides_json(const std::vector<std::string>& overrides) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const SceneOverride& o : parse_overrides(overrides)) out[o.path] = nlohmann::ordered_json::parse(o.value);
  return out;
}

void header_csv(CsvTable& t, const ReportHeader& h) {
  t.set("clrt_version", h.clrt_version);
  t.set("timestamp_utc", h.timestamp_utc);
  t.set("device_driver", h.device_driver);
}

}  // namespace clrt

// report_header.hpp - the fields that open every machine-readable report
// (every --json object and every CSV row, docs/guide/output.md):
// which clrt wrote it, when, and with which OpenCL driver.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "util/csv.hpp"

namespace clrt {

struct ReportHeader {
  std::string clrt_version;   // project(VERSION), as `clrt --version` prints it
  std::string timestamp_utc;  // ISO 8601, UTC, whole seconds: "2026-11-28T05:46:02Z"
  std::string
      device_driver;  // the driver version(s) of the devices used, "; "-joined; empty: none (null / empty field)
};

// The version of this build.
std::string clrt_version();
// Now, as ISO 8601 UTC.
std::string utc_timestamp();
// The header for a report of the devices named (their names as DeviceInfo
// holds them, or several within one string, e.g. "A + B"); the drivers are
// looked up among list_devices(); no OpenCL device named: no driver.
ReportHeader report_header(const std::vector<std::string>& device_names);
ReportHeader report_header(const std::string& device_names);

// The header's keys, in this order: clrt_version, timestamp_utc, device_driver.
nlohmann::ordered_json header_json(const ReportHeader& h);
// The same three as the leading columns of a CSV row.
void header_csv(CsvTable& t, const ReportHeader& h);

// The -D overrides of a command (ImageOptions::overrides) as one JSON
// object, path: value, in the order given: "overrides" of the reports that
// read scene files, and the images' clrt:overrides.
nlohmann::ordered_json overrides_json(const std::vector<std::string>& overrides);

}  // namespace clrt

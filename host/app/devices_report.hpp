// devices_report.hpp - `clrt devices --json`'s object, built in one place
// for the command and the Python module's clrt.devices().
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "render/build_options.hpp"
#include "util/progress.hpp"

namespace clrt {

// The report header and "devices": every OpenCL device (index,
// platform_device, default, platform, name, ...) and, with `check`, its
// self-test with `precision` under "check" (eval/device_check.hpp).
// *failed (optional): how many devices failed it. `cancel` (optional):
// asked before each device's check; true: Cancelled (util/error.hpp).
nlohmann::ordered_json devices_json(bool check, const std::string& precision, int* failed = nullptr,
                                    const CancelFn& cancel = {});

}  // namespace clrt

// device_check.hpp - does a device render correctly? Builds the kernel,
// renders a small image of the built-in demo scene and compares it with the
// reference (`clrt devices --check`).
#pragma once
#include <string>

#include "cl/device.hpp"
#include "eval/compare.hpp"
#include "render/build_options.hpp"

namespace clrt {

struct DeviceCheckResult {
  bool pass = false;
  std::string error;  // build/run failure, empty when it ran
  Comparison cmp;
  double build_ms = 0, kernel_ms = 0;
  int launches = 0, host_timed_launches = 0;  // launch_timing.hpp
};

// Pass: it ran and the image is within_tolerance (compare.hpp; the demo is
// normally at ~0.001% of pixels off by more than one level). Never throws: a
// failure to build or run is a failed check with its reason.
DeviceCheckResult check_device(const DeviceInfo& dev, const KernelConfig& cfg, int width = 160, int height = 120);

}  // namespace clrt

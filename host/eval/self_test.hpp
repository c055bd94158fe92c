// self_test.hpp - per-device self-test: build the kernel, render a small image
// of the built-in demo scene, compare it with the reference.
#pragma once
#include <string>

#include "render/build_options.hpp"
#include "eval/compare.hpp"
#include "cl/device.hpp"

namespace clrt {

struct SelfTestResult {
  bool pass = false;
  std::string error;  // build/run failure, empty when it ran
  Comparison cmp;
  double build_ms = 0, kernel_ms = 0;
  int launches = 0, host_timed_launches = 0;  // launch_timing.hpp
};

// Pass: ran, no NaN/Inf pixel, at most 0.05% of pixels off by more than one
// level (the stability-suite threshold; the demo is normally at ~0.001%).
SelfTestResult self_test(const DeviceInfo& dev, const KernelConfig& cfg, int width = 160, int height = 120);

}  // namespace clrt

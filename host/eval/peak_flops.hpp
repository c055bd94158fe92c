// peak_flops.hpp - the single-precision multiply-add rate a device actually
// reaches, measured with a small kernel (kernels/peak_flops.cl), so `clrt
// bench` can say what share of it the renderer uses. Nothing is assumed from
// the device's advertised clock or vector width.
#pragma once
#include <string>

#include "cl/device.hpp"
#include "util/stats.hpp"

namespace clrt {

struct PeakFlops {
  bool measured = false;
  double gflops = 0;        // best of the timed launches
  Stats launch_ms;          // the timed launches
  bool from_events = true;  // false: the launches were timed by the host clock (launch_timing.hpp)
  std::string note;         // why it is unknown, when !measured
};

// Calibrates the iteration count to about 20 ms per launch, then times
// `repeat` launches and keeps the fastest. Never throws: a device where the
// kernel cannot be built or run gives measured = false and a note.
PeakFlops measure_peak_flops(const DeviceInfo& dev, int repeat = 3);

}  // namespace clrt

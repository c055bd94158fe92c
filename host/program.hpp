// program.hpp - building OpenCL programs (build log on failure).
#pragma once
#include <string>

#include "cl.hpp"
#include "device.hpp"

namespace clrt {

struct BuildStats {
  double ms = 0;       // wall time of getting a built program
  bool cached = false;  // came from the on-disk binary cache
};

// Builds `source` with `options` for one device. On failure the build log is
// written to stderr and a DeviceError names the device and the error.
cl::Program build_program(const cl::Context& ctx, const DeviceInfo& dev, const std::string& source,
                          const std::string& options, BuildStats* stats = nullptr);

}  // namespace clrt

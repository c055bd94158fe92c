// program.hpp - building OpenCL programs (build log on failure, binary cache).
#pragma once
#include <string>

#include "cl/cl.hpp"
#include "cl/device.hpp"

namespace clrt {

struct BuildStats {
  double ms = 0;        // wall time of getting a built program
  bool cached = false;  // came from the on-disk binary cache
};

struct BuildFlags {
  bool use_cache = true;  // look up / store the binary in the program cache
  bool verbose = false;   // log options and cache hit/miss on stderr
};

// Builds `source` with `options` for one device, through the on-disk program
// cache (host/program_cache.hpp) unless flags.use_cache is false: a valid
// entry is loaded as a binary, anything else (missing, corrupted, rejected by
// the driver) falls back to a build from source, which is then stored. On
// failure the build log is written to stderr and a DeviceError names the
// device and the error.
cl::Program build_program(const cl::Context& ctx, const DeviceInfo& dev, const std::string& source,
                          const std::string& options, BuildStats* stats = nullptr, BuildFlags flags = {});

}  // namespace clrt

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

// Whether the device's driver keeps the programs it builds across processes
// itself, so that clrt's copy of a binary would only duplicate it: PoCL with
// its kernel cache on (its default; POCL_KERNEL_CACHE=0 turns it off). There
// the copy costs more than it saves: asking PoCL for a program's binary makes
// it compile every kernel again, for a dynamic work-group size clrt never
// launches (measured: 3.6 s of CPU instead of 2.1 s for the demo's first
// build, to save 0.1 s on each later run; docs/reference/kernel.md, "Program
// cache"). PyOpenCL leaves its own cache out on PoCL for the same reason.
bool driver_caches_programs(const DeviceInfo& dev);

// Builds `source` with `options` for one device, through the on-disk program
// cache (host/program_cache.hpp) unless flags.use_cache is false: a valid
// entry is loaded as a binary, anything else (missing, corrupted, rejected by
// the driver) falls back to a build from source, which is then stored, unless
// driver_caches_programs(dev). On failure the build log is written to stderr
// and a DeviceError names the device and the error.
cl::Program build_program(const cl::Context& ctx, const DeviceInfo& dev, const std::string& source,
                          const std::string& options, BuildStats* stats = nullptr, BuildFlags flags = {});

}  // namespace clrt

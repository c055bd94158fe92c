// program.cpp - program build with the build log surfaced on failure.
#include "program.hpp"

#include <chrono>
#include <iostream>

#include "error.hpp"

namespace clrt {

cl::Program build_program(const cl::Context& ctx, const DeviceInfo& dev, const std::string& source,
                          const std::string& options, BuildStats* stats) {
  auto t0 = std::chrono::steady_clock::now();
  cl::Program program(ctx, source);
  try {
    program.build({dev.device}, options.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(dev.device);
    } catch (const cl::Error&) {
    }
    std::cerr << "---- kernel build log (" << dev.name << ", options: " << options << ") ----\n"
              << log << "\n---- end of build log ----\n";
    throw DeviceError("kernel build failed on " + dev.name + ": " + cl_error_name(e.err()) + " (build log above)");
  }
  if (stats) {
    stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    stats->cached = false;
  }
  return program;
}

}  // namespace clrt

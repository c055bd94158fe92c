// error.hpp - error types that map to exit codes in the CLI.
#pragma once
#include <stdexcept>
#include <string>

namespace clrt {

// Bad input from the user (scene file, options, output path): exit status 2.
struct UserError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The OpenCL runtime or device failed (no platform, build failure, ...):
// also exit status 2, but kept distinct so callers can tell them apart.
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace clrt

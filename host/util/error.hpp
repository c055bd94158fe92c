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

// A check ran to the end and its result is outside what was asked for
// (`compare --fail-*`, `stability --check`, `devices --check`): exit status 1.
struct CheckFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A caller asked for the work to stop (RenderSettings::cancel: the Python
// module's Ctrl-C); what was in flight finished first. The CLI never asks.
struct Cancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad input whose problems the command has printed already, one line each
// (`clrt validate`): exit status 2, and no line more.
struct ProblemsReported : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Exit statuses, in one place (docs/guide/errors.md).
constexpr int kExitOk = 0, kExitCheckFailed = 1, kExitBadInput = 2, kExitInternalError = 3;

}  // namespace clrt

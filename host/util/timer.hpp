// timer.hpp - wall-clock milliseconds, the one conversion every timing uses.
#pragma once
#include <chrono>

namespace clrt {

using Clock = std::chrono::steady_clock;

// Milliseconds elapsed since `t0`.
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace clrt

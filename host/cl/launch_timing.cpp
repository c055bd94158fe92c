// launch_timing.cpp - the plausibility rule for profiling-event times.
#include "cl/launch_timing.hpp"

#include <cmath>

#include "util/timer.hpp"

namespace clrt {

bool event_time_plausible(double event_ms, double wall_ms) {
  if (!std::isfinite(event_ms) || event_ms <= 0) return false;
  if (event_ms > wall_ms * kEventMaxOverWall + kEventSlackMs) return false;
  if (wall_ms >= kEventMinCheckedWallMs && event_ms < kEventMinFractionOfWall * wall_ms) return false;
  return true;
}

LaunchTime launch_time(double event_ms, double wall_ms) {
  LaunchTime t;
  t.event_ms = event_ms;
  t.wall_ms = wall_ms;
  t.from_events = event_time_plausible(event_ms, wall_ms);
  t.ms = t.from_events ? event_ms : wall_ms;
  return t;
}

TimedLaunch start_timed(const cl::CommandQueue& queue, const cl::Kernel& kernel, const cl::NDRange& global,
                        const cl::NDRange& local) {
  TimedLaunch launch;
  launch.launched = Clock::now();
  queue.enqueueNDRangeKernel(kernel, cl::NullRange, global, local, nullptr, &launch.event);
  return launch;
}

TimedLaunch start_timed_after(const TimedLaunch& earlier, const cl::CommandQueue& queue, const cl::Kernel& kernel,
                              const cl::NDRange& global, const cl::NDRange& local) {
  TimedLaunch launch;
  launch.launched = earlier.launched;
  launch.first = earlier.first() ? earlier.first : earlier.event;
  queue.enqueueNDRangeKernel(kernel, cl::NullRange, global, local, nullptr, &launch.event);
  return launch;
}

LaunchTime finish_timed(const TimedLaunch& launch) {
  launch.event.wait();
  const double wall_ms = ms_since(launch.launched);
  // As doubles: a driver that reports END before START gives a negative
  // (implausible) time instead of a wrapped-around huge one.
  const cl::Event& first = launch.first() ? launch.first : launch.event;
  const double start = double(first.getProfilingInfo<CL_PROFILING_COMMAND_START>());
  const double end = double(launch.event.getProfilingInfo<CL_PROFILING_COMMAND_END>());
  return launch_time((end - start) * 1e-6, wall_ms);
}

LaunchTime run_timed(const cl::CommandQueue& queue, const cl::Kernel& kernel, const cl::NDRange& global,
                     const cl::NDRange& local) {
  return finish_timed(start_timed(queue, kernel, global, local));
}

std::string time_source(int host_timed, int launches) {
  if (host_timed <= 0) return "events";
  return host_timed >= launches ? "host" : "mixed";
}

std::string time_source_note(int host_timed, int launches) {
  if (host_timed <= 0) return "";
  if (host_timed >= launches) return " (host wall clock: the device's profiling events were implausible)";
  return " (" + std::to_string(host_timed) + " of " + std::to_string(launches) +
         " launches timed by the host wall clock: implausible profiling events)";
}

}  // namespace clrt

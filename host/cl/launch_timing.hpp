// launch_timing.hpp - how long a kernel launch took, and whether the OpenCL
// profiling events can be believed. Some drivers return nonsense from
// CL_PROFILING_COMMAND_START/END (Mesa rusticl on llvmpipe reports ~1 ns for
// launches that take tens of milliseconds), so every event time is checked
// against the host's wall time of the same launch (enqueue to completion);
// an implausible one is replaced by the wall time and the replacement is
// reported. This file is the one place for that rule.
#pragma once
#include <string>

#include "cl/cl.hpp"
#include "util/timer.hpp"

namespace clrt {

// An event time is plausible when it is positive, no longer than the host
// waited for the launch (plus 10% and 0.05 ms for clock granularity and the
// two clocks' offsets), and - for launches the host waited at least 1 ms for -
// at least 1% of that wait: launch overhead on every driver measured here is
// well under 1 ms, so it cannot explain a 100x gap.
constexpr double kEventMaxOverWall = 1.10, kEventSlackMs = 0.05;
constexpr double kEventMinFractionOfWall = 0.01, kEventMinCheckedWallMs = 1.0;

bool event_time_plausible(double event_ms, double wall_ms);

struct LaunchTime {
  double ms = 0;            // the time used: the event time when plausible, else wall_ms
  double event_ms = 0;      // what the profiling events said
  double wall_ms = 0;       // host wall time, enqueue to completion
  bool from_events = true;  // false: the events were implausible, ms is wall_ms
};

LaunchTime launch_time(double event_ms, double wall_ms);

// Enqueues `kernel` on `queue` (created with CL_QUEUE_PROFILING_ENABLE),
// waits for it, and times it both ways: every launch clrt times goes through
// here.
LaunchTime run_timed(const cl::CommandQueue& queue, const cl::Kernel& kernel, const cl::NDRange& global,
                     const cl::NDRange& local);

// The same in two steps, so that the host can work (download another tile)
// while the launch runs: start_timed() enqueues without waiting,
// finish_timed() waits and times. The wall time then runs from the enqueue
// to the end of the wait, longer than the launch when the host was busy
// elsewhere or the launch queued behind another, so a pipelined caller
// should rely on it only where the events were plausible before.
struct TimedLaunch {
  cl::Event event;
  Clock::time_point launched;
  // A sequence of launches (start_timed_after()): the first one's event,
  // whose start is the sequence's; null for a single launch.
  cl::Event first;
};
TimedLaunch start_timed(const cl::CommandQueue& queue, const cl::Kernel& kernel, const cl::NDRange& global,
                        const cl::NDRange& local);
LaunchTime finish_timed(const TimedLaunch& launch);
// Enqueues `kernel` after `earlier` on the same in-order queue and returns
// the two as one timed launch: from earlier's enqueue (host) and start
// (events) to this one's end.
TimedLaunch start_timed_after(const TimedLaunch& earlier, const cl::CommandQueue& queue, const cl::Kernel& kernel,
                              const cl::NDRange& global, const cl::NDRange& local);

// Where a total over `launches` launches came from, `host_timed` of which
// used the host clock: "events", "host" or "mixed" (JSON/CSV value).
std::string time_source(int host_timed, int launches);
// The same for people: empty for events, otherwise a parenthesised note.
std::string time_source_note(int host_timed, int launches);

}  // namespace clrt

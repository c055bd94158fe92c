// pocl_workers.hpp - PoCL's worker threads, one pinned to each core unless
// the user chose otherwise.
//
// Why: PoCL's CPU device runs a kernel on one worker thread per core, woken
// together when the kernel is queued. On a 2-core virtual machine Linux
// often woke both onto the core that woke them and left them there for the
// whole launch: a 4.3 ms frame of the demo took 8.7 ms (one core's worth)
// in about half the rounds (docs/results/wide-hierarchy.md, "Short frames
// on one core"; the lanes probe, which times short bands, is exposed to the
// same). PoCL's own switch, POCL_AFFINITY=1, pins worker i to CPU i;
// clrt sets it before the first OpenCL call where that is safe.
#pragma once
#include <vector>

namespace clrt {

// Whether to set POCL_AFFINITY=1: only where the user set neither it nor
// POCL_MAX_PTHREAD_COUNT (a rank given one thread would pin it to CPU 0,
// beside every other rank's), the process may run on every online CPU and
// those are CPUs 0..online-1 (PoCL pins worker i to CPU i; a CPU outside
// the process's mask would fail), and there are at least two of them.
// `affinity` and `max_threads` are the variables' values (nullptr: unset),
// `allowed` the CPUs of the process's affinity mask, ascending.
bool should_pin_pocl_workers(const char* affinity, const char* max_threads, const std::vector<int>& allowed,
                             long online);

// The CPUs this process may run on (its affinity mask), ascending; empty
// where the system does not say (or not Linux).
std::vector<int> process_cpus();

// Sets POCL_AFFINITY=1 where should_pin_pocl_workers() says so, once, before
// the process's first OpenCL call (list_devices() calls it); Linux only.
void pin_pocl_workers_by_default();

}  // namespace clrt

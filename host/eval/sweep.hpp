// sweep.hpp - `clrt sweep`: the bench figures per recursion depth and per
// device, with the error against the reference at each depth and the change
// from depth d-1 to d.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "eval/bench.hpp"
#include "eval/compare.hpp"

namespace clrt {

struct SweepRow {
  std::string device;
  int device_index = 0;   // DeviceInfo::index: tells devices with equal names apart
  std::string device_pd;  // "P:D", platform and device position (as --device takes it)
  int depth = 0;
  BenchResult bench;                // without the reference (timed once per depth, below); images dropped after use
  Comparison error;                 // OpenCL vs reference at this depth
  Comparison change;                // OpenCL image at d vs d-1 (same device); d = first: all zero
  double kernel_ms_delta = 0;       // median kernel ms at d minus at d-1
  double reference_ms = 0;          // the reference at this depth (one run, shared by the devices)
  double speedup_vs_reference = 0;  // reference_ms / median clrt frame
};

// Called before each row with the rows done so far, and once with done ==
// total at the end; `what` names the row about to run ("done" at the end).
using SweepProgress = std::function<void(int done, int total, const std::string& what)>;

struct SweepSettings {
  BenchSettings bench;  // depth is set per row
  int depth_from = 0, depth_to = 10;
  SweepProgress progress;  // empty: none
};

std::vector<SweepRow> run_sweep(const Scene& scene, const std::vector<DeviceInfo>& devices,
                                const RenderSettings& settings, const SweepSettings& s);

// The pieces of run_sweep, which a sweep spread over the ranks of an MPI job
// (dist/eval_grids.hpp) runs on different ranks: the reference at a depth,
// one (depth, device) row, and the comparisons that join them.
struct SweepReference {
  Image image;
  double ms = 0;  // its render time
};
SweepReference sweep_reference(const Scene& scene, const SweepSettings& s, int depth);
// The bench of one row, with its OpenCL image kept in bench.image (for
// sweep_compare); error, change and the reference's figures left empty.
SweepRow sweep_row(const Scene& scene, const DeviceInfo& device, const RenderSettings& settings, const SweepSettings& s,
                   int depth);
// Fills a row's error and reference figures from the reference at its
// depth, and its change and kernel_ms_delta from the image and median kernel
// time of the same device at the depth before (previous = null at the first
// depth: both stay zero).
void sweep_compare(SweepRow& row, const SweepReference& ref, const Image* previous, double previous_kernel_ms);

}  // namespace clrt

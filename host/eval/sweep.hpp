// sweep.hpp - `clrt sweep`: the bench figures per recursion depth and per
// device, with the error against the reference at each depth and the change
// from depth d-1 to d.
#pragma once
#include <string>
#include <vector>

#include "eval/bench.hpp"
#include "eval/compare.hpp"

namespace clrt {

struct SweepRow {
  std::string device;
  int depth = 0;
  BenchResult bench;           // images dropped after use
  Comparison error;            // OpenCL vs reference at this depth
  Comparison change;           // OpenCL image at d vs d-1 (same device); d = first: all zero
  double kernel_ms_delta = 0;  // median kernel ms at d minus at d-1
  double reference_ms = 0;
};

struct SweepSettings {
  BenchSettings bench;  // depth is set per row
  int depth_from = 0, depth_to = 10;
  bool progress = false;  // progress bar on stderr
};

// Parses "A:B" (inclusive, 0 <= A <= B <= CLRT_MAX_DEPTH) or a single "N".
void parse_depth_range(const std::string& s, int& from, int& to);

std::vector<SweepRow> run_sweep(const Scene& scene, const std::vector<DeviceInfo>& devices, const KernelConfig& cfg,
                                const SweepSettings& s);

std::string sweep_csv(const std::vector<SweepRow>& rows);
void print_sweep(const std::vector<SweepRow>& rows);
// Time per depth to `path`; rays per depth to the same name with "-rays"
// before the extension. Returns the second path.
std::string rays_plot_path(const std::string& path);  // "a/t.png" -> "a/t-rays.png"
std::string plot_sweep(const std::vector<SweepRow>& rows, const std::string& path, const std::string& title);

}  // namespace clrt

// bench.hpp - `clrt bench`: build (cold/warm), upload, kernel (median/min/max
// of N timed launches after a warm-up), download and end-to-end times of the
// OpenCL renderer on one or more devices (several share each frame, see
// multi_renderer.hpp), rays by kind (counted by the kernel), and in
// the same run the scalar double reference and the OpenMP float tracer
// (bench/omp_tracer.hpp) for speedups.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "build_options.hpp"
#include "cl_renderer.hpp"
#include "multi_renderer.hpp"
#include "device.hpp"
#include "image.hpp"
#include "scene.hpp"
#include "tile_scheduler.hpp"

namespace clrt {

struct BenchSettings {
  int width = 600, height = 600, depth = 3;
  int repeat = 5;  // timed launches after one warm-up launch
  int local_x = 0, local_y = 0;
  bool reference = true;  // time the scalar double reference (and keep its image)
  bool omp = true;        // time the OpenMP float tracer
  bool builds = true;     // measure cold (no cache) and warm (cache hit) builds
  TilePolicy policy;      // bands per launch (tile_scheduler.hpp)
};

// Nominal FLOP counts (the book's float formulas, see docs/performance.md):
// a ray-sphere test is O-C (3), D.D (5), 2 CO.D (6), CO.CO - r^2 (7),
// b^2 - 4ac (4) = 25; roots, shading and the robust variant's compensated
// arithmetic are not counted, so GFLOP/s is a lower bound.
constexpr double kFlopPerSphereTest = 25;

// Peak single-precision GFLOP/s assumed for a CPU device: compute units x
// clock x 16 lanes (AVX-512) x 2 (FMA) x 2 FMA units per core.
double cpu_peak_gflops(const DeviceInfo& dev);

struct BenchResult {
  std::string device, options;
  int width = 0, height = 0, depth = 0, repeat = 0;
  double build_cold_ms = 0, build_warm_ms = 0;
  bool build_warm_cached = false;
  double upload_ms = 0, first_launch_ms = 0;
  std::vector<double> kernel_ms;  // each timed frame: kernel time summed over launches (and devices)
  double frame_ms_median = 0;     // wall time of render() (all devices together)
  std::vector<DeviceShare> shares;  // per device, median-ish (last timed) frame
  double kernel_ms_median = 0, kernel_ms_min = 0, kernel_ms_max = 0;
  double download_ms = 0;    // median run
  double end_to_end_ms = 0;  // new renderer: (warm) build + upload + render
  RayCounts rays;
  double mrays_per_s = 0, ns_per_sphere_test = 0, gflops = 0, peak_gflops = 0;
  double reference_ms = 0, speedup_vs_reference = 0;    // reference / kernel median
  double omp_ms_median = 0, opencl_speedup_vs_omp = 0;  // omp / kernel median
  int omp_threads = 0;
  Image image;      // the OpenCL image (last timed run)
  Image reference;  // the reference image (if settings.reference)
};

BenchResult run_bench(const Scene& scene, const std::vector<DeviceInfo>& devs, const KernelConfig& cfg,
                      const BenchSettings& s);

nlohmann::json bench_json(const BenchResult& r);
nlohmann::json shares_json(const std::vector<DeviceShare>& shares);
void print_bench(const BenchResult& r);

double median(std::vector<double> v);

}  // namespace clrt

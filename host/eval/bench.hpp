// bench.hpp - `clrt bench`: build (cold/warm), upload, kernel, download and
// frame times of the OpenCL renderer on one or more devices (several share
// each frame, see render/renderer.hpp), rays by kind (counted by the kernel),
// the device's measured multiply-add peak, and in the same run the scalar
// double reference, the OpenMP float tracer (bench/omp_tracer.hpp) and the
// same tracer on an Embree BVH (bench/embree_tracer.hpp).
//
// Like for like: the headline comparison is clrt's warm frame (every launch
// plus the download into host memory) against the OpenMP tracer's frame,
// timed in alternating rounds (clrt, OpenMP, Embree) so background load falls
// on all alike; kernel-only ratios are secondary. The Embree frame is its
// render only: its BVH build (once per frame there) is reported apart, as
// clrt's hierarchy build is part of end to end, not of its frame. Every timed figure is a Stats (N, median, mean ± sd,
// min, max). Kernel times are profiling events checked against the host
// clock (launch_timing.hpp); the result says which clock they came from.
#pragma once
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "eval/peak_flops.hpp"
#include "image/image.hpp"
#include "render/renderer.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"
#include "util/progress.hpp"
#include "util/stats.hpp"

namespace clrt {

struct BenchSettings {
  int width = 600, height = 600, depth = 3;
  int spp = 1;           // N x N samples per pixel (clrt and the reference; the tracers trace one, see omp/embree)
  double adaptive = -1;  // adaptive supersampling's threshold (scene/sampling.hpp); negative: off
  Subsample subsample = Subsample::Off;  // the book's subsampling (scene/sampling.hpp), clrt and the reference
  int repeat = 5;         // >= 1 (--repeat checks it): timed rounds (clrt, OpenMP, Embree frame) after one warm-up each
  bool reference = true;  // time the scalar double reference (and keep its image)
  bool omp = true;        // time the OpenMP float tracer (one ray per pixel: not run when spp > 1)
  bool embree = true;     // time the Embree tracer (and check its image against the OpenMP tracer's; not when spp > 1)
  bool builds = true;     // measure cold (no cache) and warm (cache hit) builds
  bool peak = true;       // measure the device's multiply-add peak
  // Each build, the first frame, each timed round, the ray count, the peak
  // and the reference; once with done == total at the end. Empty: none.
  ProgressFn progress{};

  Sampling sampling() const { return Sampling(spp, adaptive, subsample); }
};

// Builds timed per kind: at most this many (a cold build costs up to seconds).
constexpr int kMaxBuildRepeat = 3;

// Nominal FLOP counts (the book's float formulas, see docs/developer/benchmarking.md):
// a ray-sphere test is O-C (3), D.D (5), 2 CO.D (6), CO.CO - r^2 (7),
// b^2 - 4ac (4) = 25; roots, shading and the robust variant's compensated
// arithmetic are not counted, so GFLOP/s is a lower bound.
constexpr double kFlopPerSphereTest = 25;

// The share of pixels by which the Embree tracer's image may differ from
// clrt's (> 1 level) before bench calls the comparison suspect. Measured
// (docs/results/meshes.md): none on scenes/large/mesh.json, 0.03% on a grid
// of 4 million triangles, where float rounding or Embree's triangle test
// (not clrt's watertight one) tips a ray on an edge or silhouette to
// another surface; 1% leaves room for that and still catches a different
// picture (one reflection level less differs in > 1% on the demo).
constexpr double kEmbreeVsClrtTolerance = 0.01;

struct BenchResult {
  std::string device, options;
  int width = 0, height = 0, depth = 0, spp = 1, repeat = 0;
  Subsample subsample = Subsample::Off;
  bool rgba8 = false;            // frames (clrt's and the tracers') held as 8-bit RGBA, else float RGB
  std::string tracers_not_run;   // why the OpenMP/Embree tracers were not run ("" when they were)
  std::string omp_not_run;       // why the OpenMP tracer alone was not run (scenes with triangles)
  Stats build_cold, build_warm;  // ms per build of every device (the longest, they run in parallel)
  bool build_warm_cached = false;         // every warm build loaded clrt's cached binary
  bool build_warm_driver_cached = false;  // the drivers keep the programs instead (cl/program.hpp: PoCL)
  Stats upload;                // ms, scene buffers (one per build above)
  double end_to_end_ms = 0;    // N=1: new renderer, (warm) build + upload + first frame
  double first_launch_ms = 0;  // N=1: kernel time of that first frame
  bool bvh = false;            // the kernel walks a hierarchy (render/bvh.hpp)
  double bvh_build_ms = 0;     // N=1: its build on the host, part of end_to_end_ms
  size_t bvh_bytes = 0;
  int bvh_depth = 0;
  std::vector<double> kernel_ms;              // each timed frame: kernel time summed over launches (and devices)
  Stats kernel;                               // of kernel_ms
  int launches = 0, host_timed_launches = 0;  // over the timed frames (launch_timing.hpp)
  Stats frame;                                // wall ms of a warm frame: every launch + download into host memory
  Stats download;                             // ms per frame
  std::vector<DeviceShare> shares;            // per device, last timed frame
  RayCounts rays;
  double mrays_per_s = 0, ns_per_sphere_test = 0, gflops = 0;  // from the median kernel time
  std::vector<PeakFlops> peaks;                                // per device
  double peak_gflops = 0;                                      // sum of the measured peaks; 0 when any is unknown
  Stats reference;                                             // ms, scalar double reference (N=1)
  double speedup_vs_reference = 0;                             // reference / frame (medians)
  Stats omp;                                                   // ms per OpenMP frame
  int omp_threads = 0;
  Stats speedup_vs_omp;         // per round: OpenMP frame / clrt frame (the headline)
  Stats kernel_speedup_vs_omp;  // per round: OpenMP frame / clrt kernel time (secondary)
  Stats embree;                 // ms per Embree frame: the render only, without its BVH build
  Stats embree_build;           // ms per Embree BVH build (geometry + rtcCommitScene), one per frame
  double embree_build_ms = 0;   // embree_build.median
  int embree_threads = 0;
  Stats speedup_vs_embree;  // per round: Embree frame / clrt frame
  // The Embree image against the OpenMP tracer's (both in the frame's
  // format, float or 8-bit; the same algorithm; last timed round): the fraction of pixels where a channel
  // differs by more than one level of 255 after clamping and rounding, and
  // the largest such difference. -1: not checked (no OpenMP or no Embree run).
  double embree_vs_omp_differ = -1;
  int embree_vs_omp_max_levels = -1;
  // The Embree image against clrt's (the same measure; last timed round):
  // the check where the OpenMP tracer does not run (meshes). Not equal by
  // construction: clrt's kernel and the float tracer round differently, and
  // Embree's triangle test is not clrt's watertight one. -1: not checked.
  // Flagged beyond kEmbreeVsClrtTolerance.
  double embree_vs_clrt_differ = -1;
  int embree_vs_clrt_max_levels = -1;
  Image image;            // the OpenCL image (last timed run)
  Image reference_image;  // the reference image (if settings.reference)

  // "events", "host" or "mixed" (launch_timing.hpp)
  std::string kernel_time_source() const;
};

// Two float RGB images of the same size (width*height*3, 0..255 unclamped),
// both clamped and rounded like every output (image.hpp's to_u8): the
// fraction of pixels where some channel differs by more than `levels`, and
// the largest difference in levels.
struct PixelAgreement {
  double differ = 0;
  int max_levels = 0;
};
PixelAgreement compare_rgb(const std::vector<float>& a, const std::vector<float>& b, int levels = 1);
// The same for two 8-bit RGBA images (width*height*4; alpha ignored).
PixelAgreement compare_rgba8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int levels = 1);

BenchResult run_bench(const Scene& scene, const std::vector<DeviceInfo>& devs, const RenderSettings& settings,
                      const BenchSettings& s);

}  // namespace clrt

// bench.cpp - one device, one scene: every time of the pipeline, rays, and
// the reference / OpenMP comparisons measured in the same run.
#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "omp_tracer.hpp"
#include "reference.hpp"
#include "timer.hpp"

namespace clrt {
namespace {

MultiRenderer make_renderer(const std::vector<DeviceInfo>& devs, const KernelConfig& cfg, const BenchSettings& s) {
  MultiRenderer r(devs, cfg);
  r.set_local_size(s.local_x, s.local_y);
  r.set_tile_policy(s.policy);
  return r;
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double cpu_peak_gflops(const DeviceInfo& dev) {
  return double(dev.compute_units) * dev.clock_mhz * 1e-3 * 16 * 2 * 2;
}

BenchResult run_bench(const Scene& scene, const std::vector<DeviceInfo>& devs, const KernelConfig& cfg,
                      const BenchSettings& s) {
  BenchResult r;
  for (size_t i = 0; i < devs.size(); ++i) r.device += (i ? " + " : "") + devs[i].name;
  r.width = s.width;
  r.height = s.height;
  r.depth = s.depth;
  r.repeat = s.repeat;

  if (s.builds) {
    // Cold: from source, program cache bypassed (PoCL's own cache is only
    // off if POCL_KERNEL_CACHE=0 is set; see docs/performance.md).
    KernelConfig cold = cfg;
    cold.use_cache = false;
    MultiRenderer c = make_renderer(devs, cold, s);
    c.prepare(scene, s.width, s.height, s.depth);
    r.build_cold_ms = c.build_ms();
    // Make sure the entry exists, then time a load from the cache.
    if (cfg.use_cache) {
      MultiRenderer store = make_renderer(devs, cfg, s);
      store.prepare(scene, s.width, s.height, s.depth);
    }
  }

  // End to end on a fresh renderer: (warm) build + upload + first render.
  auto t0 = std::chrono::steady_clock::now();
  MultiRenderer cl = make_renderer(devs, cfg, s);
  cl.prepare(scene, s.width, s.height, s.depth);
  r.build_warm_ms = cl.build_ms();
  r.build_warm_cached = true;
  for (size_t i = 0; i < cl.size(); ++i) r.build_warm_cached = r.build_warm_cached && cl.renderer(i).timings().build_cached;
  r.upload_ms = cl.upload_ms();
  r.options = cl.renderer(0).options();
  r.image = cl.render();
  r.end_to_end_ms = ms_since(t0);
  r.first_launch_ms = cl.kernel_ms();

  std::vector<double> downloads, frames;
  for (int i = 0; i < std::max(1, s.repeat); ++i) {
    r.image = cl.render();
    r.kernel_ms.push_back(cl.kernel_ms());
    frames.push_back(cl.wall_ms());
    double dl = 0;
    for (size_t d = 0; d < cl.size(); ++d) dl += cl.renderer(d).timings().download_ms;
    downloads.push_back(dl);
  }
  r.shares = cl.shares();
  r.frame_ms_median = median(frames);
  r.kernel_ms_median = median(r.kernel_ms);
  r.kernel_ms_min = *std::min_element(r.kernel_ms.begin(), r.kernel_ms.end());
  r.kernel_ms_max = *std::max_element(r.kernel_ms.begin(), r.kernel_ms.end());
  r.download_ms = median(downloads);

  // Rays: a separate build with per-pixel counters (they cost time).
  KernelConfig counting = cfg;
  counting.count_rays = true;
  MultiRenderer rc = make_renderer(devs, counting, s);
  rc.prepare(scene, s.width, s.height, s.depth);
  (void)rc.render();
  r.rays = rc.ray_counts();
  if (r.kernel_ms_median > 0) {
    r.mrays_per_s = r.rays.total() / (r.kernel_ms_median * 1e3);
    r.gflops = kFlopPerSphereTest * r.rays.sphere_tests / (r.kernel_ms_median * 1e6);
  }
  if (r.rays.sphere_tests) r.ns_per_sphere_test = r.kernel_ms_median * 1e6 / r.rays.sphere_tests;
  for (const auto& d : devs)
    if (d.type.find("CPU") != std::string::npos) r.peak_gflops += cpu_peak_gflops(d);

  if (s.reference) {
    auto t1 = std::chrono::steady_clock::now();
    r.reference = render_reference(scene, s.width, s.height, s.depth);
    r.reference_ms = ms_since(t1);
    if (r.kernel_ms_median > 0) r.speedup_vs_reference = r.reference_ms / r.kernel_ms_median;
  }
  if (s.omp) {
    std::vector<float> rgb;
    std::vector<double> t;
    for (int i = 0; i <= std::max(1, s.repeat); ++i) {  // first run is the warm-up
      auto t2 = std::chrono::steady_clock::now();
      r.omp_threads = clrt_bench::omp_render(scene, s.width, s.height, s.depth, rgb);
      if (i > 0) t.push_back(ms_since(t2));
    }
    r.omp_ms_median = median(t);
    if (r.kernel_ms_median > 0) r.opencl_speedup_vs_omp = r.omp_ms_median / r.kernel_ms_median;
  }
  return r;
}

nlohmann::json shares_json(const std::vector<DeviceShare>& shares) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& d : shares)
    a.push_back({{"device", d.device},
                 {"tiles", d.tiles},
                 {"rows", d.rows},
                 {"kernel_ms", d.kernel_ms},
                 {"busy_ms", d.busy_ms},
                 {"longest_launch_ms", d.max_launch_ms}});
  return a;
}

nlohmann::json bench_json(const BenchResult& r) {
  const char* pocl_cache = std::getenv("POCL_KERNEL_CACHE");
  return {{"device", r.device},
          {"build_options", r.options},
          {"width", r.width},
          {"height", r.height},
          {"depth", r.depth},
          {"repeat", r.repeat},
          {"build_cold_ms", r.build_cold_ms},
          {"build_warm_ms", r.build_warm_ms},
          {"build_warm_cached", r.build_warm_cached},
          {"pocl_kernel_cache", pocl_cache ? pocl_cache : "default"},
          {"upload_ms", r.upload_ms},
          {"first_launch_ms", r.first_launch_ms},
          {"kernel_ms", r.kernel_ms},
          {"kernel_ms_median", r.kernel_ms_median},
          {"kernel_ms_min", r.kernel_ms_min},
          {"kernel_ms_max", r.kernel_ms_max},
          {"frame_ms_median", r.frame_ms_median},
          {"devices", shares_json(r.shares)},
          {"download_ms", r.download_ms},
          {"end_to_end_ms", r.end_to_end_ms},
          {"rays_primary", r.rays.primary},
          {"rays_shadow", r.rays.shadow},
          {"rays_reflection", r.rays.reflection},
          {"rays_total", r.rays.total()},
          {"sphere_tests", r.rays.sphere_tests},
          {"mrays_per_s", r.mrays_per_s},
          {"ns_per_sphere_test", r.ns_per_sphere_test},
          {"flop_per_sphere_test", kFlopPerSphereTest},
          {"gflops", r.gflops},
          {"peak_gflops", r.peak_gflops},
          {"reference_ms", r.reference_ms},
          {"speedup_vs_reference", r.speedup_vs_reference},
          {"omp_ms_median", r.omp_ms_median},
          {"omp_threads", r.omp_threads},
          {"opencl_speedup_vs_omp", r.opencl_speedup_vs_omp}};
}

void print_bench(const BenchResult& r) {
  std::printf("device         %s\n", r.device.c_str());
  std::printf("image          %dx%d, depth %d, %d timed launches after a warm-up\n", r.width, r.height, r.depth,
              r.repeat);
  std::printf("options        %s\n", r.options.c_str());
  std::printf("build          cold %.1f ms (no program cache), warm %.1f ms%s\n", r.build_cold_ms, r.build_warm_ms,
              r.build_warm_cached ? " (cache hit)" : " (cache miss)");
  std::printf("upload         %.3f ms\n", r.upload_ms);
  std::printf("kernel         median %.2f ms, min %.2f, max %.2f (first launch %.2f ms)\n", r.kernel_ms_median,
              r.kernel_ms_min, r.kernel_ms_max, r.first_launch_ms);
  std::printf("frame          median %.2f ms wall (all devices, launches + downloads)\n", r.frame_ms_median);
  if (r.shares.size() > 1) {
    std::printf("tiles          share of the last timed frame per device:\n");
    print_shares(r.shares);
  }
  std::printf("download       %.2f ms\n", r.download_ms);
  std::printf("end to end     %.1f ms (new renderer: build + upload + render)\n", r.end_to_end_ms);
  std::printf("rays           %llu total: %llu primary, %llu shadow, %llu reflection; %llu ray-sphere tests\n",
              (unsigned long long)r.rays.total(), (unsigned long long)r.rays.primary, (unsigned long long)r.rays.shadow,
              (unsigned long long)r.rays.reflection, (unsigned long long)r.rays.sphere_tests);
  std::printf("throughput     %.1f Mrays/s, %.3f ns per ray-sphere test\n", r.mrays_per_s, r.ns_per_sphere_test);
  std::printf("GFLOP/s        %.1f (%.0f FLOP per ray-sphere test) of %.0f peak (%.1f%%)\n", r.gflops,
              kFlopPerSphereTest, r.peak_gflops, r.peak_gflops > 0 ? 100 * r.gflops / r.peak_gflops : 0.0);
  if (r.reference_ms > 0)
    std::printf("reference      %.1f ms (scalar double, 1 thread): OpenCL is %.2fx faster\n", r.reference_ms,
                r.speedup_vs_reference);
  if (r.omp_ms_median > 0)
    std::printf("OpenMP float   %.1f ms median (%d threads, -O3 -march=native): OpenCL is %.2fx faster\n",
                r.omp_ms_median, r.omp_threads, r.opencl_speedup_vs_omp);
}

}  // namespace clrt

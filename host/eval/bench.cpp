// bench.cpp - one scene on one or more devices: every time of the pipeline,
// rays, the device's measured peak, and the reference / OpenMP comparisons
// measured in the same run.
#include "eval/bench.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "cl/launch_timing.hpp"
#include "omp_tracer.hpp"
#include "reference/reference.hpp"
#include "util/timer.hpp"

namespace clrt {
namespace {

MultiRenderer make_renderer(const std::vector<DeviceInfo>& devs, const KernelConfig& cfg, const BenchSettings& s) {
  MultiRenderer r(devs, cfg);
  r.set_local_size(s.local_x, s.local_y);
  r.set_tile_policy(s.policy);
  return r;
}

bool all_cached(MultiRenderer& cl) {
  for (size_t d = 0; d < cl.size(); ++d)
    if (!cl.renderer(d).timings().build_cached) return false;
  return true;
}

double download_ms(MultiRenderer& cl) {
  double ms = 0;
  for (size_t d = 0; d < cl.size(); ++d) ms += cl.renderer(d).timings().download_ms;
  return ms;
}

}  // namespace

std::string BenchResult::kernel_time_source() const {
  return time_source(host_timed_launches, launches);
}

BenchResult run_bench(const Scene& scene, const std::vector<DeviceInfo>& devs, const KernelConfig& cfg,
                      const BenchSettings& s) {
  BenchResult r;
  for (size_t i = 0; i < devs.size(); ++i) r.device += (i ? " + " : "") + devs[i].name;
  r.width = s.width;
  r.height = s.height;
  r.depth = s.depth;
  r.repeat = std::max(1, s.repeat);
  const int build_repeat = std::min(r.repeat, kMaxBuildRepeat);

  std::vector<double> cold, warm, uploads;
  if (s.builds) {
    // Cold: from source, program cache bypassed (PoCL's own cache is only
    // off if POCL_KERNEL_CACHE=0 is set; see docs/performance.md).
    KernelConfig no_cache = cfg;
    no_cache.use_cache = false;
    for (int i = 0; i < build_repeat; ++i) {
      MultiRenderer c = make_renderer(devs, no_cache, s);
      c.prepare(scene, s.width, s.height, s.depth);
      cold.push_back(c.build_ms());
    }
    // Make sure the entry exists, then time loads from the cache.
    if (cfg.use_cache) {
      r.build_warm_cached = true;
      for (int i = 0; i <= build_repeat; ++i) {
        MultiRenderer c = make_renderer(devs, cfg, s);
        c.prepare(scene, s.width, s.height, s.depth);
        if (i == 0) continue;  // the one that stores the entry
        warm.push_back(c.build_ms());
        uploads.push_back(c.upload_ms());
        r.build_warm_cached = r.build_warm_cached && all_cached(c);
      }
    }
  }

  // End to end on a fresh renderer: (warm) build + upload + first frame.
  const auto t0 = Clock::now();
  MultiRenderer cl = make_renderer(devs, cfg, s);
  cl.prepare(scene, s.width, s.height, s.depth);
  r.options = cl.renderer(0).options();
  if (warm.empty()) {
    warm.push_back(cl.build_ms());
    r.build_warm_cached = cfg.use_cache && all_cached(cl);
  }
  uploads.push_back(cl.upload_ms());
  r.image = cl.render();
  r.end_to_end_ms = ms_since(t0);
  r.first_launch_ms = cl.kernel_ms();
  r.build_cold = summarize(cold);
  r.build_warm = summarize(warm);
  r.upload = summarize(uploads);

  // Timed rounds: a clrt frame, then an OpenMP frame of the same image, so
  // background load on a shared machine falls on both alike and each round
  // gives one like-for-like ratio.
  std::vector<float> omp_rgb;
  if (s.omp) r.omp_threads = clrt_bench::omp_render(scene, s.width, s.height, s.depth, omp_rgb);  // warm-up
  std::vector<double> frames, downloads, omp_ms, frame_ratio, kernel_ratio;
  for (int i = 0; i < r.repeat; ++i) {
    r.image = cl.render();
    r.kernel_ms.push_back(cl.kernel_ms());
    frames.push_back(cl.wall_ms());
    downloads.push_back(download_ms(cl));
    r.launches += cl.launches();
    r.host_timed_launches += cl.host_timed_launches();
    if (s.omp) {
      const auto t1 = Clock::now();
      r.omp_threads = clrt_bench::omp_render(scene, s.width, s.height, s.depth, omp_rgb);
      omp_ms.push_back(ms_since(t1));
      if (frames.back() > 0) frame_ratio.push_back(omp_ms.back() / frames.back());
      if (r.kernel_ms.back() > 0) kernel_ratio.push_back(omp_ms.back() / r.kernel_ms.back());
    }
  }
  r.shares = cl.shares();
  r.kernel = summarize(r.kernel_ms);
  r.frame = summarize(frames);
  r.download = summarize(downloads);
  r.omp = summarize(omp_ms);
  r.speedup_vs_omp = summarize(frame_ratio);
  r.kernel_speedup_vs_omp = summarize(kernel_ratio);

  // Rays: a separate build with per-pixel counters (they cost time).
  KernelConfig counting = cfg;
  counting.count_rays = true;
  MultiRenderer rc = make_renderer(devs, counting, s);
  rc.prepare(scene, s.width, s.height, s.depth);
  (void)rc.render();
  r.rays = rc.ray_counts();
  if (r.kernel.median > 0) {
    r.mrays_per_s = r.rays.total() / (r.kernel.median * 1e3);
    r.gflops = kFlopPerSphereTest * r.rays.sphere_tests / (r.kernel.median * 1e6);
  }
  if (r.rays.sphere_tests) r.ns_per_sphere_test = r.kernel.median * 1e6 / r.rays.sphere_tests;

  if (s.peak) {
    bool all = true;
    for (const auto& d : devs) {
      r.peaks.push_back(measure_peak_flops(d));
      all = all && r.peaks.back().measured;
      r.peak_gflops += r.peaks.back().gflops;
    }
    if (!all) r.peak_gflops = 0;
  }

  if (s.reference) {
    const auto t2 = Clock::now();
    r.reference_image = render_reference(scene, s.width, s.height, s.depth);
    r.reference = summarize({ms_since(t2)});
    if (r.frame.median > 0) r.speedup_vs_reference = r.reference.median / r.frame.median;
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
                 {"kernel_time_source", time_source(d.host_timed_launches, d.tiles)},
                 {"busy_ms", d.busy_ms},
                 {"longest_launch_ms", d.max_launch_ms}});
  return a;
}

nlohmann::json bench_json(const BenchResult& r) {
  const char* pocl_cache = std::getenv("POCL_KERNEL_CACHE");
  nlohmann::json peaks = nlohmann::json::array();
  for (const auto& p : r.peaks) {
    nlohmann::json j = {{"measured", p.measured}};
    if (p.measured)
      j.update({{"gflops", p.gflops},
                {"launch_ms", stats_json(p.launch_ms)},
                {"time_source", p.from_events ? "events" : "host"}});
    else
      j["note"] = p.note;
    peaks.push_back(j);
  }
  // Flat *_ms / *_median keys are the medians of the matching Stats objects.
  return {{"device", r.device},
          {"build_options", r.options},
          {"width", r.width},
          {"height", r.height},
          {"depth", r.depth},
          {"repeat", r.repeat},
          {"build_cold", stats_json(r.build_cold)},
          {"build_cold_ms", r.build_cold.median},
          {"build_warm", stats_json(r.build_warm)},
          {"build_warm_ms", r.build_warm.median},
          {"build_warm_cached", r.build_warm_cached},
          {"pocl_kernel_cache", pocl_cache ? pocl_cache : "default"},
          {"upload", stats_json(r.upload)},
          {"upload_ms", r.upload.median},
          {"first_launch_ms", r.first_launch_ms},
          {"kernel_ms", r.kernel_ms},
          {"kernel", stats_json(r.kernel)},
          {"kernel_ms_median", r.kernel.median},
          {"kernel_ms_min", r.kernel.min},
          {"kernel_ms_max", r.kernel.max},
          {"kernel_time_source", r.kernel_time_source()},
          {"launches", r.launches},
          {"host_timed_launches", r.host_timed_launches},
          {"frame", stats_json(r.frame)},
          {"frame_ms_median", r.frame.median},
          {"devices", shares_json(r.shares)},
          {"download", stats_json(r.download)},
          {"download_ms", r.download.median},
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
          {"peak_gflops", r.peak_gflops > 0 ? nlohmann::json(r.peak_gflops) : nlohmann::json()},
          {"peaks", peaks},
          {"reference", stats_json(r.reference)},
          {"reference_ms", r.reference.median},
          {"speedup_vs_reference", r.speedup_vs_reference},
          {"omp", stats_json(r.omp)},
          {"omp_ms_median", r.omp.median},
          {"omp_threads", r.omp_threads},
          {"speedup_vs_omp", stats_json(r.speedup_vs_omp)},
          {"opencl_speedup_vs_omp", r.speedup_vs_omp.median},
          {"kernel_speedup_vs_omp", stats_json(r.kernel_speedup_vs_omp)}};
}

void print_bench(const BenchResult& r) {
  const std::string source = time_source_note(r.host_timed_launches, r.launches);
  std::printf("device         %s\n", r.device.c_str());
  std::printf("image          %dx%d, depth %d, %d timed rounds after a warm-up\n", r.width, r.height, r.depth,
              r.repeat);
  std::printf("options        %s\n", r.options.c_str());
  std::printf("build cold     %s (no program cache)\n", format_stats(r.build_cold, "ms", 1).c_str());
  std::printf("build warm     %s%s\n", format_stats(r.build_warm, "ms", 1).c_str(),
              r.build_warm_cached ? " (cache hit)" : " (cache miss)");
  std::printf("upload         %s\n", format_stats(r.upload, "ms", 3).c_str());
  std::printf("frame          %s (warm: launches + download into host memory)\n", format_stats(r.frame).c_str());
  std::printf("kernel         %s%s\n", format_stats(r.kernel).c_str(), source.c_str());
  std::printf("download       %s\n", format_stats(r.download).c_str());
  if (r.shares.size() > 1) {
    std::printf("tiles          share of the last timed frame per device:\n");
    print_shares(r.shares);
  }
  std::printf("end to end     %.1f ms (N=1: new renderer, build + upload + first frame; its kernel %.2f ms)\n",
              r.end_to_end_ms, r.first_launch_ms);
  std::printf("rays           %llu total: %llu primary, %llu shadow, %llu reflection; %llu ray-sphere tests\n",
              (unsigned long long)r.rays.total(), (unsigned long long)r.rays.primary, (unsigned long long)r.rays.shadow,
              (unsigned long long)r.rays.reflection, (unsigned long long)r.rays.sphere_tests);
  std::printf("throughput     %.1f Mrays/s, %.3f ns per ray-sphere test (median kernel time%s)\n", r.mrays_per_s,
              r.ns_per_sphere_test, r.host_timed_launches ? ", host clock" : "");
  if (r.peak_gflops > 0)
    std::printf("GFLOP/s        %.1f (%.0f FLOP per ray-sphere test) of %.0f measured peak (%.1f%%)\n", r.gflops,
                kFlopPerSphereTest, r.peak_gflops, 100 * r.gflops / r.peak_gflops);
  else
    std::printf("GFLOP/s        %.1f (%.0f FLOP per ray-sphere test); device peak unknown%s\n", r.gflops,
                kFlopPerSphereTest, r.peaks.empty() ? " (not measured)" : "");
  for (size_t i = 0; i < r.peaks.size(); ++i) {
    const auto& p = r.peaks[i];
    if (p.measured)
      std::printf("  peak %zu       %.1f GFLOP/s multiply-add kernel, best of %d launches (%s)\n", i, p.gflops,
                  p.launch_ms.n, p.from_events ? "profiling events" : "host clock");
    else
      std::printf("  peak %zu       unknown: %s\n", i, p.note.c_str());
  }
  if (r.reference.n > 0)
    std::printf("reference      %s (scalar double, 1 thread): speedup %.2fx (reference / clrt frame)\n",
                format_stats(r.reference, "ms", 1).c_str(), r.speedup_vs_reference);
  if (r.omp.n > 0) {
    std::printf("OpenMP float   %s (%d threads, -O3 -march=native)\n", format_stats(r.omp).c_str(), r.omp_threads);
    std::printf("speedup        %s (OpenMP frame / clrt frame, per round; > 1: clrt is faster)\n",
                format_stats(r.speedup_vs_omp, "x").c_str());
    std::printf("  kernel only  %s (OpenMP frame / clrt kernel time%s; not like for like)\n",
                format_stats(r.kernel_speedup_vs_omp, "x").c_str(), r.host_timed_launches ? ", host clock" : "");
  }
}

}  // namespace clrt

// bench.cpp - one scene on one or more devices: every time of the pipeline,
// rays, the device's measured peak, and the reference / OpenMP / Embree
// comparisons measured in the same run.
#include "eval/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>

#include "cl/launch_timing.hpp"
#include "cl/program.hpp"
#include "embree_tracer.hpp"
#include "omp_tracer.hpp"
#include "reference/reference.hpp"
#include "util/build_features.hpp"
#include "util/timer.hpp"

namespace clrt {

std::string BenchResult::kernel_time_source() const {
  return time_source(host_timed_launches, launches);
}

namespace {

// The agreement of two images of `channels` values per pixel, comparing the
// first three channels as 8-bit levels (`level` maps a stored value to one).
template <class T, class Level>
PixelAgreement pixel_agreement(const std::vector<T>& a, const std::vector<T>& b, size_t channels, int levels,
                               Level level) {
  PixelAgreement p;
  if (a.size() != b.size()) {
    p.differ = 1;
    p.max_levels = 255;
    return p;
  }
  const size_t pixels = a.size() / channels;
  size_t differ = 0;
  for (size_t i = 0; i < pixels; ++i) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(level(a[channels * i + c]) - level(b[channels * i + c])));
    p.max_levels = std::max(p.max_levels, worst);
    if (worst > levels) ++differ;
  }
  if (pixels) p.differ = double(differ) / double(pixels);
  return p;
}

}  // namespace

PixelAgreement compare_rgb(const std::vector<float>& a, const std::vector<float>& b, int levels) {
  return pixel_agreement(a, b, 3, levels, [](float v) { return int(to_u8(v)); });
}

PixelAgreement compare_rgba8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int levels) {
  return pixel_agreement(a, b, 4, levels, [](uint8_t v) { return int(v); });
}

namespace {

using StepFn = std::function<void(const std::string& what)>;

// Why the OpenMP and Embree tracers are not run on `scene` ("": they are).
// They trace one ray per pixel: at spp > 1 or subsampled their frames
// would not be the same image; a lean build has none.
std::string tracers_not_run(const BenchSettings& s) {
  if (kLeanBuild) return std::string(kLeanBuildNote) + " (no OpenMP/Embree comparison tracers)";
  if (s.subsample != Subsample::Off) return "they do not subsample (--subsample)";
  if (s.spp > 1)
    return "they trace one ray per pixel (--spp " + std::to_string(s.spp) + " traces " + std::to_string(s.spp * s.spp) +
           ")";
  return "";
}

// Why the OpenMP tracer alone is not run ("": it is): it tests every
// primitive for every ray, which for a mesh is no comparison (and hours at
// a million triangles); the Embree tracer, with Embree's own triangles, is.
std::string omp_not_run(const Scene& scene) {
  if (scene.triangles.empty()) return "";
  return "it tests every triangle for every ray (the scene has " + std::to_string(scene.triangles.size()) +
         "); the Embree tracer is the comparison for meshes";
}

// The Embree image against clrt's (both in the frame's format).
PixelAgreement against_clrt(const Image& clrt_image, bool rgba8, const std::vector<float>& embree_rgb,
                            const std::vector<uint8_t>& embree_rgba8) {
  if (rgba8) return compare_rgba8(embree_rgba8, clrt_image.rgba8);
  const std::vector<float> clrt_rgb(clrt_image.rgb.begin(), clrt_image.rgb.end());
  return compare_rgb(embree_rgb, clrt_rgb);
}

// Cold builds (from source, the program cache bypassed) and cached builds:
// their times, into the three lists.
void time_builds(const Scene& scene, const std::vector<DeviceInfo>& devs, const RenderSettings& settings,
                 const BenchSettings& s, int build_repeat, const StepFn& step, BenchResult& r,
                 std::vector<double>& cold, std::vector<double>& warm, std::vector<double>& uploads) {
  // Cold: from source, program cache bypassed (PoCL's own cache is only
  // off if POCL_KERNEL_CACHE=0 is set; see docs/reference/kernel.md).
  RenderSettings no_cache = settings;
  no_cache.kernel.use_cache = false;
  for (int i = 0; i < build_repeat; ++i) {
    step("cold build " + std::to_string(i + 1) + " of " + std::to_string(build_repeat));
    Renderer c(devs, no_cache);
    c.prepare(scene, s.width, s.height, s.depth, s.sampling());
    cold.push_back(c.stats().build_ms);
  }
  // Make sure the entry exists, then time loads from the cache.
  if (settings.kernel.use_cache) {
    r.build_warm_cached = true;
    r.build_warm_driver_cached = std::all_of(devs.begin(), devs.end(), driver_caches_programs);
    for (int i = 0; i <= build_repeat; ++i) {
      step("cached build " + std::to_string(i + 1) + " of " + std::to_string(build_repeat + 1));
      Renderer c(devs, settings);
      c.prepare(scene, s.width, s.height, s.depth, s.sampling());
      if (i == 0) continue;  // the one that stores the entry
      warm.push_back(c.stats().build_ms);
      uploads.push_back(c.stats().upload_ms);
      r.build_warm_cached = r.build_warm_cached && c.stats().build_cached;
    }
  }
}

// The pause before a clrt frame that follows the other tracers' frames.
constexpr std::chrono::milliseconds kTracerSettle{30};

// The timed rounds on `cl`, with the OpenMP and Embree frames beside
// clrt's when `tracers`.
void time_rounds(const Scene& scene, const RenderSettings& settings, const BenchSettings& s, bool tracers, Renderer& cl,
                 const StepFn& step, BenchResult& r) {
  // Timed rounds: a clrt frame, then an OpenMP frame and an Embree frame of
  // the same image, so background load on a shared machine falls on all
  // alike and each round gives one like-for-like ratio per comparison. The
  // Embree frame builds its BVH first; only its render is the frame.
  // The tracers write the frame's format too (float RGB, or 8-bit RGBA with
  // the canvas rule), into memory reused from frame to frame like clrt's.
  const bool rgba8 = settings.kernel.output.pixels == PixelFormat::Rgba8;
  r.rgba8 = rgba8;
  std::vector<float> omp_rgb, embree_rgb;
  std::vector<uint8_t> omp_rgba8, embree_rgba8;
  clrt_bench::EmbreeBuildInfo embree_info;
  const auto omp_frame = [&] {
    return rgba8 ? clrt_bench::omp_render(scene, s.width, s.height, s.depth, omp_rgba8)
                 : clrt_bench::omp_render(scene, s.width, s.height, s.depth, omp_rgb);
  };
  const auto embree_frame = [&] {
    return rgba8 ? clrt_bench::embree_render(scene, s.width, s.height, s.depth, embree_rgba8, &embree_info)
                 : clrt_bench::embree_render(scene, s.width, s.height, s.depth, embree_rgb, &embree_info);
  };
  const bool omp = s.omp && tracers && r.omp_not_run.empty();
  if (omp) r.omp_threads = omp_frame();  // warm-up
  if (s.embree && tracers) r.embree_threads = embree_frame();
  std::vector<double> frames, downloads, omp_ms, frame_ratio, kernel_ratio, embree_ms, embree_build, embree_ratio;
  // Each tracer's frame as in frames rendered back to back by it alone:
  // libgomp's idle threads spin on after a parallel region (GOMP_SPINCOUNT,
  // 300 000 pauses: milliseconds) and would take a core from clrt's next
  // kernel, so clrt's frame waits kTracerSettle after the others' (the demo's
  // kernel: 4.9-7.9 ms without, 5.2-6.0 with, docs/results/wide-hierarchy.md
  // "Short frames on one core"); the OpenMP threads are woken just before
  // the OpenMP frame and the Embree render (after its build), as their own
  // last frame would leave them.
  const bool other_tracers = omp || (s.embree && tracers);
  for (int i = 0; i < r.repeat; ++i) {
    step("round " + std::to_string(i + 1) + " of " + std::to_string(r.repeat));
    if (other_tracers) std::this_thread::sleep_for(kTracerSettle);
    cl.render_into(r.image);  // like the OpenMP tracer's, the image's memory is reused
    const FrameStats& frame = cl.stats();
    r.kernel_ms.push_back(frame.kernel_ms);
    frames.push_back(frame.wall_ms);
    downloads.push_back(frame.download_ms);
    r.launches += frame.launches;
    r.host_timed_launches += frame.host_timed_launches;
    if (omp) {
      clrt_bench::omp_warm_threads();
      const auto t1 = Clock::now();
      r.omp_threads = omp_frame();
      omp_ms.push_back(ms_since(t1));
      if (frames.back() > 0) frame_ratio.push_back(omp_ms.back() / frames.back());
      if (r.kernel_ms.back() > 0) kernel_ratio.push_back(omp_ms.back() / r.kernel_ms.back());
    }
    if (s.embree && tracers) {
      r.embree_threads = embree_frame();  // (it wakes the OpenMP threads after its build)
      embree_ms.push_back(embree_info.render_ms);
      embree_build.push_back(embree_info.build_ms);
      if (frames.back() > 0) embree_ratio.push_back(embree_ms.back() / frames.back());
    }
  }
  if (s.embree && tracers) {
    const PixelAgreement a = against_clrt(r.image, rgba8, embree_rgb, embree_rgba8);
    r.embree_vs_clrt_differ = a.differ;
    r.embree_vs_clrt_max_levels = a.max_levels;
  }
  if (omp && s.embree) {
    const PixelAgreement a = rgba8 ? compare_rgba8(embree_rgba8, omp_rgba8) : compare_rgb(embree_rgb, omp_rgb);
    r.embree_vs_omp_differ = a.differ;
    r.embree_vs_omp_max_levels = a.max_levels;
  }
  r.shares = cl.stats().shares;
  r.kernel = summarize(r.kernel_ms);
  r.frame = summarize(frames);
  r.download = summarize(downloads);
  r.omp = summarize(omp_ms);
  r.speedup_vs_omp = summarize(frame_ratio);
  r.kernel_speedup_vs_omp = summarize(kernel_ratio);
  r.embree = summarize(embree_ms);
  r.embree_build = summarize(embree_build);
  r.embree_build_ms = r.embree_build.median;
  r.speedup_vs_embree = summarize(embree_ratio);
}

// Rays: a separate build with per-pixel counters (they cost time).
void count_rays(const Scene& scene, const std::vector<DeviceInfo>& devs, const RenderSettings& settings,
                const BenchSettings& s, BenchResult& r) {
  RenderSettings counting = settings;
  counting.kernel.count_rays = true;
  Renderer rc(devs, counting);
  rc.prepare(scene, s.width, s.height, s.depth, s.sampling());
  (void)rc.render();
  r.rays = rc.stats().rays;
  if (r.kernel.median > 0) {
    r.mrays_per_s = r.rays.total() / (r.kernel.median * 1e3);
    r.gflops = kFlopPerSphereTest * r.rays.sphere_tests / (r.kernel.median * 1e6);
  }
  if (r.rays.sphere_tests) r.ns_per_sphere_test = r.kernel.median * 1e6 / r.rays.sphere_tests;
}

// Each device's measured peak of multiply-adds (0 in all when one was not
// measured).
void measure_peaks(const std::vector<DeviceInfo>& devs, BenchResult& r) {
  bool all = true;
  for (const auto& d : devs) {
    r.peaks.push_back(measure_peak_flops(d));
    all = all && r.peaks.back().measured;
    r.peak_gflops += r.peaks.back().gflops;
  }
  if (!all) r.peak_gflops = 0;
}

// The scalar double reference's time for the same image.
void time_reference(const Scene& scene, const BenchSettings& s, BenchResult& r) {
  const auto t2 = Clock::now();
  r.reference_image = render_reference(scene, s.width, s.height, s.depth, s.sampling());
  r.reference = summarize({ms_since(t2)});
  if (r.frame.median > 0) r.speedup_vs_reference = r.reference.median / r.frame.median;
}

}  // namespace

BenchResult run_bench(const Scene& scene, const std::vector<DeviceInfo>& devs, const RenderSettings& settings,
                      const BenchSettings& s) {
  BenchResult r;
  for (size_t i = 0; i < devs.size(); ++i) r.device += (i ? " + " : "") + devs[i].name;
  r.width = s.width;
  r.height = s.height;
  r.depth = s.depth;
  r.spp = s.spp;
  r.subsample = s.subsample;
  r.repeat = s.repeat;
  r.tracers_not_run = tracers_not_run(s);
  r.omp_not_run = omp_not_run(scene);
  const bool tracers = r.tracers_not_run.empty();
  const int build_repeat = std::min(r.repeat, kMaxBuildRepeat);
  const bool warm_builds = s.builds && settings.kernel.use_cache;
  const int total = (s.builds ? build_repeat : 0) + (warm_builds ? build_repeat + 1 : 0) + 1 + r.repeat + 1 +
                    (s.peak ? 1 : 0) + (s.reference ? 1 : 0);
  int done = 0;
  const auto step = [&](const std::string& what) {
    if (s.progress) s.progress(done++, total, what);
  };

  std::vector<double> cold, warm, uploads;
  if (s.builds) time_builds(scene, devs, settings, s, build_repeat, step, r, cold, warm, uploads);

  // End to end on a fresh renderer: (warm) build + upload + first frame.
  step("first frame and warm-ups");
  const auto t0 = Clock::now();
  Renderer cl(devs, settings);
  cl.prepare(scene, s.width, s.height, s.depth, s.sampling());
  r.options = cl.options();
  if (warm.empty()) {
    warm.push_back(cl.stats().build_ms);
    r.build_warm_cached = settings.kernel.use_cache && cl.stats().build_cached;
  }
  uploads.push_back(cl.stats().upload_ms);
  r.image = cl.render();
  r.end_to_end_ms = ms_since(t0);
  r.first_launch_ms = cl.stats().kernel_ms;
  r.bvh = cl.stats().bvh;
  r.bvh_build_ms = cl.stats().bvh_build_ms;
  r.bvh_bytes = cl.stats().bvh_bytes;
  r.bvh_depth = cl.stats().bvh_depth;
  r.build_cold = summarize(cold);
  r.build_warm = summarize(warm);
  r.upload = summarize(uploads);

  time_rounds(scene, settings, s, tracers, cl, step, r);

  step("counting rays");
  count_rays(scene, devs, settings, s, r);
  if (s.peak) {
    step("peak multiply-adds");
    measure_peaks(devs, r);
  }
  if (s.reference) {
    step("reference (scalar double)");
    time_reference(scene, s, r);
  }
  if (s.progress) s.progress(total, total, "done");
  return r;
}

}  // namespace clrt

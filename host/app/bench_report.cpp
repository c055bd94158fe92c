// bench_report.cpp - a BenchResult as text and JSON.
#include "app/bench_report.hpp"

#include <cstdio>
#include <cstdlib>

#include "app/frame_report.hpp"
#include "app/report_header.hpp"
#include "cl/launch_timing.hpp"
#include "util/stats.hpp"

namespace clrt {

nlohmann::ordered_json bench_json(const BenchResult& r) {
  const char* pocl_cache = std::getenv("POCL_KERNEL_CACHE");
  // (the user's, or clrt's own where it pinned PoCL's workers: cl/pocl_workers.hpp)
  const char* pocl_affinity = std::getenv("POCL_AFFINITY");
  nlohmann::ordered_json peaks = nlohmann::ordered_json::array();
  for (const auto& p : r.peaks) {
    nlohmann::ordered_json j = {{"measured", p.measured}};
    if (p.measured)
      j.update({{"gflops", p.gflops},
                {"launch_ms", stats_json(p.launch_ms, "ms")},
                {"time_source", p.from_events ? "events" : "host"}});
    else
      j["note"] = p.note;
    peaks.push_back(j);
  }
  // Flat *_ms / *_median keys are the medians of the matching Stats objects.
  nlohmann::ordered_json out = header_json(report_header(r.device));
  out.update(nlohmann::ordered_json{
      {"device", r.device},
      {"build_options", r.options},
      {"width", r.width},
      {"pixels", r.rgba8 ? "rgba8" : "float"},
      {"height", r.height},
      {"depth", r.depth},
      {"spp", r.spp},
      {"subsample", subsample_name(r.subsample)},
      {"repeat", r.repeat},
      {"build_cold", stats_json(r.build_cold, "ms")},
      {"build_cold_ms", r.build_cold.median},
      {"build_warm", stats_json(r.build_warm, "ms")},
      {"build_warm_ms", r.build_warm.median},
      {"build_warm_cached", r.build_warm_cached},
      {"build_warm_driver_cached", r.build_warm_driver_cached},
      {"pocl_kernel_cache", pocl_cache ? pocl_cache : "default"},
      {"pocl_affinity", pocl_affinity ? pocl_affinity : "unset"},
      {"upload", stats_json(r.upload, "ms")},
      {"upload_ms", r.upload.median},
      {"first_launch_ms", r.first_launch_ms},
      {"kernel_ms", r.kernel_ms},
      {"kernel", stats_json(r.kernel, "ms")},
      {"kernel_ms_median", r.kernel.median},
      {"kernel_ms_min", r.kernel.min},
      {"kernel_ms_max", r.kernel.max},
      {"kernel_time_source", r.kernel_time_source()},
      {"launches", r.launches},
      {"host_timed_launches", r.host_timed_launches},
      {"frame", stats_json(r.frame, "ms")},
      {"frame_ms_median", r.frame.median},
      {"devices", shares_json(r.shares)},
      {"download", stats_json(r.download, "ms")},
      {"download_ms", r.download.median},
      {"end_to_end_ms", r.end_to_end_ms},
      {"accel", r.bvh ? "bvh" : "none"},
      {"bvh_build_ms", r.bvh_build_ms},
      {"bvh_bytes", r.bvh_bytes},
      {"bvh_depth", r.bvh_depth},
      {"rays_primary", r.rays.primary},
      {"rays_shadow", r.rays.shadow},
      {"rays_reflection", r.rays.reflection},
      {"rays_refraction", r.rays.refraction},
      {"rays_total", r.rays.total()},
      {"sphere_tests", r.rays.sphere_tests},
      {"mrays_per_s", r.mrays_per_s},
      {"ns_per_sphere_test", r.ns_per_sphere_test},
      {"flop_per_sphere_test", kFlopPerSphereTest},
      {"gflops", r.gflops},
      {"peak_gflops", r.peak_gflops > 0 ? nlohmann::ordered_json(r.peak_gflops) : nlohmann::ordered_json()},
      {"peaks", peaks},
      {"reference", stats_json(r.reference, "ms")},
      {"reference_ms", r.reference.median},
      {"speedup_vs_reference", r.speedup_vs_reference},
      {"omp", stats_json(r.omp, "ms")},
      {"omp_ms_median", r.omp.median},
      {"omp_threads", r.omp_threads},
      {"speedup_vs_omp", stats_json(r.speedup_vs_omp, "ratio")},
      {"opencl_speedup_vs_omp", r.speedup_vs_omp.median},
      {"kernel_speedup_vs_omp", stats_json(r.kernel_speedup_vs_omp, "ratio")},
      {"embree", stats_json(r.embree, "ms")},
      {"embree_ms_median", r.embree.median},
      {"embree_build", stats_json(r.embree_build, "ms")},
      {"embree_build_ms", r.embree_build_ms},
      {"embree_threads", r.embree_threads},
      {"speedup_vs_embree", stats_json(r.speedup_vs_embree, "ratio")},
      {"opencl_speedup_vs_embree", r.speedup_vs_embree.median},
      {"embree_vs_omp_differ",
       r.embree_vs_omp_differ >= 0 ? nlohmann::ordered_json(r.embree_vs_omp_differ) : nlohmann::ordered_json()},
      {"embree_vs_omp_max_levels",
       r.embree_vs_omp_max_levels >= 0 ? nlohmann::ordered_json(r.embree_vs_omp_max_levels) : nlohmann::ordered_json()},
      {"omp_not_run", r.omp_not_run},
      {"embree_vs_clrt_differ",
       r.embree_vs_clrt_differ >= 0 ? nlohmann::ordered_json(r.embree_vs_clrt_differ) : nlohmann::ordered_json()},
      {"embree_vs_clrt_max_levels",
       r.embree_vs_clrt_max_levels >= 0 ? nlohmann::ordered_json(r.embree_vs_clrt_max_levels)
                                        : nlohmann::ordered_json()}});
  return out;
}

void print_bench(const BenchResult& r) {
  const std::string source = time_source_note(r.host_timed_launches, r.launches);
  std::printf("device         %s\n", r.device.c_str());
  std::printf("image          %dx%d, depth %d, %dx%d samples per pixel%s, %s, %d timed rounds after a warm-up\n",
              r.width, r.height, r.depth, r.spp, r.spp,
              r.subsample == Subsample::Off ? "" : (", subsampled (" + subsample_name(r.subsample) + ")").c_str(),
              r.rgba8 ? "8-bit RGBA frames" : "float RGB frames", r.repeat);
  std::printf("options        %s\n", r.options.c_str());
  std::printf("build cold     %s (no program cache)\n", format_stats(r.build_cold, "ms", 1).c_str());
  std::printf("build warm     %s%s\n", format_stats(r.build_warm, "ms", 1).c_str(),
              r.build_warm_cached          ? " (cache hit)"
              : r.build_warm_driver_cached ? " (the driver's own cache: clrt stores nothing there)"
                                           : " (cache miss)");
  std::printf("upload         %s\n", format_stats(r.upload, "ms", 3).c_str());
  std::printf("frame          %s (warm: launches + the result in host memory, in the frame's format)\n",
              format_stats(r.frame).c_str());
  std::printf("kernel         %s%s\n", format_stats(r.kernel).c_str(), source.c_str());
  std::printf("download       %s\n", format_stats(r.download).c_str());
  if (r.shares.size() > 1) {
    std::printf("tiles          share of the last timed frame per device:\n");
    print_shares(r.shares);
  }
  std::printf("end to end     %.1f ms (N=1: new renderer, build + upload + first frame; its kernel %.2f ms)\n",
              r.end_to_end_ms, r.first_launch_ms);
  if (r.bvh)
    std::printf("hierarchy      built in %.1f ms (part of end to end), %.2f MiB, %d levels\n", r.bvh_build_ms,
                double(r.bvh_bytes) / (1 << 20), r.bvh_depth + 1);
  else
    std::printf("hierarchy      none: every ray tests every sphere (--accel)\n");
  std::printf(
      "rays           %llu total: %llu primary, %llu shadow, %llu reflection, %llu refraction; %llu ray-sphere tests\n",
      (unsigned long long)r.rays.total(), (unsigned long long)r.rays.primary, (unsigned long long)r.rays.shadow,
      (unsigned long long)r.rays.reflection, (unsigned long long)r.rays.refraction,
      (unsigned long long)r.rays.sphere_tests);
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
  if (!r.tracers_not_run.empty()) std::printf("OpenMP/Embree  not run: %s\n", r.tracers_not_run.c_str());
  if (!r.omp_not_run.empty()) std::printf("OpenMP         not run: %s\n", r.omp_not_run.c_str());
  if (r.omp.n > 0) {
    std::printf("OpenMP float   %s (%d threads, -O3 -march=native)\n", format_stats(r.omp).c_str(), r.omp_threads);
    std::printf("speedup        %s (OpenMP frame / clrt frame, per round; > 1: clrt is faster)\n",
                format_stats(r.speedup_vs_omp, "x").c_str());
    std::printf("  kernel only  %s (OpenMP frame / clrt kernel time%s; not like for like)\n",
                format_stats(r.kernel_speedup_vs_omp, "x").c_str(), r.host_timed_launches ? ", host clock" : "");
  }
  if (r.embree.n > 0) {
    std::printf("Embree float   %s (%d threads, render only; Embree 3 BVH, user-geometry spheres, %s)\n",
                format_stats(r.embree).c_str(), r.embree_threads,
                r.omp_not_run.empty() ? "no triangles" : "Embree's own triangles");
    std::printf("  BVH build    %s (once per Embree frame, not in it)\n", format_stats(r.embree_build).c_str());
    std::printf("speedup        %s (Embree frame / clrt frame, per round; > 1: clrt is faster)\n",
                format_stats(r.speedup_vs_embree, "x").c_str());
    if (r.embree_vs_omp_differ >= 0)
      std::printf("  image        %.4f%% of pixels differ from the OpenMP tracer's by > 1 level (max %d)%s\n",
                  100 * r.embree_vs_omp_differ, r.embree_vs_omp_max_levels,
                  r.embree_vs_omp_differ > 0.001 ? ": NOT the same image, the comparison is suspect" : "");
    else
      std::printf("  image        not checked against the OpenMP tracer's (%s)\n",
                  r.omp_not_run.empty() ? "--no-omp" : "not run on meshes");
    if (r.embree_vs_clrt_differ >= 0)
      std::printf("  vs clrt      %.4f%% of pixels differ from clrt's by > 1 level (max %d)%s\n",
                  100 * r.embree_vs_clrt_differ, r.embree_vs_clrt_max_levels,
                  r.embree_vs_clrt_differ > kEmbreeVsClrtTolerance ? ": NOT the same image, the comparison is suspect"
                                                                   : "");
  }
}

}  // namespace clrt

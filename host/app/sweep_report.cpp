// sweep_report.cpp - sweep rows as a table, CSV and two plots.
#include "app/sweep_report.hpp"

#include <cstdio>
#include <map>
#include <sstream>

#include "cl/launch_timing.hpp"
#include "image/plot.hpp"
#include "util/csv.hpp"

namespace clrt {

std::string sweep_csv(const std::vector<SweepRow>& rows) {
  std::ostringstream o;
  o << "device,depth,kernel_ms_median,kernel_ms_min,kernel_ms_max,kernel_ms_mean,kernel_ms_sd,kernel_n,"
       "kernel_time_source,kernel_ms_delta,frame_ms_median,frame_ms_mean,frame_ms_sd,build_warm_ms,upload_ms,"
       "download_ms,rays_primary,rays_shadow,rays_reflection,rays_refraction,rays_total,sphere_tests,mrays_per_s,"
       "ns_per_sphere_test,gflops,reference_ms,speedup_vs_reference,omp_ms_median,opencl_speedup_vs_omp,"
       "err_pixels_differ,err_off_by_gt1,err_max_abs_8bit,err_rmse_8bit,err_hit_flips,err_shadow_flips,"
       "err_nan_inf,change_pixels_differ,change_rmse_8bit,change_max_abs_8bit\n";
  for (const auto& r : rows) {
    const BenchResult& b = r.bench;
    o << csv_field(r.device) << ',' << r.depth << ',' << b.kernel.median << ',' << b.kernel.min << ',' << b.kernel.max
      << ',' << b.kernel.mean << ',' << b.kernel.sd << ',' << b.kernel.n << ',' << b.kernel_time_source() << ','
      << r.kernel_ms_delta << ',' << b.frame.median << ',' << b.frame.mean << ',' << b.frame.sd << ','
      << b.build_warm.median << ',' << b.upload.median << ',' << b.download.median << ',' << b.rays.primary << ','
      << b.rays.shadow << ',' << b.rays.reflection << ',' << b.rays.refraction << ',' << b.rays.total() << ','
      << b.rays.sphere_tests << ',' << b.mrays_per_s << ',' << b.ns_per_sphere_test << ',' << b.gflops << ','
      << r.reference_ms << ',' << r.speedup_vs_reference << ',' << b.omp.median << ',' << b.speedup_vs_omp.median << ','
      << r.error.differ << ',' << r.error.off_by_gt1 << ',' << r.error.max_abs_8bit << ',' << r.error.rmse_8bit << ','
      << r.error.hit_flips << ',' << r.error.shadow_flips << ',' << r.error.nan_inf << ',' << r.change.differ << ','
      << r.change.rmse_8bit << ',' << r.change.max_abs_8bit << '\n';
  }
  return o.str();
}

void print_sweep(const std::vector<SweepRow>& rows) {
  std::printf("%-5s %10s %9s %12s %9s %9s %9s %8s %7s %8s %9s %9s  %s\n", "depth", "kernel_ms", "delta_ms", "rays",
              "Mrays/s", "ref_ms", "vs_ref", "differ", "off>1", "rmse", "changed", "chg_rmse", "device");
  for (const auto& r : rows) {
    const BenchResult& b = r.bench;
    std::printf("%-5d %10.2f %+9.2f %12llu %9.1f %9.1f %8.1fx %8zu %7zu %8.4f %9zu %9.4f  %s\n", r.depth,
                b.kernel.median, r.kernel_ms_delta, (unsigned long long)b.rays.total(), b.mrays_per_s, r.reference_ms,
                r.speedup_vs_reference, r.error.differ, r.error.off_by_gt1, r.error.rmse_8bit, r.change.differ,
                r.change.rmse_8bit, r.device.c_str());
  }
  for (const auto& r : rows)
    if (r.bench.host_timed_launches) {
      std::printf("kernel_ms of %s%s\n", r.device.c_str(),
                  time_source_note(r.bench.host_timed_launches, r.bench.launches).c_str());
      break;
    }
}

std::string rays_plot_path(const std::string& path) {
  std::string rays_path = path;
  size_t dot = rays_path.find_last_of('.'), slash = rays_path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) dot = rays_path.size();
  rays_path.insert(dot, "-rays");
  return rays_path;
}

std::string plot_sweep(const std::vector<SweepRow>& rows, const std::string& path, const std::string& title) {
  std::map<std::string, Series> time, rays;
  Series ref("reference (scalar double)", {}, {});
  std::map<int, bool> ref_seen;
  for (const auto& r : rows) {
    Series& t = time[r.device];
    t.name = "OpenCL kernel, " + r.device;
    t.lines = true;
    t.x.push_back(r.depth);
    t.y.push_back(r.bench.kernel.median);
    Series& n = rays[r.device];
    n.name = "rays traced, " + r.device;
    n.lines = true;
    n.x.push_back(r.depth);
    n.y.push_back(r.bench.rays.total() * 1e-6);
    if (!ref_seen[r.depth]) {
      ref_seen[r.depth] = true;
      ref.x.push_back(r.depth);
      ref.y.push_back(r.reference_ms);
    }
  }
  ref.lines = true;
  std::vector<Series> ts, rs;
  for (auto& kv : time) ts.push_back(kv.second);
  ts.push_back(ref);
  for (auto& kv : rays) rs.push_back(kv.second);
  PlotOptions po;
  po.x_from_zero = true;
  po.y_from_zero = true;
  write_plot(path, title + ": time per depth", "recursion depth", "ms", ts, po);
  const std::string rays_path = rays_plot_path(path);
  write_plot(rays_path, title + ": rays per depth", "recursion depth", "million rays", rs, po);
  return rays_path;
}

}  // namespace clrt

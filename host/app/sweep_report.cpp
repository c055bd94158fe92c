// sweep_report.cpp - sweep rows as a table, CSV and two plot files.
#include "app/sweep_report.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "app/compare_report.hpp"
#include "app/report_header.hpp"
#include "cl/launch_timing.hpp"
#include "image/plot.hpp"
#include "util/csv.hpp"
#include "util/output_file.hpp"
#include "util/stats.hpp"

namespace clrt {

namespace {

using Figures = std::vector<std::pair<std::string, nlohmann::ordered_json>>;

// Appends a timing's columns, named by stats_columns()'s rule.
void add_stats(Figures& f, const std::string& prefix, const Stats& s, const std::vector<std::string>& fields) {
  for (const auto& [name, value] : stats_columns(prefix, s, fields)) f.emplace_back(name, value);
}

// The figures of one row, by name (one list for the CSV and the JSON).
Figures sweep_figures(const SweepRow& r) {
  const BenchResult& b = r.bench;
  Figures f{{"device", r.device}, {"depth", r.depth}};
  add_stats(f, "kernel_ms", b.kernel, {"median", "min", "max", "mean", "sd"});
  f.insert(f.end(), {{"kernel_n", b.kernel.n},
                     {"kernel_time_source", b.kernel_time_source()},
                     {"kernel_ms_delta", r.kernel_ms_delta}});
  add_stats(f, "frame_ms", b.frame, {"median", "mean", "sd"});
  f.insert(f.end(), {{"build_warm_ms", b.build_warm.median},
                     {"upload_ms", b.upload.median},
                     {"download_ms", b.download.median},
                     {"rays_primary", b.rays.primary},
                     {"rays_shadow", b.rays.shadow},
                     {"rays_reflection", b.rays.reflection},
                     {"rays_refraction", b.rays.refraction},
                     {"rays_total", b.rays.total()},
                     {"sphere_tests", b.rays.sphere_tests},
                     {"mrays_per_s", b.mrays_per_s},
                     {"ns_per_sphere_test", b.ns_per_sphere_test},
                     {"gflops", b.gflops},
                     {"reference_ms", r.reference_ms},
                     {"speedup_vs_reference", r.speedup_vs_reference},
                     {"omp_ms_median", b.omp.median},
                     {"opencl_speedup_vs_omp", b.speedup_vs_omp.median}});
  return f;
}

}  // namespace

std::string sweep_csv(const std::vector<SweepRow>& rows) {
  CsvTable t;
  std::map<std::string, ReportHeader> headers;  // per device: its driver
  for (const auto& r : rows) {
    if (!headers.count(r.device)) headers[r.device] = report_header(r.device);
    t.row();
    header_csv(t, headers[r.device]);
    for (auto& [k, v] : sweep_figures(r)) {
      if (v.is_string())
        t.set(k, v.get<std::string>());
      else if (v.is_number_float())
        t.set_number(k, v.get<double>());
      else
        t.set(k, v.dump());
    }
    comparison_csv(t, r.error, "error_");
    comparison_csv(t, r.change, "change_");
  }
  return t.text();
}

nlohmann::ordered_json sweep_json(const std::vector<SweepRow>& rows, const std::string& scene,
                                  const nlohmann::ordered_json& overrides, int mpi_ranks) {
  std::vector<std::string> devices;
  for (const auto& r : rows)
    if (std::find(devices.begin(), devices.end(), r.device) == devices.end()) devices.push_back(r.device);
  nlohmann::ordered_json out = header_json(report_header(devices));
  if (mpi_ranks > 1) out["mpi_ranks"] = mpi_ranks;
  out["scene"] = scene;
  out["overrides"] = overrides;
  if (!rows.empty()) {
    const BenchResult& b = rows.front().bench;
    out.update(nlohmann::ordered_json{{"width", b.width}, {"height", b.height}, {"spp", b.spp}, {"repeat", b.repeat}});
  }
  nlohmann::ordered_json arr = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (auto& [k, v] : sweep_figures(r)) j[k] = v;
    j["error"] = comparison_json(r.error);
    j["change"] = comparison_json(r.change);
    arr.push_back(j);
  }
  out["rows"] = arr;
  return out;
}

void print_sweep(const std::vector<SweepRow>& rows) {
  std::fprintf(report_stream(), "%-5s %10s %9s %12s %9s %9s %9s %8s %7s %8s %9s %9s  %s\n", "depth", "kernel_ms",
               "delta_ms", "rays", "Mrays/s", "ref_ms", "vs_ref", "differ", "off>1", "rmse", "changed", "chg_rmse",
               "device");
  for (const auto& r : rows) {
    const BenchResult& b = r.bench;
    std::fprintf(report_stream(), "%-5d %10.2f %+9.2f %12llu %9.1f %9.1f %8.1fx %8zu %7zu %8.4f %9zu %9.4f  %s\n",
                 r.depth, b.kernel.median, r.kernel_ms_delta, (unsigned long long)b.rays.total(), b.mrays_per_s,
                 r.reference_ms, r.speedup_vs_reference, r.error.differ, r.error.off_by_gt1, r.error.rmse_8bit,
                 r.change.differ, r.change.rmse_8bit, r.device.c_str());
  }
  for (const auto& r : rows)
    if (r.bench.host_timed_launches) {
      std::fprintf(report_stream(), "kernel_ms of %s%s\n", r.device.c_str(),
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

std::vector<PlotPanel> sweep_plot_panels(const std::vector<SweepRow>& rows, const std::string& title,
                                         std::vector<PlotPanel>* rays_panel) {
  // One series per device (by index and P:D: two devices of the same name
  // stay apart), labelled "name [P:D]" when names repeat.
  std::vector<std::pair<int, std::string>> keys;
  std::map<std::string, int> name_count;
  for (const auto& r : rows) {
    const auto key = std::make_pair(r.device_index, r.device_pd);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      keys.push_back(key);
      ++name_count[r.device];
    }
  }
  const size_t n = keys.size();
  std::vector<Series> time(n), error(n), rays(n);
  Series ref("reference (scalar double)", {}, {});
  ref.lines = true;
  ref.color = plot_color_for_name("reference");
  ref.marker = 1;
  std::map<int, bool> ref_seen;
  for (const auto& r : rows) {
    const size_t k =
        size_t(std::find(keys.begin(), keys.end(), std::make_pair(r.device_index, r.device_pd)) - keys.begin());
    const std::string label =
        r.device + (name_count[r.device] > 1
                        ? " [" + (r.device_pd.empty() ? "#" + std::to_string(r.device_index) : r.device_pd) + "]"
                        : "");
    for (Series* s : {&time[k], &error[k], &rays[k]}) {
      s->lines = true;
      s->color = plot_palette_color(k);
      s->marker = 0;
      s->x.push_back(r.depth);
    }
    time[k].name = "OpenCL kernel, " + label;
    time[k].y.push_back(r.bench.kernel.median);
    time[k].y_lo.push_back(r.bench.kernel.min);
    time[k].y_hi.push_back(r.bench.kernel.max);
    error[k].name = "RMSE vs reference, " + label;
    error[k].y.push_back(r.error.rmse_8bit);
    rays[k].name = "rays traced, " + label;
    rays[k].y.push_back(r.bench.rays.total() * 1e-6);
    if (!ref_seen[r.depth]) {
      ref_seen[r.depth] = true;
      ref.x.push_back(r.depth);
      ref.y.push_back(r.reference_ms);
    }
  }
  time.push_back(ref);
  PlotOptions po;
  po.x_from_zero = po.y_from_zero = po.integer_x = true;
  po.height = 480;
  std::vector<PlotPanel> panels{
      {title + ": time per depth", "recursion depth", "ms (median; bar: min-max)", time, po},
      {title + ": error per depth", "recursion depth", "RMSE vs reference (8-bit levels)", error, po}};
  if (rays_panel) *rays_panel = {{title + ": rays per depth", "recursion depth", "million rays", rays, po}};
  return panels;
}

std::string plot_sweep(const std::vector<SweepRow>& rows, const std::string& path, const std::string& title) {
  std::vector<PlotPanel> rays;
  write_plot(path, sweep_plot_panels(rows, title, &rays));
  const std::string rays_path = rays_plot_path(path);
  write_plot(rays_path, rays);
  return rays_path;
}

}  // namespace clrt

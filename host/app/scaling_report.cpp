// scaling_report.cpp - scaling rows as a table, CSV and a log-log plot.
#include "app/scaling_report.hpp"

#include <cstdio>
#include <sstream>

#include "app/report_header.hpp"
#include "cl/launch_timing.hpp"
#include "image/plot.hpp"
#include "util/csv.hpp"
#include "util/output_file.hpp"
#include "util/stats.hpp"

namespace clrt {

std::string scaling_csv(const std::vector<ScalingRow>& rows) {
  CsvTable t;
  const ReportHeader h = report_header(rows.empty() ? std::string() : rows.front().bench.device);
  for (const auto& r : rows) {
    const BenchResult& b = r.bench;
    const double per_million = r.spheres > 0 ? r.parse_ms * 1e-3 / (double(r.spheres) * 1e-6) : 0;
    t.row();
    header_csv(t, h);
    t.set("device", b.device);
    t.set_number("spheres", r.spheres);
    t.set_number("triangles", r.triangles);
    t.set_number("json_bytes", r.json_bytes);
    t.set_number("parse_ms", r.parse_ms);
    t.set_number("parse_s_per_million_spheres", per_million);
    t.set_number("bvh_build_ms", b.bvh_build_ms);
    t.set_number("bvh_bytes", b.bvh_bytes);
    t.set_number("bvh_depth", b.bvh_depth);
    t.set_number("width", b.width);
    t.set_number("height", b.height);
    t.set_number("depth", b.depth);
    t.set_number("rays_total", b.rays.total());
    t.set_number("sphere_tests", b.rays.sphere_tests);
    // A timing's median, mean and sd, named by stats_columns()'s rule.
    const auto set_spread = [&t](const std::string& prefix, const Stats& s) {
      for (const auto& [name, value] : stats_columns(prefix, s, {"median", "mean", "sd"})) t.set_number(name, value);
    };
    set_spread("frame_ms", b.frame);
    t.set_number("frame_n", b.frame.n);
    t.set_number("kernel_ms_median", b.kernel.median);
    t.set("kernel_time_source", b.kernel_time_source());
    t.set_number("ns_per_ray", r.ns_per_ray);
    set_spread("embree_ms", b.embree);
    t.set_number("embree_n", b.embree.n);
    t.set_number("embree_build_ms", b.embree_build_ms);
    t.set_number("embree_ns_per_ray", r.embree_ns_per_ray);
    set_spread("speedup_vs_embree", b.speedup_vs_embree);
    t.set_number("load_peak_bytes", r.load.peak_bytes);
    t.set_number("resident_bytes", r.resident_bytes);
    t.set_number("prepare_ms", r.prepare.ms);
    t.set_number("prepare_peak_bytes", r.prepare.peak_bytes);
    t.set_number("embree_build_once_ms", r.embree_build.ms);
    t.set_number("embree_build_peak_bytes", r.embree_build.peak_bytes);
    t.set_number("embree_vs_clrt_differ", b.embree_vs_clrt_differ);
  }
  return t.text();
}

namespace {

double mib(size_t bytes) {
  return double(bytes) / (1 << 20);
}

// The mesh scenes' load, clrt's preparation and the Embree tracer's build:
// time and the resident memory each added at its peak (N=1 each).
void print_mesh_loads(const std::vector<ScalingRow>& rows) {
  bool any = false;
  for (const auto& r : rows) any = any || r.triangles > 0;
  if (!any) return;
  std::fprintf(report_stream(),
               "\nmesh scenes, N=1 each: load = scene + OBJ file parsed; clrt prepare = hierarchy build + upload; "
               "Embree build = its scene from the loaded one; peak = resident memory the phase added at its peak\n");
  std::fprintf(report_stream(), "%10s %9s %9s %9s %11s %9s %9s %10s %10s %10s %9s\n", "triangles", "OBJ_MiB", "load_ms",
               "peak_MiB", "held_MiB", "prep_ms", "bvh_ms", "peak_MiB", "Embree_ms", "peak_MiB", "vs_clrt%");
  for (const auto& r : rows) {
    if (r.triangles == 0) continue;
    const BenchResult& b = r.bench;
    std::fprintf(report_stream(), "%10zu %9.1f %9.0f %9.0f %11.0f %9.0f %9.0f %10.0f %10.0f %10.0f %9.3f\n",
                 r.triangles, mib(r.json_bytes), r.load.ms, mib(r.load.peak_bytes), mib(r.resident_bytes), r.prepare.ms,
                 b.bvh_build_ms, mib(r.prepare.peak_bytes), r.embree_build.ms, mib(r.embree_build.peak_bytes),
                 b.embree_vs_clrt_differ >= 0 ? 100 * b.embree_vs_clrt_differ : -1.0);
  }
  std::fprintf(report_stream(),
               "held_MiB: the process's resident memory with the scene loaded; vs_clrt%%: pixels of the Embree "
               "image differing from clrt's by > 1 level\n");
}

}  // namespace

void print_scaling(const std::vector<ScalingRow>& rows) {
  if (rows.empty()) return;
  const BenchResult& first = rows.front().bench;
  std::fprintf(report_stream(), "%dx%d, depth %d, on %s; frame = every launch + download (median of N, mean ± sd)\n",
               first.width, first.height, first.depth, first.device.c_str());
  std::fprintf(report_stream(), "%9s %9s %8s %9s %7s %22s %9s %22s %9s %16s\n", "primitives", "parse_ms", "s/M",
               "bvh_ms", "bvh_MiB", "clrt frame ms", "ns/ray", "Embree frame ms", "ns/ray", "Embree/clrt");
  for (const auto& r : rows) {
    const BenchResult& b = r.bench;
    const size_t primitives = r.spheres + r.triangles;
    const double per_million = primitives > 0 ? r.parse_ms * 1e-3 / (double(primitives) * 1e-6) : 0;
    char clrt_ms[64], embree_ms[64], ratio[64];
    std::snprintf(clrt_ms, sizeof clrt_ms, "%.1f ± %.1f (N=%d)", b.frame.median, b.frame.sd, b.frame.n);
    if (b.embree.n > 0) {
      std::snprintf(embree_ms, sizeof embree_ms, "%.1f ± %.1f (N=%d)", b.embree.median, b.embree.sd, b.embree.n);
      std::snprintf(ratio, sizeof ratio, "%.2f ± %.2f", b.speedup_vs_embree.median, b.speedup_vs_embree.sd);
    } else {
      std::snprintf(embree_ms, sizeof embree_ms, "-");
      std::snprintf(ratio, sizeof ratio, "-");
    }
    std::fprintf(report_stream(), "%9zu%c %9.1f %8.2f %9.1f %7.2f %22s %9.0f %22s %9.0f %16s\n", primitives,
                 r.triangles ? 't' : 's', r.parse_ms, per_million, b.bvh_build_ms, double(b.bvh_bytes) / (1 << 20),
                 clrt_ms, r.ns_per_ray, embree_ms, r.embree_ns_per_ray, ratio);
  }
  std::fprintf(report_stream(),
               "Embree/clrt: Embree frame / clrt frame per round (> 1: clrt is faster); ns/ray: frame wall time / "
               "rays traced; s/M: parse seconds per million primitives (s: spheres, t: triangles)\n");
  print_mesh_loads(rows);
  for (const auto& r : rows)
    if (r.bench.host_timed_launches) {
      std::fprintf(report_stream(), "kernel times%s\n",
                   time_source_note(r.bench.host_timed_launches, r.bench.launches).c_str());
      break;
    }
}

void plot_scaling(const std::vector<ScalingRow>& rows, const std::string& path, const std::string& title) {
  Series clrt("clrt frame", {}, {}), embree("Embree frame (render only)", {}, {});
  clrt.lines = embree.lines = true;
  clrt.color = plot_color_for_name("clrt");
  embree.color = plot_color_for_name("Embree");
  embree.marker = 1;
  for (const auto& r : rows) {  // median, bars from the fastest to the slowest frame
    clrt.x.push_back(double(r.spheres + r.triangles));
    clrt.y.push_back(r.bench.frame.median);
    clrt.y_lo.push_back(r.bench.frame.min);
    clrt.y_hi.push_back(r.bench.frame.max);
    if (r.bench.embree.n > 0) {
      embree.x.push_back(double(r.spheres + r.triangles));
      embree.y.push_back(r.bench.embree.median);
      embree.y_lo.push_back(r.bench.embree.min);
      embree.y_hi.push_back(r.bench.embree.max);
    }
  }
  std::vector<Series> series{clrt};
  if (!embree.x.empty()) series.push_back(embree);
  PlotOptions po;
  po.log_x = po.log_y = true;
  std::string full_title = title;
  if (!rows.empty()) {
    const BenchResult& b = rows.front().bench;
    full_title +=
        " (" + std::to_string(b.width) + "x" + std::to_string(b.height) + ", depth " + std::to_string(b.depth) + ")";
  }
  write_plot(path, full_title, rows.empty() || rows.front().triangles == 0 ? "random spheres" : "triangles",
             "ms per frame (median; bar: min-max)", series, po);
}

}  // namespace clrt

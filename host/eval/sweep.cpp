// sweep.cpp - bench per depth and device, errors vs reference and vs the
// previous depth.
#include "eval/sweep.hpp"

#include <map>

#include "reference/reference.hpp"
#include "util/timer.hpp"

namespace clrt {

SweepReference sweep_reference(const Scene& scene, const SweepSettings& s, int depth) {
  SweepReference ref;
  const auto t0 = Clock::now();
  ref.image = render_reference(scene, s.bench.width, s.bench.height, depth, s.bench.sampling());
  ref.ms = ms_since(t0);
  return ref;
}

SweepRow sweep_row(const Scene& scene, const DeviceInfo& device, const RenderSettings& settings, const SweepSettings& s,
                   int depth) {
  BenchSettings b = s.bench;
  b.depth = depth;
  b.reference = false;
  b.peak = false;  // a property of the device, not of the depth: `clrt bench` measures it
  SweepRow row;
  row.device = device.name;
  row.device_index = device.index;
  row.device_pd = std::to_string(device.platform_index) + ":" + std::to_string(device.device_index);
  row.depth = depth;
  row.bench = run_bench(scene, {device}, settings, b);
  return row;
}

void sweep_compare(SweepRow& row, const SweepReference& ref, const Image* previous, double previous_kernel_ms) {
  row.reference_ms = ref.ms;
  if (row.bench.frame.median > 0) row.speedup_vs_reference = ref.ms / row.bench.frame.median;
  row.error = compare_images(row.bench.image, ref.image);
  if (previous) {
    row.change = compare_images(row.bench.image, *previous);
    row.kernel_ms_delta = row.bench.kernel.median - previous_kernel_ms;
  }
}

std::vector<SweepRow> run_sweep(const Scene& scene, const std::vector<DeviceInfo>& devices,
                                const RenderSettings& settings, const SweepSettings& s) {
  std::vector<SweepRow> rows;
  const int n_depths = s.depth_to - s.depth_from + 1;
  const int total = n_depths * int(devices.size());
  int done = 0;
  std::map<int, Image> previous;  // device index -> image at d-1
  std::map<int, double> previous_ms;
  for (int d = s.depth_from; d <= s.depth_to; ++d) {
    // The reference once per depth, shared by the devices.
    const SweepReference ref = sweep_reference(scene, s, d);
    for (size_t k = 0; k < devices.size(); ++k) {
      if (s.progress) s.progress(done, total, "depth " + std::to_string(d) + " on " + devices[k].name);
      SweepRow row = sweep_row(scene, devices[k], settings, s, d);
      const bool first = !previous.count(int(k));
      sweep_compare(row, ref, first ? nullptr : &previous[int(k)], first ? 0 : previous_ms[int(k)]);
      previous[int(k)] = std::move(row.bench.image);
      previous_ms[int(k)] = row.bench.kernel.median;
      row.bench.image = Image();
      rows.push_back(std::move(row));
      ++done;
    }
  }
  if (s.progress) s.progress(total, total, "done");
  return rows;
}

}  // namespace clrt

// sweep.cpp - bench per depth and device, errors vs reference and vs the
// previous depth.
#include "eval/sweep.hpp"

#include <map>

#include "reference/reference.hpp"
#include "util/timer.hpp"

namespace clrt {

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
    const auto t0 = Clock::now();
    Image ref = render_reference(scene, s.bench.width, s.bench.height, d, s.bench.sampling());
    double ref_ms = ms_since(t0);
    for (size_t k = 0; k < devices.size(); ++k) {
      if (s.progress) s.progress(done, total, "depth " + std::to_string(d) + " on " + devices[k].name);
      BenchSettings b = s.bench;
      b.depth = d;
      b.reference = false;
      b.peak = false;  // a property of the device, not of the depth: `clrt bench` measures it
      SweepRow row;
      row.device = devices[k].name;
      row.device_index = devices[k].index;
      row.device_pd = std::to_string(devices[k].platform_index) + ":" + std::to_string(devices[k].device_index);
      row.depth = d;
      row.bench = run_bench(scene, {devices[k]}, settings, b);
      row.reference_ms = ref_ms;
      if (row.bench.frame.median > 0) row.speedup_vs_reference = ref_ms / row.bench.frame.median;
      row.error = compare_images(row.bench.image, ref);
      if (previous.count(int(k))) {
        row.change = compare_images(row.bench.image, previous[int(k)]);
        row.kernel_ms_delta = row.bench.kernel.median - previous_ms[int(k)];
      }
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

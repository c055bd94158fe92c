// scaling.cpp - the scenes of `clrt scaling`, one after another (only one is
// in memory at a time: a million spheres take ~200 MB with its JSON text).
#include "eval/scaling.hpp"

#include "scene/random_scene.hpp"
#include "scene/scene_json.hpp"
#include "util/timer.hpp"

namespace clrt {

std::vector<ScalingRow> run_scaling(const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
                                    const ScalingSettings& s) {
  std::vector<ScalingRow> rows;
  const int total = static_cast<int>(s.counts.size());
  for (size_t count : s.counts) {
    if (s.progress) s.progress(static_cast<int>(rows.size()), total, std::to_string(count) + " spheres");
    ScalingRow row;
    row.spheres = count;
    RandomSceneSettings scene_settings;
    scene_settings.count = count;
    scene_settings.seed = s.seed;
    scene_settings.fill = s.fill;
    // What is rendered is what the file would give: the scene read back
    // (the generated scene and its text freed before the bench).
    Scene scene;
    {
      const std::string text = scene_to_json(random_scene(scene_settings), JsonStyle::Compact);
      row.json_bytes = text.size();
      const auto t0 = Clock::now();
      scene = parse_scene(text, "scaling");
      row.parse_ms = ms_since(t0);
    }
    BenchSettings bench = s.bench;
    if (bench.depth < 0) bench.depth = scene.recursion_depth;
    row.bench = run_bench(scene, devices, settings, bench);
    row.bench.image = Image();
    row.bench.reference_image = Image();
    const double rays = double(row.bench.rays.total());
    if (rays > 0) {
      row.ns_per_ray = row.bench.frame.median * 1e6 / rays;
      if (row.bench.embree.n > 0) row.embree_ns_per_ray = row.bench.embree.median * 1e6 / rays;
    }
    rows.push_back(std::move(row));
  }
  if (s.progress) s.progress(total, total, "done");
  return rows;
}

}  // namespace clrt

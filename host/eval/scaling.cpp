// scaling.cpp - the scenes of `clrt scaling`, one after another (only one is
// in memory at a time: a million spheres take ~200 MB with its JSON text).
#include "eval/scaling.hpp"

#include <malloc.h>
#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "embree_tracer.hpp"
#include "scene/mesh_grid.hpp"
#include "scene/random_scene.hpp"
#include "scene/scene_json.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"
#include "util/memory_use.hpp"
#include "util/output_file.hpp"
#include "util/timer.hpp"

namespace clrt {

namespace {

// The bench of `scene` into `row`, images dropped, with ns per ray.
void bench_row(const Scene& scene, const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
               const ScalingSettings& s, ScalingRow& row) {
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
}

ScalingRow sphere_row(size_t count, const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
                      const ScalingSettings& s) {
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
  bench_row(scene, devices, settings, s, row);
  return row;
}

// A folder of our own under the system's temporary one, removed with
// everything in it when done.
struct TemporaryFolder {
  std::filesystem::path path;
  TemporaryFolder() {
    std::string name = (std::filesystem::temp_directory_path() / "clrt-scaling-XXXXXX").string();
    if (!::mkdtemp(name.data()))
      throw UserError("cannot make a temporary folder for the mesh scenes: " + std::string(std::strerror(errno)));
    path = name;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// Runs `phase`, timed, with the peak resident memory it adds. Memory freed
// before it is first handed back to the system (malloc_trim), so that the
// phase's allocations show as growth rather than reuse.
template <class Phase>
PhaseCost measure(const Phase& phase) {
  ::malloc_trim(0);
  const bool reset = reset_peak_resident();
  const size_t before = resident_bytes();
  const auto t0 = Clock::now();
  phase();
  PhaseCost cost;
  cost.ms = ms_since(t0);
  const size_t peak = peak_resident_bytes();
  cost.peak_bytes = reset && peak > before ? peak - before : 0;
  return cost;
}

ScalingRow mesh_row(size_t count, const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
                    const ScalingSettings& s) {
  ScalingRow row;
  TemporaryFolder folder;
  const std::filesystem::path scene_file = folder.path / "scene.json";
  {
    const MeshGrid grid = torus_grid(count, "grid.obj");
    row.triangles = grid.triangles;
    row.json_bytes = grid.obj.size() + grid.scene_json.size();
    write_text_atomic((folder.path / "grid.obj").string(), grid.obj, "mesh");
    write_text_atomic(scene_file.string(), grid.scene_json, "scene");
  }
  Scene scene;
  row.load = measure([&] { scene = load_scene(scene_file.string()); });
  row.parse_ms = row.load.ms;
  row.resident_bytes = resident_bytes();
  const int depth = s.bench.depth < 0 ? scene.recursion_depth : s.bench.depth;
  // The kernel's program built first (a compiler's memory and seconds are
  // no part of the scene's cost): the measured preparation finds it made.
  double program_ms = 0;
  {
    Renderer renderer(devices, settings);
    renderer.prepare(scene, s.bench.width, s.bench.height, depth, s.bench.sampling());
  }
  row.prepare = measure([&] {
    Renderer renderer(devices, settings);
    renderer.prepare(scene, s.bench.width, s.bench.height, depth, s.bench.sampling());
    program_ms = renderer.stats().build_ms;
  });
  row.prepare.ms -= program_ms;
  if (s.bench.embree && !kLeanBuild) {
    std::vector<uint8_t> pixel;
    clrt_bench::EmbreeBuildInfo info;
    row.embree_build = measure([&] { clrt_bench::embree_render(scene, 1, 1, depth, pixel, &info); });
    row.embree_build.ms = info.build_ms;  // the build alone, as bench reports it
  }
  bench_row(scene, devices, settings, s, row);
  return row;
}

}  // namespace

std::vector<ScalingRow> run_scaling(const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
                                    const ScalingSettings& s) {
  std::vector<ScalingRow> rows;
  const int total = static_cast<int>(s.counts.size() + s.triangles.size());
  for (size_t count : s.counts) {
    if (s.progress) s.progress(static_cast<int>(rows.size()), total, std::to_string(count) + " spheres");
    rows.push_back(sphere_row(count, devices, settings, s));
  }
  for (size_t count : s.triangles) {
    if (s.progress) s.progress(static_cast<int>(rows.size()), total, std::to_string(count) + " triangles");
    rows.push_back(mesh_row(count, devices, settings, s));
  }
  if (s.progress) s.progress(total, total, "done");
  return rows;
}

}  // namespace clrt

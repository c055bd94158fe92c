// scaling.hpp - `clrt scaling`: how a frame's cost grows with the number of
// spheres or triangles. Random-sphere scenes (scene/random_scene.hpp) of
// each count are made in memory, loaded back from their JSON text (the
// parser timed), and benchmarked like `clrt bench`: clrt's frame against
// the Embree tracer's in alternating rounds, with the hierarchy's build time
// and size. Mesh scenes (scene/mesh_grid.hpp) are written as files (a scene
// and one OBJ) into a temporary folder and loaded from there; their load,
// clrt's preparation (hierarchy build and upload) and the Embree tracer's
// build are each timed once with the growth of resident memory they cause.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "eval/bench.hpp"

namespace clrt {

// The time and resident memory of one phase (N=1): `peak_bytes` is the
// process's peak during it above its resident size when it began (0 when
// the peak could not be reset, util/memory_use.hpp).
struct PhaseCost {
  double ms = 0;
  size_t peak_bytes = 0;
};

struct ScalingRow {
  size_t spheres = 0;     // random spheres (the book's floor comes on top)
  size_t triangles = 0;   // a mesh scene's triangles (spheres is then 0)
  size_t json_bytes = 0;  // the scene as compact JSON (with a mesh scene: and its OBJ file)
  double parse_ms = 0;    // N=1: parse_scene() of that text (with a mesh scene: load_scene(), OBJ included)
  // Mesh scenes only (N=1 each): the load (parse_ms), clrt's renderer
  // prepared (hierarchy build and upload, without the kernel program's
  // build or cache load; the hierarchy alone in bench.bvh_build_ms), and
  // the Embree tracer's scene built (one 1 x 1 frame).
  PhaseCost load, prepare, embree_build;
  size_t resident_bytes = 0;     // the process's resident memory with the scene loaded
  BenchResult bench;             // images dropped
  double ns_per_ray = 0;         // median clrt frame / rays traced (wall time, all devices)
  double embree_ns_per_ray = 0;  // median Embree frame / the same ray count (0 without Embree)
};

// Called before each scene with the rows done so far, and once with done ==
// total at the end; `what` names the scene about to run ("done" at the end).
using ScalingProgress = std::function<void(int done, int total, const std::string& what)>;

struct ScalingSettings {
  std::vector<size_t> counts;     // spheres per scene, in the order run
  std::vector<size_t> triangles;  // triangles per mesh scene, run after the sphere scenes
  uint64_t seed = 5;
  double fill = 0.05;
  BenchSettings bench;  // depth < 0: the scenes' recursion depth (3)
  ScalingProgress progress;
};

std::vector<ScalingRow> run_scaling(const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
                                    const ScalingSettings& s);

}  // namespace clrt

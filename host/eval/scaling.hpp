// scaling.hpp - `clrt scaling`: how a frame's cost grows with the number of
// spheres. Random-sphere scenes (scene/random_scene.hpp) of each count are
// made in memory, loaded back from their JSON text (the parser timed), and
// benchmarked like `clrt bench`: clrt's frame against the Embree tracer's in
// alternating rounds, with the hierarchy's build time and size.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "eval/bench.hpp"

namespace clrt {

struct ScalingRow {
  size_t spheres = 0;            // random spheres (the book's floor comes on top)
  size_t json_bytes = 0;         // the scene as compact JSON
  double parse_ms = 0;           // N=1: parse_scene() of that text
  BenchResult bench;             // images dropped
  double ns_per_ray = 0;         // median clrt frame / rays traced (wall time, all devices)
  double embree_ns_per_ray = 0;  // median Embree frame / the same ray count (0 without Embree)
};

// Called before each scene with the rows done so far, and once with done ==
// total at the end; `what` names the scene about to run ("done" at the end).
using ScalingProgress = std::function<void(int done, int total, const std::string& what)>;

struct ScalingSettings {
  std::vector<size_t> counts;  // spheres per scene, in the order run
  uint64_t seed = 5;
  double fill = 0.05;
  BenchSettings bench;  // depth < 0: the scenes' recursion depth (3)
  ScalingProgress progress;
};

std::vector<ScalingRow> run_scaling(const std::vector<DeviceInfo>& devices, const RenderSettings& settings,
                                    const ScalingSettings& s);

}  // namespace clrt

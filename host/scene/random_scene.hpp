// random_scene.hpp - scenes of any size for tests and benchmarks: N random
// spheres in a cube in front of the camera, above the book's floor, lit by
// the book's three lights. The same (count, seed, fill) gives the same scene
// on every machine (a fixed generator, no std distributions). Values are
// multiples of 1/64 (colours and exponents whole numbers), so that a scene
// written to JSON reads back exactly and briefly.
#pragma once
#include <cstdint>

#include "scene/scene.hpp"

namespace clrt {

// Most spheres a generated scene has: its file (compact JSON, about 120
// bytes a sphere: 2 000 000 spheres take 229 MiB) stays within the loader's
// limit, kMaxSceneBytes (256 MiB), and kMaxSceneSpheres.
constexpr size_t kMaxGeneratedSpheres = 2000000;

struct RandomSceneSettings {
  size_t count = 1000;  // spheres, besides the floor
  uint64_t seed = 1;
  // Fraction of the cube's volume the spheres fill (their sum, overlaps
  // counted twice): the density stays the same at every count.
  double fill = 0.05;
};

Scene random_scene(const RandomSceneSettings& settings);

}  // namespace clrt

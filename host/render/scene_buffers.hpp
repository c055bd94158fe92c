// scene_buffers.hpp - packs a Scene into the layouts of kernels/clrt_layout.h.
#pragma once
#include <vector>

#include "clrt_layout.h"
#include "render/precision.hpp"
#include "scene/scene.hpp"

namespace clrt {

struct SceneData {
  clrt_params params{};
  std::vector<clrt_sphere> spheres;
  std::vector<clrt_light> lights;
};

// Robust and fast modes are camera-relative: the host subtracts the camera
// position in double before rounding to float, so geometry near the camera
// keeps full float precision wherever the scene sits in world space.
bool camera_relative(Precision p);

SceneData pack_scene(const Scene& scene, Precision precision, int width, int height, int depth);

}  // namespace clrt

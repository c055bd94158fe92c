// flat_scene.hpp - a small scene of every primitive kind, for the tests of
// planes and triangles and of what works on any primitive (subsampling).
#pragma once
#include "scene/scene.hpp"
#include "scene/scene_json.hpp"

namespace clrt_test {

// A reflective plane floor, a sphere, a tilted plane far behind and two
// triangles (one leaning over the floor, one standing on it but clear of
// it: no primitive touches another, so no pixel's nearest hit is a tie).
inline clrt::Scene flat_scene() {
  return clrt::parse_scene(R"({"camera": {"position": [0, 0.5, -1]}, "background": [20, 30, 50],
      "spheres": [{"center": [-1.5, 0, 4], "radius": 1, "color": [255, 0, 0], "specular": 500, "reflective": 0.2}],
      "planes": [{"point": [0, -1, 0], "normal": [0, 2, 0], "color": [200, 200, 100], "specular": 1000,
                  "reflective": 0.3},
                 {"point": [0, 0, 30], "normal": [0.2, 0.1, -1], "color": [90, 90, 200]}],
      "triangles": [{"vertices": [[0.5, -0.9, 5], [2.5, -0.9, 5], [1.5, 1.5, 5.5]], "color": [0, 128, 255],
                     "specular": 100, "reflective": 0.1},
                    {"vertices": [[-0.5, 0.8, 3], [0.4, 1.2, 3.5], [-0.2, 0.2, 2.5]], "color": [255, 255, 255],
                     "reflective": 0.6}],
      "lights": [{"type": "ambient", "intensity": 0.2}, {"type": "point", "intensity": 0.6, "position": [2, 1, 0]},
                 {"type": "directional", "intensity": 0.2, "direction": [1, 4, 4]}]})",
                           "flat");
}

}  // namespace clrt_test

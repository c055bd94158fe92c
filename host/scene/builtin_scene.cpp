// builtin_scene.cpp - the demo scene (same values as scenes/cgfs-demo.json).
#include "scene/builtin_scene.hpp"

#include "scene/scene_json.hpp"

namespace clrt {

Scene builtin_demo_scene() {
  static const char* kDemo = R"({
    "camera": {"position": [0, 0, 0], "viewport": [1, 1], "projection_plane_d": 1},
    "background": [0, 0, 0], "recursion_depth": 3,
    "spheres": [
      {"center": [0, -1, 3], "radius": 1, "color": [255, 0, 0], "specular": 500, "reflective": 0.2},
      {"center": [-2, 0, 4], "radius": 1, "color": [0, 255, 0], "specular": 10, "reflective": 0.4},
      {"center": [2, 0, 4], "radius": 1, "color": [0, 0, 255], "specular": 500, "reflective": 0.3},
      {"center": [0, -5001, 0], "radius": 5000, "color": [255, 255, 0], "specular": 1000, "reflective": 0.5}],
    "lights": [
      {"type": "ambient", "intensity": 0.2},
      {"type": "point", "intensity": 0.6, "position": [2, 1, 0]},
      {"type": "directional", "intensity": 0.2, "direction": [1, 4, 4]}]})";
  return parse_scene(kDemo, "built-in demo scene");
}

}  // namespace clrt

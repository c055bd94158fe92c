// scene.hpp - the scene model (double precision) and its JSON loader.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "vec3.hpp"

namespace clrt {

struct Sphere {
  Vec3 center;
  double radius = 1;
  Vec3 color;               // 0..255
  double specular = -1;     // -1 = matte
  double reflective = 0;    // 0..1
};

enum class LightType { Ambient, Point, Directional };

struct Light {
  LightType type = LightType::Ambient;
  double intensity = 0;
  Vec3 vec;  // position (point) or direction (directional)
};

struct Camera {
  Vec3 position;
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
  double viewport_w = 1, viewport_h = 1;
  double projection_plane_d = 1;
};

struct Scene {
  Camera camera;
  Vec3 background;
  int recursion_depth = 3;
  double epsilon = 0.001;
  std::vector<Sphere> spheres;
  std::vector<Light> lights;
};

// Parses and validates a scene; throws UserError("<name>: <path>: <problem>").
Scene parse_scene(const std::string& json_text, const std::string& name);
// Largest scene file load_scene() accepts.
constexpr size_t kMaxSceneBytes = size_t(64) << 20;
// Reads a file and parses it; a missing/unreadable/oversized file is a UserError.
Scene load_scene(const std::string& path);
// Serializes a scene back to JSON text (used by generated test suites).
std::string scene_to_json(const Scene& s);

}  // namespace clrt

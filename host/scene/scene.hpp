// scene.hpp - the scene model (double precision) and the range every engine
// renders; scene_json.hpp reads and writes it.
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "util/vec3.hpp"

namespace clrt {

struct Sphere {
  Vec3 center;
  double radius = 1;
  Vec3 color;             // 0..255
  double specular = -1;   // -1 = matte
  double reflective = 0;  // 0..1
  // Chapter 5's transparency and refraction: the share of the light that
  // is not reflected which passes through the surface (0..1), and the
  // refractive index of the sphere's inside (1 = no bending, the book's
  // plain transparency). reference/reference.hpp states how they combine.
  double transparency = 0;
  double refractive_index = 1;
};

// The material of a plane or triangle (chapter 5's other primitives): the
// sphere's shading fields. Planes and triangles are opaque (no transparency).
struct Material {
  Vec3 color;             // 0..255
  double specular = -1;   // -1 = matte
  double reflective = 0;  // 0..1
};

// An infinite plane: the points P with dot(normal, P) = dot(normal, point).
// `normal` is not unit length (the parser rescales it by a power of two; the
// engines normalize it where they shade); both sides are surfaces (the
// normal is turned toward the ray when shading).
struct Plane {
  Vec3 point;
  Vec3 normal;
  Material material;
};

// A triangle (inline, or one face of an OBJ mesh after its transform):
// vertices in the scene's coordinates, flat shaded with the geometric normal
// turned toward the ray, both sides visible.
struct Triangle {
  Vec3 v0, v1, v2;
  Material material;
};

enum class LightType { Ambient, Point, Directional };

struct Light {
  LightType type = LightType::Ambient;
  double intensity = 0;
  Vec3 vec;  // position (point) or direction (directional)
  // Directional: the scene gave vec x 2^scale_exponent (the parser rescales
  // a direction by a power of two so that no length over- or underflows).
  // The book's shadow ray covers [epsilon, inf) in units of the direction
  // it was given, so along vec it starts at epsilon x 2^scale_exponent: the
  // same points, exactly (a power of two), as the book's.
  int scale_exponent = 0;
  double shadow_t_min(double epsilon) const { return std::ldexp(epsilon, scale_exponent); }
  Vec3 given_vec() const {
    return {std::ldexp(vec.x, scale_exponent), std::ldexp(vec.y, scale_exponent), std::ldexp(vec.z, scale_exponent)};
  }
};

struct Camera {
  Vec3 position;
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
  double viewport_w = 1, viewport_h = 1;
  double projection_plane_d = 1;
  // "aspect": "image": the viewport's shape follows the image's
  // (scene/viewport.hpp); false ("viewport", the default): the book's
  // viewport as given, stretched to any image.
  bool aspect_from_image = false;
};

struct Scene {
  Camera camera;
  Vec3 background;
  int recursion_depth = 3;
  double epsilon = 0.001;
  std::vector<Sphere> spheres;
  std::vector<Light> lights;
  std::vector<Plane> planes;
  // Inline triangles and every mesh's faces (scene_json.cpp loads the OBJ
  // files, render/mesh ... see obj_mesh.hpp), in file order.
  std::vector<Triangle> triangles;
};

// The range every engine and precision renders without overflow or
// underflow (so without NaN/Inf): every coordinate within ±kMaxLength, every
// size (radius, viewport, projection distance) in [kMinLength, kMaxLength],
// the camera's ray directions (rotation × viewport/projection distance)
// within kMaxLength, specular exponents up to kMaxSpecular, the sum of all
// light intensities up to kMaxTotalIntensity. Why these numbers: the kernels
// compute in float32 (fp64 builds receive scene values as float hi + lo
// pairs), where squares of differences of two coordinates must stay below
// FLT_MAX ~ 3.4e38 and squares of sizes above FLT_MIN ~ 1.2e-38: 1e8 leaves
// them 1e16 and 1e-16, with room for the quadratic's b^2 - 4ac. The parser
// rejects anything outside, naming the value and the limit.
constexpr double kMaxLength = 1e8, kMinLength = 1e-8;
constexpr double kMaxSpecular = 1e8, kMaxTotalIntensity = 1e30;
// Refractive indices: physical ones lie in [1, ~4]; relative indices below 1
// (an air bubble in water) are allowed down to kMinRefractiveIndex.
constexpr double kMinRefractiveIndex = 0.1, kMaxRefractiveIndex = 10;

}  // namespace clrt

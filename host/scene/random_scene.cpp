// random_scene.cpp - the random-sphere scene generator.
#include "scene/random_scene.hpp"

#include <algorithm>
#include <cmath>

namespace clrt {
namespace {

// SplitMix64: small, fast, and the same sequence everywhere.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1), 53 bits.
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  // The same, rounded to a multiple of 1/64.
  double coarse(double low, double high) { return std::round(uniform(low, high) * 64) / 64; }

 private:
  uint64_t state_;
};

}  // namespace

Scene random_scene(const RandomSceneSettings& settings) {
  Random random(settings.seed);
  Scene scene;
  scene.recursion_depth = 3;
  // Spheres of radius 0.1 to 0.3; the cube's edge keeps the fill constant.
  const double mean_volume = 4.0 / 3.0 * M_PI * 0.2 * 0.2 * 0.2 * 1.3;  // E[r^3] of U(0.1, 0.3) ~ 1.3 * 0.2^3
  const double fill = std::clamp(settings.fill, 1e-6, 1.0);
  const double edge = std::max(2.0, std::cbrt(double(settings.count) * mean_volume / fill));
  // The camera looks down +z at the cube's centre from one edge away.
  scene.camera.position = {0, std::round(edge * 32) / 64, -std::round(edge * 64) / 64};
  for (size_t i = 0; i < settings.count; ++i) {
    Sphere s;
    s.center = {random.coarse(-edge / 2, edge / 2), random.coarse(0.3, edge), random.coarse(0, edge)};
    s.radius = random.coarse(0.1, 0.3);
    s.color = {std::floor(random.uniform(0, 256)), std::floor(random.uniform(0, 256)),
               std::floor(random.uniform(0, 256))};
    s.specular = random.uniform() < 0.25 ? -1 : std::floor(random.uniform(10, 1000));
    s.reflective = random.uniform() < 0.5 ? 0 : random.coarse(0, 0.5);
    scene.spheres.push_back(s);
  }
  // The book's floor and lights.
  scene.spheres.push_back({{0, -5000, 0}, 5000, {255, 255, 0}, 1000, 0.5});
  scene.lights.push_back({LightType::Ambient, 0.2, {}});
  scene.lights.push_back(
      {LightType::Point, 0.6, {std::round(edge * 16) / 64, std::round(edge * 96) / 64, -std::round(edge * 32) / 64}});
  scene.lights.push_back({LightType::Directional, 0.2, {0.125, 0.5, 0.5}});
  return scene;
}

}  // namespace clrt

// conditioning.cpp - the per-sphere choice of compensated arithmetic.
#include "render/conditioning.hpp"

namespace clrt {

double uncompensated_error(const Sphere& sphere, Vec3 camera) {
  return kFloatRoundoff * (3 * sphere.radius + length(sphere.center - camera));
}

bool needs_compensation(const Sphere& sphere, const Scene& scene) {
  return !(kCompensationSafety * uncompensated_error(sphere, scene.camera.position) <= scene.epsilon);
}

}  // namespace clrt

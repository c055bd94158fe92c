// viewport.cpp - fitting the viewport to the image (viewport.hpp).
#include "scene/viewport.hpp"

#include <algorithm>
#include <cmath>

namespace clrt {

Camera camera_for_image(const Camera& camera, int width, int height) {
  if (!camera.aspect_from_image || width <= 0 || height <= 0) return camera;
  Camera fitted = camera;
  const double side = std::max(camera.viewport_w, camera.viewport_h);
  if (width >= height) {
    fitted.viewport_w = side;
    fitted.viewport_h = side * height / width;
  } else {
    fitted.viewport_h = side;
    fitted.viewport_w = side * width / height;
  }
  return fitted;
}

double pixel_aspect(const Camera& camera, int width, int height) {
  return (camera.viewport_w / width) / (camera.viewport_h / height);
}

bool square_pixels(const Camera& camera, int width, int height) {
  return std::fabs(pixel_aspect(camera, width, height) - 1) <= 1e-9;
}

}  // namespace clrt

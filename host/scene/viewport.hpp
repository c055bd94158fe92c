// viewport.hpp - the camera's viewport against the image's size. The book
// maps a W x H canvas onto a viewport of Vw x Vh whatever their shapes
// (CanvasToViewport), so pixels are square only when Vw / Vh = W / H: the
// book's scenes, with a 1 x 1 viewport, are stretched at 1920 x 1080. A
// camera with `"aspect": "image"` (Camera::aspect_from_image, or --aspect
// image) keeps its viewport's larger side and derives the other from the
// image, so its pixels are square at any size.
#pragma once
#include "scene/scene.hpp"

namespace clrt {

// The camera the engines render `width` x `height` with: `camera` itself,
// or with aspect_from_image its viewport fitted to the image (the larger
// side kept; the image's longer side gets it).
Camera camera_for_image(const Camera& camera, int width, int height);

// Width over height of a pixel on the viewport: (Vw / W) / (Vh / H); 1 for
// square pixels.
double pixel_aspect(const Camera& camera, int width, int height);

// Whether the pixels are square within rounding (|pixel_aspect - 1| <= 1e-9).
bool square_pixels(const Camera& camera, int width, int height);

}  // namespace clrt

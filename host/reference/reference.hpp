// reference.hpp - the oracle: a scalar, recursive, double-precision, literal
// translation of the book's ray tracer (Computer Graphics from Scratch,
// chapters 2-5, and its web demo). Deliberately independent of the kernel.
#pragma once
#include "image/image.hpp"
#include "scene/scene.hpp"

namespace clrt {

// Renders width x height at the given recursion depth (the scene's own
// recursion_depth is ignored; callers pass it when they want it).
Image render_reference(const Scene& scene, int width, int height, int depth);

}  // namespace clrt

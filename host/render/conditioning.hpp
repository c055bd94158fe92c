// conditioning.hpp - which spheres the robust kernel tests with compensated
// (float-float) arithmetic: the one rule, from each sphere's conditioning.
#pragma once
#include "scene/scene.hpp"

namespace clrt {

// float32's unit roundoff (half an ulp of 1).
constexpr double kFloatRoundoff = 0x1p-24;

// How far below the scene's epsilon a sphere's uncompensated error must stay
// (see needs_compensation()).
constexpr double kCompensationSafety = 16;

// The error of the uncompensated float32 ray-sphere test, as a distance from
// the sphere's surface, for a ray origin O within reach of that surface:
//   u (3 r + |C|),
// C the centre relative to the camera (the robust kernel's coordinates,
// packing_origin() in scene_buffers.hpp), r the radius, u = kFloatRoundoff.
// Why: the test computes f = O - C and c = |f|^2 - r^2 in float32. Near the
// surface |f| ~ r, and c is the difference of two numbers near r^2: rounding C
// to float (u |C|) and the subtraction (u |f|) move f by u (|C| + r), which
// moves c by 2r times that; the three squares, their sum and r^2 add 4 u r^2.
// c is 2r times O's height over the surface, so the height is off by
// u (|C| + r) + 2 u r. (The discriminant is not part of it: the cheap path
// computes it from |f x D|, whose error, u |f| in the ray's distance from the
// centre, is what the compensated path has too.)
double uncompensated_error(const Sphere& sphere, Vec3 camera);

// Whether the robust kernel must test `sphere` with compensated arithmetic:
// kCompensationSafety * uncompensated_error() > scene.epsilon.
// Why epsilon: a ray that leaves a point within that error of the surface
// (a hit on another sphere touching this one, the camera, a light) can find
// a root of this sphere at t ~ error / |D| on the wrong side of the
// surface. Secondary rays ignore roots below epsilon, so an error well below
// epsilon decides nothing, and compensating it changes no pixel; compensated
// arithmetic brings it down to the rounding of O itself (u |O|).
// The factor 16 covers directions shorter than 1 and rays that meet the
// surface at a slant. The book's demo (epsilon 1e-3): the floor
// (r = 5000, |C| = 5001) has an error of 1.2e-3, 19x over the bound of
// 6.25e-5; the unit spheres (|C| <= 4.5) at most 4.5e-7, 140x under it.
// Scale-invariant: the error and epsilon are both lengths, so a scene scaled
// by k (epsilon too) gets the same decisions; moving the whole scene changes
// nothing either, the coordinates being camera-relative. An epsilon <= 0
// compensates every sphere.
bool needs_compensation(const Sphere& sphere, const Scene& scene);

}  // namespace clrt

// ray_tree.cpp - the largest ray tree a camera ray can grow, and the weight
// cut-off that bounds it (ray_tree.hpp; the derivation is docs/reference/limits.md).
#include "scene/ray_tree.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace clrt {

namespace {

// The shares a hit on each surface passes to its children: pairs for the
// surfaces whose rays branch (both shares > 0), and the largest single share
// of any child (total internal reflection sends r + (1 - r) t one way).
struct Shares {
  std::vector<std::pair<double, double>> pairs;
  double largest = 0;
  bool reflects = false;  // any child at all
};

Shares scene_shares(const Scene& scene) {
  Shares s;
  const auto single = [&](double share) {
    s.largest = std::max(s.largest, share);
    s.reflects |= share > 0;
  };
  for (const Sphere& sp : scene.spheres) {
    const double r = sp.reflective, refracted = (1 - r) * sp.transparency;
    single(r);
    single(refracted);
    if (sp.transparency > 0) single(r + refracted);  // total internal reflection
    if (r > 0 && refracted > 0) s.pairs.emplace_back(r, refracted);
  }
  for (const Plane& p : scene.planes) single(p.material.reflective);
  for (const Triangle& t : scene.triangles) single(t.material.reflective);
  return s;
}

// The smallest alpha in [0, 1] with a^alpha + b^alpha <= 1 (the sum falls
// from 2 at alpha = 0 to a + b <= 1 at alpha = 1); the upper end of the
// bisection, so that the inequality holds at the value returned.
double pair_exponent(double a, double b) {
  if (a + b >= 1) return 1;
  double lo = 0, hi = 1;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = (lo + hi) / 2;
    (std::pow(a, mid) + std::pow(b, mid) > 1 ? lo : hi) = mid;
  }
  return hi;
}

// The largest colour channel a ray can return. A hit's local colour is its
// colour (<= 255) times the light it receives, at most: every ambient
// intensity, plus each point or directional light's intensity once for the
// diffuse term (cos <= 1) and once more for the specular one (a cosine to a
// power >= 0, <= 1) when any surface is shiny. Nothing is clamped before the
// pixel's final rounding, so a ray's colour (a blend of local colours and the
// background, shares adding up to at most 1) stays below the largest of
// these and of the background.
double max_colour(const Scene& scene) {
  bool shiny = false;
  double colour = std::max({scene.background.x, scene.background.y, scene.background.z});
  double surface = 0;
  const auto material = [&](const Vec3& c, double specular) {
    shiny |= specular != -1;
    surface = std::max({surface, c.x, c.y, c.z});
  };
  for (const Sphere& s : scene.spheres) material(s.color, s.specular);
  for (const Plane& p : scene.planes) material(p.material.color, p.material.specular);
  for (const Triangle& t : scene.triangles) material(t.material.color, t.material.specular);
  double light = 0;
  for (const Light& l : scene.lights) light += l.type == LightType::Ambient ? l.intensity : l.intensity * (shiny ? 2 : 1);
  return std::max(colour, surface * light);
}

}  // namespace

RayCut ray_cut(const Scene& scene) {
  RayCut cut;
  const Shares shares = scene_shares(scene);
  for (const auto& [a, b] : shares.pairs) cut.exponent = std::max(cut.exponent, pair_exponent(a, b));
  cut.max_colour = max_colour(scene);
  if (cut.exponent >= 1) return cut;  // nothing can be cut with a guarantee
  const double mass = cut.max_colour > kRayCutLevels ? kRayCutLevels / cut.max_colour : 1;
  const double weight = std::pow(mass, 1 / (1 - cut.exponent));
  float rounded = static_cast<float>(weight);
  if (double(rounded) > weight) rounded = std::nextafter(rounded, 0.0f);
  // Float kernels may flush subnormal weights to zero (-cl-denorms-are-zero):
  // a cut there would not be the reference's.
  cut.min_weight = rounded >= FLT_MIN ? rounded : 0.0f;
  return cut;
}

double worst_rays_per_camera_ray(const Scene& scene, int depth, bool cut) {
  const Shares shares = scene_shares(scene);
  if (depth <= 0 || !shares.reflects) return 1;
  const bool branches = !shares.pairs.empty();
  double per_level = HUGE_VAL;  // rays of one level that pass the cut
  int levels = depth;           // the deepest level a ray can reach
  if (cut) {
    const RayCut c = ray_cut(scene);
    if (c.min_weight > 0) {
      per_level = std::floor(std::pow(double(c.min_weight), -c.exponent));
      if (shares.largest < 1)  // a ray of level L weighs at most largest^L
        levels = int(std::min<double>(depth, std::floor(std::log(double(c.min_weight)) / std::log(shares.largest) + 1e-9)));
    }
  }
  double rays = 0;
  for (int level = 0; level <= levels; ++level)
    rays += std::min(branches ? std::ldexp(1.0, level) : 1.0, per_level);
  return rays;
}

double worst_rays_per_frame(const Scene& scene, int depth, int width, int height, int spp, bool cut) {
  return worst_rays_per_camera_ray(scene, depth, cut) * double(width) * double(height) * double(spp) * double(spp);
}

std::string ray_tree_warning(const Scene& scene, int depth, int width, int height, int spp, bool cut) {
  const double frame = worst_rays_per_frame(scene, depth, width, height, spp, cut);
  if (frame < kRayWarningThreshold) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "a camera ray may branch into up to %.3g rays at depth %d (a surface both reflects and refracts): "
                "up to %.3g rays in this %dx%d frame, hours of work or more; a lower --depth bounds it",
                worst_rays_per_camera_ray(scene, depth, cut), depth, frame, width, height);
  return text;
}

std::string ray_budget_error(const Scene& scene, int depth, int width, int height, int spp, double budget, bool cut) {
  const double frame = worst_rays_per_frame(scene, depth, width, height, spp, cut);
  if (!(frame > budget)) return "";
  char text[400];
  std::snprintf(text, sizeof text,
                "a camera ray may branch into up to %.3g rays at depth %d%s: up to %.3g rays in this %dx%d frame, "
                "over the ray budget of %.3g (--ray-budget); a lower --depth bounds it",
                worst_rays_per_camera_ray(scene, depth, cut), depth,
                cut && ray_cut(scene).min_weight > 0 ? " even with the weight cut-off"
                                                      : " (a surface passes all of its light on to two rays: no cut-off)",
                frame, width, height, budget);
  return text;
}

}  // namespace clrt

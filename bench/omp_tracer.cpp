// omp_tracer.cpp - the book's TraceRay in float (whitted_float.hpp), its two
// queries a loop over every sphere and plane (triangles are the Embree
// tracer's only: eval/bench.cpp does not run this one on them). Deliberately plain: the book's
// listings, with the same any-hit shortcut for shadow rays as the OpenCL
// kernel so that both do the same work.
#include "omp_tracer.hpp"

#include <stdexcept>

#include "whitted_float.hpp"

namespace clrt_bench {
namespace {

// The scene as the loops see it (its own type, so that whitted_float.hpp
// finds the queries below).
struct World : Scenery {};

inline int closest(const World& w, V O, V D, float tmin, float tmax, float& t) {
  int best = -1;
  t = kInf;
  for (size_t i = 0; i < w.spheres.size(); ++i) {
    float t1, t2;
    intersect(O, D, w.spheres[i], t1, t2);
    if (t1 < t && tmin < t1 && t1 < tmax) t = t1, best = int(i);
    if (t2 < t && tmin < t2 && t2 < tmax) t = t2, best = int(i);
  }
  closest_plane(w, O, D, tmin, tmax, t, best);
  return best;
}

inline bool blocked(const World& w, V O, V D, float tmin, float tmax) {
  for (const Sph& s : w.spheres) {
    float t1, t2;
    intersect(O, D, s, t1, t2);
    if ((tmin < t1 && t1 < tmax) || (tmin < t2 && t2 < tmax)) return true;
  }
  return plane_blocks(w, O, D, tmin, tmax);
}

// Its queries do not test triangles: an image without them would be timed
// as if it were the scene's.
void refuse_triangles(const clrt::Scene& scene) {
  if (!scene.triangles.empty())
    throw std::invalid_argument("the OpenMP tracer does not trace triangles (the scene has " +
                                std::to_string(scene.triangles.size()) + "); the Embree tracer does");
}

}  // namespace

int omp_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<float>& rgb) {
  refuse_triangles(scene);
  const World w{scenery(scene)};
  return render_pixels(w, scene, width, height, depth, rgb);
}

int omp_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<uint8_t>& rgba8) {
  refuse_triangles(scene);
  const World w{scenery(scene)};
  return render_pixels(w, scene, width, height, depth, rgba8);
}

void omp_warm_threads() {
#pragma omp parallel
  {}
}

}  // namespace clrt_bench

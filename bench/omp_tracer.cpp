// omp_tracer.cpp - the book's TraceRay in float, one pixel per loop
// iteration, rows shared among OpenMP threads. Deliberately plain: the
// book's listings, with the same any-hit shortcut for shadow rays as the
// OpenCL kernel so that both do the same work.
//
// Same floating-point environment as the kernel, which is built with
// -cl-denorms-are-zero and has no errno: each thread runs with FTZ/DAZ set
// (x86 MXCSR), and this file is built with -fno-math-errno (CMakeLists.txt).
// Without them the book's specular term pow(r.v, 500) underflows on most
// pixels and glibc's powf takes its underflow path through denormal
// arithmetic: measured 11-14% of this tracer's frame time
// (docs/performance.md), which had inflated clrt's speedup over it.
#include "omp_tracer.hpp"

#include <omp.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <cmath>
#include <limits>

namespace clrt_bench {
namespace {

// The float vector of the comparison; its operators are vec3.hpp's.
using V = clrt::Vector3<float>;
using clrt::dot;
using clrt::length;

inline V fv(const clrt::Vec3& v) {
  return {float(v.x), float(v.y), float(v.z)};
}

struct Sph {
  V center;
  float radius, specular, reflective;
  V color;
};
struct Lig {
  clrt::LightType type;
  float intensity;
  V vec;
};
struct World {
  std::vector<Sph> spheres;
  std::vector<Lig> lights;
  V background;
};

constexpr float kInf = std::numeric_limits<float>::infinity();

inline void intersect(V O, V D, const Sph& s, float& t1, float& t2) {
  V CO = O - s.center;
  float a = dot(D, D), b = 2 * dot(CO, D), c = dot(CO, CO) - s.radius * s.radius;
  float disc = b * b - 4 * a * c;
  if (disc < 0) {
    t1 = t2 = kInf;
    return;
  }
  float sq = std::sqrt(disc);
  t1 = (-b + sq) / (2 * a);
  t2 = (-b - sq) / (2 * a);
}

inline int closest(const World& w, V O, V D, float tmin, float tmax, float& t) {
  int best = -1;
  t = kInf;
  for (size_t i = 0; i < w.spheres.size(); ++i) {
    float t1, t2;
    intersect(O, D, w.spheres[i], t1, t2);
    if (t1 < t && tmin < t1 && t1 < tmax) t = t1, best = int(i);
    if (t2 < t && tmin < t2 && t2 < tmax) t = t2, best = int(i);
  }
  return best;
}

inline bool blocked(const World& w, V O, V D, float tmin, float tmax) {
  for (const Sph& s : w.spheres) {
    float t1, t2;
    intersect(O, D, s, t1, t2);
    if ((tmin < t1 && t1 < tmax) || (tmin < t2 && t2 < tmax)) return true;
  }
  return false;
}

float lighting(const World& w, V P, V N, V Vv, float spec, float eps) {
  float i = 0;
  float ln = length(N), lv = length(Vv);
  for (const Lig& l : w.lights) {
    if (l.type == clrt::LightType::Ambient) {
      i += l.intensity;
      continue;
    }
    V L = l.type == clrt::LightType::Point ? l.vec - P : l.vec;
    float tmax = l.type == clrt::LightType::Point ? 1.f : kInf;
    if (blocked(w, P, L, eps, tmax)) continue;
    float nl = dot(N, L);
    if (nl > 0) i += l.intensity * nl / (ln * length(L));
    if (spec != -1) {
      V R = (2 * dot(N, L)) * N - L;
      float rv = dot(R, Vv);
      if (rv > 0) i += l.intensity * std::pow(rv / (length(R) * lv), spec);
    }
  }
  return i;
}

V trace(const World& w, V O, V D, float tmin, float tmax, int depth, float eps) {
  float t;
  int si = closest(w, O, D, tmin, tmax, t);
  if (si < 0) return w.background;
  const Sph& s = w.spheres[si];
  V P = O + t * D;
  V N = P - s.center;
  N = (1 / length(N)) * N;
  V Vv = {-D.x, -D.y, -D.z};
  V local = lighting(w, P, N, Vv, s.specular, eps) * s.color;
  if (depth <= 0 || s.reflective <= 0) return local;
  V R = (2 * dot(N, Vv)) * N - Vv;
  V refl = trace(w, P, R, eps, kInf, depth - 1, eps);
  return (1 - s.reflective) * local + s.reflective * refl;
}

}  // namespace

int omp_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<float>& rgb) {
  World w;
  for (const auto& s : scene.spheres)
    w.spheres.push_back({fv(s.center), float(s.radius), float(s.specular), float(s.reflective), fv(s.color)});
  for (const auto& l : scene.lights) w.lights.push_back({l.type, float(l.intensity), fv(l.vec)});
  w.background = fv(scene.background);
  const V O = fv(scene.camera.position);
  const auto& m = scene.camera.rotation;
  const float vw = float(scene.camera.viewport_w), vh = float(scene.camera.viewport_h);
  const float d = float(scene.camera.projection_plane_d), eps = float(scene.epsilon);
  rgb.assign(size_t(width) * height * 3, 0.f);
  int threads = 1;
#pragma omp parallel
  {
#if defined(__SSE__)
    const unsigned saved_csr = _mm_getcsr();
    _mm_setcsr(saved_csr | 0x8040);  // FTZ (bit 15) | DAZ (bit 6)
#endif
#pragma omp single
    threads = omp_get_num_threads();
#pragma omp for schedule(dynamic, 4)
    for (int row = 0; row < height; ++row) {
      const int y = height / 2 - 1 - row;
      for (int col = 0; col < width; ++col) {
        const int x = col - width / 2;
        V c = {x * vw / width, y * vh / height, d};
        V D = {float(m[0]) * c.x + float(m[1]) * c.y + float(m[2]) * c.z,
               float(m[3]) * c.x + float(m[4]) * c.y + float(m[5]) * c.z,
               float(m[6]) * c.x + float(m[7]) * c.y + float(m[8]) * c.z};
        V col_v = trace(w, O, D, 1.f, kInf, depth, eps);
        float* p = &rgb[(size_t(row) * width + col) * 3];
        p[0] = col_v.x;
        p[1] = col_v.y;
        p[2] = col_v.z;
      }
    }
#if defined(__SSE__)
    _mm_setcsr(saved_csr);
#endif
  }
  return threads;
}

}  // namespace clrt_bench

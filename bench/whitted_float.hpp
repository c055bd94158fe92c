// whitted_float.hpp - the float Whitted tracer that both bench comparisons
// share (omp_tracer.cpp, embree_tracer.cpp): the book's TraceRay and
// ComputeLighting in float, its sphere quadratic, chapter 5's planes,
// triangles and refraction as the reference renders them (reference/
// reference.cpp: the same rules, in float), and the loop over pixels (rows
// shared among OpenMP threads, FTZ/DAZ). Each tracer supplies only the two
// queries that walk the primitives, found by argument-dependent lookup on
// its scene type W (which holds a Scenery's fields):
//   int closest(const W&, V O, V D, float tmin, float tmax, float& t);
//   bool blocked(const W&, V O, V D, float tmin, float tmax);
// closest() returns the hit's id over all primitives, the reference's
// order: spheres, then planes, then triangles (-1: none).
// One copy of the shading means the two images can differ only by those
// queries (tests/eval/test_embree_tracer.cpp: they do not).
//
// Same floating-point environment as the kernel, which is built with
// -cl-denorms-are-zero and has no errno: each thread runs with FTZ/DAZ set
// (x86 MXCSR), and the tracers are built with -fno-math-errno
// (CMakeLists.txt). Without them the book's specular term pow(r.v, 500)
// underflows on most pixels and glibc's powf takes its underflow path
// through denormal arithmetic: measured 11-14% of the OpenMP tracer's frame
// time (docs/developer/benchmarking.md), which had inflated clrt's speedup over it.
#pragma once
#include <omp.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "scene/scene.hpp"
#include "util/vec3.hpp"

namespace clrt_bench {

// The float vector of the comparisons; its operators are vec3.hpp's.
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
  float transparency, refractive_index;
  float outside;  // the medium around it (the reference's MediumOutside)
};
// A plane's or triangle's material (opaque, flat shaded).
struct Mat {
  float specular, reflective;
  V color;
};
struct Pla {
  V point, normal;
  Mat material;
};
struct Lig {
  clrt::LightType type;
  float intensity;
  V vec;
};
// A scene in the tracers' floats.
// Triangles stay the scene's (double, read per hit): no float copy of a
// mesh of millions of faces.
struct Scenery {
  std::vector<Sph> spheres;
  std::vector<Pla> planes;
  const clrt::Triangle* triangles = nullptr;
  size_t triangle_count = 0;
  std::vector<Lig> lights;
  V background;
  float camera_medium = 1;  // the reference's CameraMedium()
};

inline Mat fmat(const clrt::Material& m) {
  return {float(m.specular), float(m.reflective), fv(m.color)};
}

// The reference's media: the index of the smallest transparent sphere that
// contains the sphere whole (or the camera), else 1; ties to the first.
inline void media(const clrt::Scene& scene, Scenery& w) {
  const auto& all = scene.spheres;
  std::vector<size_t> clear;
  for (size_t i = 0; i < all.size(); ++i)
    if (all[i].transparency > 0) clear.push_back(i);
  for (size_t i = 0; i < all.size(); ++i) {
    const clrt::Sphere* around = nullptr;
    for (size_t o : clear) {
      if (o == i) continue;
      if (clrt::length(all[o].center - all[i].center) + all[i].radius < all[o].radius &&
          (!around || all[o].radius < around->radius))
        around = &all[o];
    }
    w.spheres[i].outside = around ? float(around->refractive_index) : 1.f;
  }
  const clrt::Sphere* around = nullptr;
  for (size_t o : clear)
    if (clrt::length(scene.camera.position - all[o].center) < all[o].radius &&
        (!around || all[o].radius < around->radius))
      around = &all[o];
  w.camera_medium = around ? float(around->refractive_index) : 1.f;
}

inline Scenery scenery(const clrt::Scene& scene) {
  Scenery w;
  for (const auto& s : scene.spheres)
    w.spheres.push_back({fv(s.center), float(s.radius), float(s.specular), float(s.reflective), fv(s.color),
                         float(s.transparency), float(s.refractive_index), 1.f});
  media(scene, w);
  for (const auto& p : scene.planes) w.planes.push_back({fv(p.point), fv(p.normal), fmat(p.material)});
  w.triangles = scene.triangles.data();
  w.triangle_count = scene.triangles.size();
  // Directions as the scene gave them: the book's shadow range is in their units.
  for (const auto& l : scene.lights)
    w.lights.push_back(
        {l.type, float(l.intensity), fv(l.type == clrt::LightType::Directional ? l.given_vec() : l.vec)});
  w.background = fv(scene.background);
  return w;
}

constexpr float kInf = std::numeric_limits<float>::infinity();

// The book's IntersectRaySphere: both roots, or (inf, inf).
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

// The reference's IntersectRayPlane: inf when the ray runs parallel.
inline float intersect(V O, V D, const Pla& p) {
  const float along = dot(p.normal, D);
  if (along == 0) return kInf;
  return dot(p.normal, p.point - O) / along;
}

// The nearest plane with tmin < t < tmax and t below `t` (its id over all
// primitives into `best`), for tracers that walk planes one by one.
template <class W>
void closest_plane(const W& w, V O, V D, float tmin, float tmax, float& t, int& best) {
  for (size_t i = 0; i < w.planes.size(); ++i) {
    const float tp = intersect(O, D, w.planes[i]);
    if (tp < t && tmin < tp && tp < tmax) t = tp, best = int(w.spheres.size() + i);
  }
}
template <class W>
bool plane_blocks(const W& w, V O, V D, float tmin, float tmax) {
  for (const Pla& p : w.planes) {
    const float tp = intersect(O, D, p);
    if (tmin < tp && tp < tmax) return true;
  }
  return false;
}

// The reference's RefractRay (Snell's law for the unit direction), in float.
inline bool refract(V D, V N, float n1, float n2, V& T) {
  const V d = (1 / length(D)) * D;
  float cos_i = -dot(N, d);
  if (cos_i < 0) {
    cos_i = -cos_i;
    N = -1.f * N;
  }
  if (n1 == n2) {
    T = d;
    return true;
  }
  const float eta = n1 / n2;
  const float k = 1 - eta * eta * (1 - cos_i * cos_i);
  if (k < 0) return false;
  T = eta * d + (eta * cos_i - std::sqrt(k)) * N;
  return true;
}

template <class W>
float lighting(const W& w, V P, V N, V Vv, float spec, float eps) {
  float i = 0;
  float ln = length(N), lv = length(Vv);
  for (const Lig& l : w.lights) {
    if (l.type == clrt::LightType::Ambient) {
      i += l.intensity;
      continue;
    }
    V L = l.type == clrt::LightType::Point ? l.vec - P : l.vec;
    float tmax = l.type == clrt::LightType::Point ? 1.f : kInf;
    const float nl = dot(N, L);
    const V R = (2 * nl) * N - L;
    const float rv = dot(R, Vv);
    const bool diffuse = nl > 0, shiny = spec != -1 && rv > 0;
    // A light that adds nothing here, blocked or not, needs no shadow ray:
    // the rule the OpenCL kernel follows (clrt_shade.h), so that both trace
    // the same rays.
    if (!diffuse && !shiny) continue;
    if (blocked(w, P, L, eps, tmax)) continue;
    if (diffuse) i += l.intensity * nl / (ln * length(L));
    if (shiny) i += l.intensity * std::pow(rv / (length(R) * lv), spec);
  }
  return i;
}

template <class W>
V trace(const W& w, V O, V D, float tmin, float tmax, int depth, float eps, float medium);

// A plane or triangle (id k past the spheres): the reference's FlatColor,
// the geometric normal turned against the ray, then the book's shading.
template <class W>
V flat(const W& w, size_t k, V P, V D, int depth, float eps, float medium) {
  V N;
  Mat m;
  if (k < w.planes.size()) {
    N = w.planes[k].normal;
    m = w.planes[k].material;
  } else {
    const clrt::Triangle& tri = w.triangles[k - w.planes.size()];
    const V a = fv(tri.v0);
    N = clrt::cross(fv(tri.v1) - a, fv(tri.v2) - a);
    m = fmat(tri.material);
  }
  if (dot(N, D) > 0) N = -1.f * N;
  N = (1 / length(N)) * N;
  V Vv = {-D.x, -D.y, -D.z};
  V local = lighting(w, P, N, Vv, m.specular, eps) * m.color;
  if (depth <= 0 || m.reflective <= 0) return local;
  V R = (2 * dot(N, Vv)) * N - Vv;
  V refl = trace(w, P, R, eps, kInf, depth - 1, eps, medium);
  return (1 - m.reflective) * local + m.reflective * refl;
}

// `medium`: the refractive index the ray travels in (the reference's rule).
template <class W>
V trace(const W& w, V O, V D, float tmin, float tmax, int depth, float eps, float medium) {
  float t;
  int id = closest(w, O, D, tmin, tmax, t);
  if (id < 0) return w.background;
  V P = O + t * D;
  if (size_t(id) >= w.spheres.size()) return flat(w, size_t(id) - w.spheres.size(), P, D, depth, eps, medium);
  const Sph& s = w.spheres[id];
  V N = P - s.center;
  N = (1 / length(N)) * N;
  V Vv = {-D.x, -D.y, -D.z};
  V local = lighting(w, P, N, Vv, s.specular, eps) * s.color;
  const float r = s.reflective, tr = s.transparency;
  if (depth <= 0 || (r <= 0 && tr <= 0)) return local;
  V R = (2 * dot(N, Vv)) * N - Vv;
  if (tr <= 0) {  // the book's line
    V refl = trace(w, P, R, eps, kInf, depth - 1, eps, medium);
    return (1 - r) * local + r * refl;
  }
  // Chapter 5's transparency, as the reference blends it: total internal
  // reflection sends the refracted share along the reflected ray.
  const bool entering = dot(D, N) <= 0;
  const float n2 = entering ? s.refractive_index : s.outside;
  V T;
  const bool refracts = refract(D, N, medium, n2, T);
  V reflected = {0, 0, 0};
  if (r > 0 || !refracts) reflected = trace(w, P, R, eps, kInf, depth - 1, eps, medium);
  V refracted = refracts ? trace(w, P, T, eps, kInf, depth - 1, eps, n2) : reflected;
  return (1 - r) * ((1 - tr) * local + tr * refracted) + r * reflected;
}

// The book's canvas rule, as clrt's to_u8() and its kernel's 8-bit output:
// clamp to [0, 255], round half to even, NaN to 0.
inline uint8_t canvas_u8(float v) {
  if (std::isnan(v)) return 0;
  return uint8_t(std::nearbyint(v < 0 ? 0.f : (v > 255 ? 255.f : v)));
}

// The image: one pixel per loop iteration, rows shared among OpenMP
// threads, into `out` - float RGB (0..255 unclamped, 3 per pixel) or, like
// clrt's 8-bit frames, RGBA bytes with the canvas rule (4 per pixel). Its
// memory is reused when it has the frame's size. Returns the number of
// threads.
template <class W, class Pixel>
int render_pixels(const W& w, const clrt::Scene& scene, int width, int height, int depth, std::vector<Pixel>& out) {
  static_assert(std::is_same_v<Pixel, float> || std::is_same_v<Pixel, uint8_t>, "float RGB or 8-bit RGBA");
  constexpr bool rgba8 = std::is_same_v<Pixel, uint8_t>;
  constexpr size_t channels = rgba8 ? 4 : 3;
  const V O = fv(scene.camera.position);
  const auto& m = scene.camera.rotation;
  const float vw = float(scene.camera.viewport_w), vh = float(scene.camera.viewport_h);
  const float d = float(scene.camera.projection_plane_d), eps = float(scene.epsilon);
  out.resize(size_t(width) * height * channels);  // every pixel is written below
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
        V col_v = trace(w, O, D, 1.f, kInf, depth, eps, w.camera_medium);
        Pixel* p = &out[(size_t(row) * width + col) * channels];
        if constexpr (rgba8) {
          p[0] = canvas_u8(col_v.x);
          p[1] = canvas_u8(col_v.y);
          p[2] = canvas_u8(col_v.z);
          p[3] = 255;
        } else {
          p[0] = col_v.x;
          p[1] = col_v.y;
          p[2] = col_v.z;
        }
      }
    }
#if defined(__SSE__)
    _mm_setcsr(saved_csr);
#endif
  }
  return threads;
}

}  // namespace clrt_bench

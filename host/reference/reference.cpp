// reference.cpp - the book's algorithm, function for function, in double.
// Names follow the book (TraceRay, ClosestIntersection, ComputeLighting...).
#include "reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "scene/ray_tree.hpp"
#include "util/doing.hpp"
#include "util/error.hpp"

namespace clrt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A hit: the sphere, or (chapter 5's other primitives) the plane or triangle,
// with the surface it shows.
struct Hit {
  const Sphere* sphere = nullptr;
  const Plane* plane = nullptr;
  const Triangle* triangle = nullptr;
  double t = kInf;
  bool found() const { return sphere || plane || triangle; }
};

class Tracer {
 public:
  // min_weight: the weight cut-off (scene/ray_tree.hpp); 0 = none.
  Tracer(const Scene& s, double min_weight) : s_(s), min_weight_(min_weight) {}

  // IntersectRaySphere: both roots of |O + tD - C|^2 = r^2 (inf, inf if none).
  static void IntersectRaySphere(Vec3 O, Vec3 D, const Sphere& sphere, double& t1, double& t2) {
    Vec3 CO = O - sphere.center;
    double a = dot(D, D);
    double b = 2 * dot(CO, D);
    double c = dot(CO, CO) - sphere.radius * sphere.radius;
    double discriminant = b * b - 4 * a * c;
    if (discriminant < 0) {
      t1 = t2 = kInf;
      return;
    }
    t1 = (-b + std::sqrt(discriminant)) / (2 * a);
    t2 = (-b - std::sqrt(discriminant)) / (2 * a);
  }

  // A plane: dot(N, O + tD - P0) = 0 (inf when the ray runs parallel to it).
  static double IntersectRayPlane(Vec3 O, Vec3 D, const Plane& plane) {
    double along = dot(plane.normal, D);
    if (along == 0) return kInf;
    return dot(plane.normal, plane.point - O) / along;
  }

  // A triangle, watertight (Woop, Benthin and Wald, JCGT 2013), in double:
  // the vertices in the ray's frame, sheared so that the ray runs along +z
  // from the origin; the signs of the three 2-D edge functions decide.
  // Zero edge functions count as inside (rays through an edge or vertex hit
  // every face there); inf for a miss.
  static double IntersectRayTriangle(Vec3 O, Vec3 D, const Triangle& tri) {
    const double d[3] = {D.x, D.y, D.z};
    int kz = 0;
    if (std::fabs(d[1]) > std::fabs(d[kz])) kz = 1;
    if (std::fabs(d[2]) > std::fabs(d[kz])) kz = 2;
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0) std::swap(kx, ky);
    const double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];
    const Vec3 a3 = tri.v0 - O, b3 = tri.v1 - O, c3 = tri.v2 - O;
    const double a[3] = {a3.x, a3.y, a3.z}, b[3] = {b3.x, b3.y, b3.z}, c[3] = {c3.x, c3.y, c3.z};
    const double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
    // (products rounded one by one: -ffp-contract=off for this file, see
    // CMakeLists.txt, so a shared edge's function is exactly negated)
    const double u = cx * by - cy * bx;
    const double v = ax * cy - ay * cx;
    const double w = bx * ay - by * ax;
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return kInf;
    const double det = u + v + w;
    if (det == 0) return kInf;
    return (u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz]) / det;
  }

  Hit ClosestIntersection(Vec3 O, Vec3 D, double t_min, double t_max) const {
    Hit h;
    for (const Sphere& sphere : s_.spheres) {
      double t1, t2;
      IntersectRaySphere(O, D, sphere, t1, t2);
      if (t1 < h.t && t_min < t1 && t1 < t_max) h = {&sphere, nullptr, nullptr, t1};
      if (t2 < h.t && t_min < t2 && t2 < t_max) h = {&sphere, nullptr, nullptr, t2};
    }
    for (const Plane& plane : s_.planes) {
      double t = IntersectRayPlane(O, D, plane);
      if (t < h.t && t_min < t && t < t_max) h = {nullptr, &plane, nullptr, t};
    }
    for (const Triangle& tri : s_.triangles) {
      double t = IntersectRayTriangle(O, D, tri);
      if (t < h.t && t_min < t && t < t_max) h = {nullptr, nullptr, &tri, t};
    }
    return h;
  }

  // The closest hit in (t_min, t_max) on the primitive with id `id` alone
  // (ids as HitId's); none when the ray misses it.
  Hit IntersectOnly(int32_t id, Vec3 O, Vec3 D, double t_min, double t_max) const {
    Hit h;
    const size_t n_spheres = s_.spheres.size(), n_planes = s_.planes.size();
    if (id < 0) return h;
    if (size_t(id) < n_spheres) {
      const Sphere& sphere = s_.spheres[size_t(id)];
      double t1, t2;
      IntersectRaySphere(O, D, sphere, t1, t2);
      if (t1 < h.t && t_min < t1 && t1 < t_max) h = {&sphere, nullptr, nullptr, t1};
      if (t2 < h.t && t_min < t2 && t2 < t_max) h = {&sphere, nullptr, nullptr, t2};
    } else if (size_t(id) < n_spheres + n_planes) {
      const Plane& plane = s_.planes[size_t(id) - n_spheres];
      double t = IntersectRayPlane(O, D, plane);
      if (t_min < t && t < t_max) h = {nullptr, &plane, nullptr, t};
    } else if (size_t(id) < n_spheres + n_planes + s_.triangles.size()) {
      const Triangle& tri = s_.triangles[size_t(id) - n_spheres - n_planes];
      double t = IntersectRayTriangle(O, D, tri);
      if (t_min < t && t < t_max) h = {nullptr, nullptr, &tri, t};
    }
    return h;
  }

  // The hit's id over all primitives: spheres, then planes, then triangles
  // (the kernel numbers them the same way; compare's hit classes).
  int32_t HitId(const Hit& h) const {
    if (h.sphere) return int32_t(h.sphere - s_.spheres.data());
    if (h.plane) return int32_t(s_.spheres.size() + size_t(h.plane - s_.planes.data()));
    return int32_t(s_.spheres.size() + s_.planes.size() + size_t(h.triangle - s_.triangles.data()));
  }

  static Vec3 ReflectRay(Vec3 R, Vec3 N) { return 2 * dot(N, R) * N - R; }

  // The unit normal that shading uses at P, the hit h of a ray along D: a
  // sphere's outward normal; a plane's normal or a triangle's
  // (v1 - v0) x (v2 - v0), turned against the ray (two-sided).
  static Vec3 ShadingNormal(const Hit& h, Vec3 P, Vec3 D) {
    Vec3 N;
    if (h.sphere) {
      N = P - h.sphere->center;
    } else {
      N = h.plane ? h.plane->normal : cross(h.triangle->v1 - h.triangle->v0, h.triangle->v2 - h.triangle->v0);
      if (dot(N, D) > 0) N = -1.0 * N;
    }
    return (1.0 / length(N)) * N;
  }

  double ComputeLighting(Vec3 P, Vec3 N, Vec3 V, double s, int32_t* shadowed) const {
    double i = 0;
    double length_n = length(N);
    double length_v = length(V);
    for (size_t li = 0; li < s_.lights.size(); ++li) {
      const Light& light = s_.lights[li];
      if (light.type == LightType::Ambient) {
        i += light.intensity;
        continue;
      }
      Vec3 L;
      double t_min = s_.epsilon, t_max;
      if (light.type == LightType::Point) {
        L = light.vec - P;
        t_max = 1;
      } else {
        L = light.vec;
        t_min = light.shadow_t_min(s_.epsilon);  // in units of the direction the scene gave
        t_max = kInf;
      }
      // Shadow check.
      if (ClosestIntersection(P, L, t_min, t_max).found()) {
        if (shadowed && li < 32) *shadowed |= int32_t(1u << li);
        continue;
      }
      // Diffuse.
      double n_dot_l = dot(N, L);
      if (n_dot_l > 0) i += light.intensity * n_dot_l / (length_n * length(L));
      // Specular.
      if (s != -1) {
        Vec3 R = ReflectRay(L, N);
        double r_dot_v = dot(R, V);
        if (r_dot_v > 0) i += light.intensity * std::pow(r_dot_v / (length(R) * length_v), s);
      }
    }
    return i;
  }

  // Chapter 5's refraction. The medium a ray travels in is remembered by the
  // ray (`medium`, a refractive index): camera rays start in
  // CameraMedium(); a ray entering a sphere (D.N <= 0, N the outward
  // normal) passes into the sphere's index, one leaving it into
  // MediumOutside(sphere). Snell's law for the unit direction d = D/|D|:
  // with cos_i = |N.d| and the normal N' turned against d, eta = n1 / n2,
  // k = 1 - eta^2 (1 - cos_i^2); k < 0 is total internal reflection (returns
  // false), else T = eta d + (eta cos_i - sqrt(k)) N'. Equal indices go
  // straight on (T = d), exactly.
  static bool RefractRay(Vec3 D, Vec3 N, double n1, double n2, Vec3& T) {
    Vec3 d = (1.0 / length(D)) * D;
    double cos_i = -dot(N, d);
    if (cos_i < 0) {
      cos_i = -cos_i;
      N = -1.0 * N;
    }
    if (n1 == n2) {
      T = d;
      return true;
    }
    double eta = n1 / n2;
    double k = 1 - eta * eta * (1 - cos_i * cos_i);
    if (k < 0) return false;
    T = eta * d + (eta * cos_i - std::sqrt(k)) * N;
    return true;
  }

  // The medium around a sphere: the refractive index of the smallest
  // transparent sphere that contains it whole (|C_o - C| + r < r_o; ties:
  // the first in the scene), else 1 (air). Partly overlapping transparent
  // spheres are not nested: each sees air outside.
  double MediumOutside(const Sphere& sphere) const {
    const Sphere* around = nullptr;
    for (const Sphere& o : s_.spheres) {
      if (&o == &sphere || o.transparency <= 0) continue;
      if (length(o.center - sphere.center) + sphere.radius < o.radius && (!around || o.radius < around->radius))
        around = &o;
    }
    return around ? around->refractive_index : 1.0;
  }

  // The medium the camera is in: the index of the smallest transparent sphere
  // around the camera's position (|P - C_o| < r_o), else 1.
  double CameraMedium() const {
    const Sphere* around = nullptr;
    for (const Sphere& o : s_.spheres) {
      if (o.transparency <= 0) continue;
      if (length(s_.camera.position - o.center) < o.radius && (!around || o.radius < around->radius)) around = &o;
    }
    return around ? around->refractive_index : 1.0;
  }

  // shadowed/hit are filled for the primary ray only (classification output).
  // `weight` is the ray's share of the pixel: the product of the shares
  // (r, (1 - r) t) along its path, 1 for a camera ray. A child ray whose
  // weight would be below min_weight_ is not traced: its colour counts as
  // black (the cut-off, scene/ray_tree.hpp: it moves no pixel by a level).
  //
  // Transparency (chapter 5) extends the book's blend: of the light that is
  // not reflected (1 - r), a share t passes through the surface, so
  //   colour = (1 - r) ((1 - t) local + t refracted) + r reflected,
  // where total internal reflection sends the refracted share along the
  // reflected ray. Shadow rays stay the book's: a transparent sphere blocks
  // light like any other. With t = 0 this is the book's line, exactly.
  Vec3 TraceRay(Vec3 O, Vec3 D, double t_min, double t_max, int depth, double medium, double weight, int32_t* hit,
                int32_t* shadowed) const {
    return ShadeHit(ClosestIntersection(O, D, t_min, t_max), O, D, depth, medium, weight, hit, shadowed);
  }

  // A child ray of weight `weight`: traced, or black when the cut-off drops it.
  Vec3 TraceChild(Vec3 O, Vec3 D, int depth, double medium, double weight) const {
    if (weight < min_weight_) return Vec3{0, 0, 0};
    return TraceRay(O, D, s_.epsilon, kInf, depth, medium, weight, nullptr, nullptr);
  }

  // TraceRay after its ClosestIntersection: the colour of the hit h of the
  // ray O + tD (the background where there is none).
  Vec3 ShadeHit(const Hit& h, Vec3 O, Vec3 D, int depth, double medium, double weight, int32_t* hit,
                int32_t* shadowed) const {
    if (!h.found()) return s_.background;
    if (hit) *hit = HitId(h);
    Vec3 P = O + h.t * D;
    if (!h.sphere) return FlatColor(h, P, D, depth, medium, weight, shadowed);
    Vec3 N = ShadingNormal(h, P, D);
    Vec3 V = -1.0 * D;
    Vec3 local_color = ComputeLighting(P, N, V, h.sphere->specular, shadowed) * h.sphere->color;
    double r = h.sphere->reflective;
    double t = h.sphere->transparency;
    if (depth <= 0 || (r <= 0 && t <= 0)) return local_color;
    Vec3 R = ReflectRay(V, N);
    if (t <= 0) {
      Vec3 reflected_color = TraceChild(P, R, depth - 1, medium, weight * r);
      return (1 - r) * local_color + r * reflected_color;
    }
    bool entering = dot(D, N) <= 0;
    double n2 = entering ? h.sphere->refractive_index : MediumOutside(*h.sphere);
    Vec3 T;
    bool refracts = RefractRay(D, N, medium, n2, T);
    // Under total internal reflection the reflected ray carries the
    // refracted share too.
    const double refracted_share = (1 - r) * t;
    const double reflected_share = refracts ? r : r + refracted_share;
    Vec3 reflected_color{0, 0, 0};
    if (r > 0 || !refracts) reflected_color = TraceChild(P, R, depth - 1, medium, weight * reflected_share);
    Vec3 refracted_color = refracts ? TraceChild(P, T, depth - 1, n2, weight * refracted_share) : reflected_color;
    return (1 - r) * ((1 - t) * local_color + t * refracted_color) + r * reflected_color;
  }

  // A plane or triangle: opaque, two-sided, flat shaded. Its normal is the
  // plane's, or the triangle's (v1 - v0) x (v2 - v0), turned against the ray;
  // then the book's shading and reflection as for a sphere.
  Vec3 FlatColor(const Hit& h, Vec3 P, Vec3 D, int depth, double medium, double weight, int32_t* shadowed) const {
    const Material& m = h.plane ? h.plane->material : h.triangle->material;
    Vec3 N = ShadingNormal(h, P, D);
    Vec3 V = -1.0 * D;
    Vec3 local_color = ComputeLighting(P, N, V, m.specular, shadowed) * m.color;
    double r = m.reflective;
    if (depth <= 0 || r <= 0) return local_color;
    Vec3 R = ReflectRay(V, N);
    Vec3 reflected_color = TraceChild(P, R, depth - 1, medium, weight * r);
    return (1 - r) * local_color + r * reflected_color;
  }

 private:
  const Scene& s_;
  double min_weight_;
};

// The camera ray's direction through canvas point (cx, cy) of a width x
// height frame: CanvasToViewport, then the camera rotation.
Vec3 CameraRay(const Camera& cam, int width, int height, double cx, double cy) {
  const auto& m = cam.rotation;
  const Vec3 d{cx * cam.viewport_w / width, cy * cam.viewport_h / height, cam.projection_plane_d};
  return Vec3{m[0] * d.x + m[1] * d.y + m[2] * d.z, m[3] * d.x + m[4] * d.y + m[5] * d.z,
              m[6] * d.x + m[7] * d.y + m[8] * d.z};
}

// The camera's rays and a pixel's samples (chapter 5's supersampling).
class PixelSampler {
 public:
  PixelSampler(const Tracer& tracer, const Camera& cam, int width, int height, int depth, const Sampling& sampling)
      : tracer_(tracer),
        cam_(cam),
        width_(width),
        height_(height),
        depth_(depth),
        n_(sampling.spp),
        sampling_(sampling),
        camera_medium_(tracer.CameraMedium()) {}

  double camera_medium() const { return camera_medium_; }

  // The camera ray's direction through canvas point (cx, cy).
  Vec3 ray(double cx, double cy) const { return CameraRay(cam_, width_, height_, cx, cy); }

  // Canvas point (x, y)'s colour: the mean of its samples (for N = 1, the
  // one sample's colour exactly). The classification - the primary hit and
  // the shadow mask - is the first sample's.
  Vec3 pixel(int x, int y, int32_t* hit, int32_t* shadowed) const {
    const int n = n_;
    // Supersampling: the N x N sub-pixel points (x + o_i, y + o_j),
    // o_k = (k + 0.5) / N - 0.5; N = 1 is the point (x, y) itself.
    // Sample s's colour; its primary hit goes to *hit_id.
    auto sample = [&](int s, int32_t* hit_id, int32_t* shadow) {
      const double ox = ((s % n) + 0.5) / n - 0.5, oy = ((s / n) + 0.5) / n - 0.5;
      return tracer_.TraceRay(cam_.position, ray(x + ox, y + oy), 1, kInf, depth_, camera_medium_, 1.0, hit_id, shadow);
    };
    Vec3 sum{0, 0, 0};
    int traced = 0;
    if (sampling_.adaptive()) {
      // The four corners of the grid; sample 0 first.
      const int corners[4] = {0, n - 1, n * (n - 1), n * n - 1};
      int32_t hits[4] = {-1, -1, -1, -1};
      Vec3 c[4];
      for (int k = 0; k < 4; ++k) c[k] = sample(corners[k], &hits[k], k == 0 ? shadowed : nullptr);
      *hit = hits[0];
      bool flat = hits[1] == hits[0] && hits[2] == hits[0] && hits[3] == hits[0];
      for (double Vec3::*channel : {&Vec3::x, &Vec3::y, &Vec3::z}) {
        const double lo = std::min({c[0].*channel, c[1].*channel, c[2].*channel, c[3].*channel});
        const double hi = std::max({c[0].*channel, c[1].*channel, c[2].*channel, c[3].*channel});
        flat = flat && hi - lo <= sampling_.adaptive_threshold;
      }
      sum = c[0] + c[1] + c[2] + c[3];
      traced = 4;
      if (!flat) {
        for (int s = 0; s < n * n; ++s)
          if (s != corners[0] && s != corners[1] && s != corners[2] && s != corners[3])
            sum = sum + sample(s, nullptr, nullptr);
        traced = n * n;
      }
    } else {
      for (int s = 0; s < n * n; ++s) {
        const bool first = s == 0;
        Vec3 c = sample(s, first ? hit : nullptr, first ? shadowed : nullptr);
        sum = first ? c : sum + c;
      }
      traced = n * n;
    }
    const double samples = double(traced);
    return Vec3{sum.x / samples, sum.y / samples, sum.z / samples};
  }

 private:
  const Tracer& tracer_;
  const Camera& cam_;
  int width_, height_, depth_, n_;
  Sampling sampling_;
  double camera_medium_;
};

}  // namespace

Image render_reference(const Scene& scene, int width, int height, int depth, Sampling sampling,
                       const CancelFn& cancel) {
  const int n = sampling.spp;
  if (n < 1) throw std::invalid_argument("render_reference: spp must be >= 1");
  if (sampling.subsample != Subsample::Off && n != 1)
    throw std::invalid_argument("render_reference: subsampling needs spp 1");
  const Doing doing("rendering " + std::to_string(width) + "x" + std::to_string(height) + " with the reference");
  Image img(width, height);
  Tracer tracer(scene, sampling.ray_cut ? double(ray_cut(scene).min_weight) : 0.0);
  const Camera& cam = scene.camera;
  const PixelSampler sampler(tracer, cam, width, height, depth, sampling);
  const double camera_medium = sampler.camera_medium();
  // Subsampling: the even columns first, each traced as usual; then the odd
  // ones, from their neighbours' primary hits (scene/sampling.hpp).
  const int passes = sampling.subsample != Subsample::Off ? 2 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    for (int x = -width / 2; x < width - width / 2; ++x) {
      const int col = width / 2 + x;
      if (passes == 2 && col % 2 != pass) continue;
      if (cancel && cancel()) throw Cancelled("reference render cancelled");
      for (int y = height / 2 - height; y < height / 2; ++y) {  // row in [0, H)
        int row = height / 2 - y - 1;
        size_t p = size_t(row) * width + col;
        if (pass == 1) {
          // An odd column: both neighbours must exist and have hit the same
          // primitive (or both missed) for the pixel to be assumed.
          const bool assumed = col + 1 < width && img.hit[p - 1] == img.hit[p + 1];
          if (assumed && sampling.subsample == Subsample::Interpolate) {
            // the mean of the neighbours' canvas colours, no ray
            for (int c = 0; c < 3; ++c)
              img.rgb[p * 3 + c] =
                  (double(to_u8(img.rgb[(p - 1) * 3 + c])) + double(to_u8(img.rgb[(p + 1) * 3 + c]))) / 2;
            img.hit[p] = img.hit[p - 1];
            img.shadowed[p] = img.shadowed[p - 1] & img.shadowed[p + 1];
            continue;
          }
          if (assumed) {
            const int32_t id = img.hit[p - 1];
            const Vec3 D = sampler.ray(x, y);
            Hit h;  // both neighbours missed: background, no search
            if (id >= 0) {
              h = tracer.IntersectOnly(id, cam.position, D, 1, kInf);
              // the ray passes the assumed primitive by: search after all
              if (!h.found()) h = tracer.ClosestIntersection(cam.position, D, 1, kInf);
            }
            const Vec3 c =
                tracer.ShadeHit(h, cam.position, D, depth, camera_medium, 1.0, &img.hit[p], &img.shadowed[p]);
            img.rgb[p * 3 + 0] = c.x;
            img.rgb[p * 3 + 1] = c.y;
            img.rgb[p * 3 + 2] = c.z;
            continue;
          }
        }
        const Vec3 c = sampler.pixel(x, y, &img.hit[p], &img.shadowed[p]);
        img.rgb[p * 3 + 0] = c.x;
        img.rgb[p * 3 + 1] = c.y;
        img.rgb[p * 3 + 2] = c.z;
      }
    }
  }
  return img;
}

FrameLayers render_reference_layers(const Scene& scene, int width, int height, unsigned layers,
                                    const CancelFn& cancel, std::vector<float>* incidence) {
  const Doing doing("the layers of " + std::to_string(width) + "x" + std::to_string(height) + " with the reference");
  FrameLayers img(width, height, layers);  // every pixel a miss
  if (incidence) incidence->assign(img.pixels(), 1.0f);
  const Tracer tracer(scene, 0);
  const Camera& cam = scene.camera;
  for (int row = 0; row < height; ++row) {
    if (cancel && cancel()) throw Cancelled("reference render cancelled");
    const int y = height / 2 - 1 - row;
    for (int col = 0; col < width; ++col) {
      const int x = col - width / 2;
      const Vec3 D = CameraRay(cam, width, height, x, y);
      const Hit h = tracer.ClosestIntersection(cam.position, D, 1, kInf);
      if (!h.found()) continue;  // the misses' values, as assigned above
      const size_t p = size_t(row) * width + col;
      const Vec3 P = cam.position + h.t * D;
      const Vec3 N = Tracer::ShadingNormal(h, P, D);
      const Vec3 color = h.sphere ? h.sphere->color : h.plane ? h.plane->material.color : h.triangle->material.color;
      if (layers & kLayerDepth) img.depth[p] = float(h.t * length(D));
      if (layers & kLayerNormal) {
        img.normal[p * 3 + 0] = float(N.x), img.normal[p * 3 + 1] = float(N.y), img.normal[p * 3 + 2] = float(N.z);
      }
      if (layers & kLayerAlbedo) {
        img.albedo[p * 3 + 0] = float(color.x / 255), img.albedo[p * 3 + 1] = float(color.y / 255);
        img.albedo[p * 3 + 2] = float(color.z / 255);
      }
      if (layers & kLayerId) img.id[p] = tracer.HitId(h);
      if (incidence) (*incidence)[p] = float(std::fabs(dot(N, D)) / length(D));
    }
  }
  return img;
}

}  // namespace clrt

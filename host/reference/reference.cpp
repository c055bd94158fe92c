// reference.cpp - the book's algorithm, function for function, in double.
// Names follow the book (TraceRay, ClosestIntersection, ComputeLighting...).
#include "reference/reference.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace clrt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Hit {
  const Sphere* sphere = nullptr;
  double t = kInf;
};

class Tracer {
 public:
  explicit Tracer(const Scene& s) : s_(s) {}

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

  Hit ClosestIntersection(Vec3 O, Vec3 D, double t_min, double t_max) const {
    Hit h;
    for (const Sphere& sphere : s_.spheres) {
      double t1, t2;
      IntersectRaySphere(O, D, sphere, t1, t2);
      if (t1 < h.t && t_min < t1 && t1 < t_max) h = {&sphere, t1};
      if (t2 < h.t && t_min < t2 && t2 < t_max) h = {&sphere, t2};
    }
    return h;
  }

  static Vec3 ReflectRay(Vec3 R, Vec3 N) { return 2 * dot(N, R) * N - R; }

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
      double t_max;
      if (light.type == LightType::Point) {
        L = light.vec - P;
        t_max = 1;
      } else {
        L = light.vec;
        t_max = kInf;
      }
      // Shadow check.
      if (ClosestIntersection(P, L, s_.epsilon, t_max).sphere) {
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

  // shadowed/hit are filled for the primary ray only (classification output).
  Vec3 TraceRay(Vec3 O, Vec3 D, double t_min, double t_max, int depth, int32_t* hit, int32_t* shadowed) const {
    Hit h = ClosestIntersection(O, D, t_min, t_max);
    if (!h.sphere) return s_.background;
    if (hit) *hit = int32_t(h.sphere - s_.spheres.data());
    Vec3 P = O + h.t * D;
    Vec3 N = P - h.sphere->center;
    N = (1.0 / length(N)) * N;
    Vec3 V = -1.0 * D;
    Vec3 local_color = ComputeLighting(P, N, V, h.sphere->specular, shadowed) * h.sphere->color;
    double r = h.sphere->reflective;
    if (depth <= 0 || r <= 0) return local_color;
    Vec3 R = ReflectRay(V, N);
    Vec3 reflected_color = TraceRay(P, R, s_.epsilon, kInf, depth - 1, nullptr, nullptr);
    return (1 - r) * local_color + r * reflected_color;
  }

 private:
  const Scene& s_;
};

}  // namespace

Image render_reference(const Scene& scene, int width, int height, int depth, int spp) {
  if (spp < 1) throw std::invalid_argument("render_reference: spp must be >= 1");
  Image img(width, height);
  Tracer tracer(scene);
  const Camera& cam = scene.camera;
  const auto& m = cam.rotation;
  const int n = spp;
  for (int x = -width / 2; x < width - width / 2; ++x) {
    for (int y = height / 2 - height; y < height / 2; ++y) {  // row in [0, H)
      int col = width / 2 + x;
      int row = height / 2 - y - 1;
      size_t p = size_t(row) * width + col;
      // Supersampling: the N x N sub-pixel points (x + o_i, y + o_j),
      // o_k = (k + 0.5) / N - 0.5; N = 1 is the point (x, y) itself.
      Vec3 sum{0, 0, 0};
      for (int s = 0; s < n * n; ++s) {
        const double ox = ((s % n) + 0.5) / n - 0.5, oy = ((s / n) + 0.5) / n - 0.5;
        // CanvasToViewport, then the camera rotation.
        Vec3 d{(x + ox) * cam.viewport_w / width, (y + oy) * cam.viewport_h / height, cam.projection_plane_d};
        Vec3 D{m[0] * d.x + m[1] * d.y + m[2] * d.z, m[3] * d.x + m[4] * d.y + m[5] * d.z,
               m[6] * d.x + m[7] * d.y + m[8] * d.z};
        // The classification is the first sample's.
        const bool first = s == 0;
        Vec3 c = tracer.TraceRay(cam.position, D, 1, kInf, depth, first ? &img.hit[p] : nullptr,
                                 first ? &img.shadowed[p] : nullptr);
        sum = first ? c : sum + c;
      }
      // The mean of the samples (for N = 1, the one sample's colour exactly).
      const double samples = double(n) * n;
      const Vec3 c{sum.x / samples, sum.y / samples, sum.z / samples};
      img.rgb[p * 3 + 0] = c.x;
      img.rgb[p * 3 + 1] = c.y;
      img.rgb[p * 3 + 2] = c.z;
    }
  }
  return img;
}

}  // namespace clrt

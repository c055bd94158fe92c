// embree_tracer.cpp - the float tracer of whitted_float.hpp (the book's
// TraceRay, shared with omp_tracer.cpp) with its two queries,
// ClosestIntersection and the shadow test, answered by an Embree 3 scene
// instead of a loop over every sphere. Camera, lighting, shading and the
// self-hit rule are omp_tracer's: the same code.
//
// Triangles: Embree's own RTC_GEOMETRY_TYPE_TRIANGLE (geomID 1, build
// quality high), three vertices per face as the scene holds them (it keeps
// no shared indices). Embree's float triangle test is not clrt's watertight
// one, so on an edge between two faces a ray may hit the one face where
// clrt hits the other, or neither (a crack) where clrt hits one: bench
// checks this tracer's image against clrt's and reports the pixels that
// differ. Planes (few, infinite: no box) are tested one by one after the
// Embree query, as the OpenMP tracer does.
//
// Geometry: RTC_GEOMETRY_TYPE_USER, one primitive per sphere, whose
// intersect/occluded callbacks run the tracers' float quadratic (the book's
// IntersectRaySphere), so that Embree changes which spheres a ray is tested
// against and nothing else: the image is omp_render's, float for float
// (tests/eval/test_embree_tracer.cpp). Embree's own sphere primitive,
// RTC_GEOMETRY_TYPE_SPHERE_POINT (kept as EmbreeSpheres::Builtin to measure
// this), solves the intersection geometrically (the centre projected onto
// the ray, then the half chord, with an approximate reciprocal of D.D): on
// the book's floor (radius 5000, centre 5001 away) its hit points differ
// from the book's b^2 - 4ac, whose c = |CO|^2 - r^2 cancels ~25e6 - 25e6 in
// float, by more than the book's epsilon of 0.001, and shadow and
// reflection rays leaving the floor then hit it or miss it in other places:
// speckle over the far floor and in the reflections. Measured on
// scenes/cgfs-demo.json at 600x600, depth 3: 4.3% of the pixels differ from
// omp_render by more than one level of 255 (up to 92 levels); on 200 and
// 2000 random spheres above the floor (320x240) 7.9% and 5.4%. With the
// user geometry: none (every float equal). A comparison whose image is not
// the OpenMP tracer's would time different work, hence the user geometry.
// It costs Embree little here: its render measured no slower than the
// built-in sphere's up to 10^4 spheres and ~25% slower at 10^6 (320x180,
// 2 cores), where the built-in intersects a leaf's spheres in SIMD.
//
// Self-hit rule: omp_tracer's, the book's t_min. Primary rays accept
// 1 < t < inf; reflection and shadow rays start on the surface and accept
// epsilon < t < t_max (t_max 1 toward a point light, inf otherwise), both
// roots of every sphere, no geomID/primID filter: RTCRay::tnear = t_min,
// tfar = t_max, and the callbacks test strictly as omp_tracer does.
//
// Bounds: a sphere's box is its exact box grown by 4 * FLT_EPSILON *
// (d^2 / r + d + |c|_max), d the distance from the camera to the far side
// of the sphere. The float quadratic misjudges a ray's closest approach to
// the centre by a few FLT_EPSILON * d^2 / r for an origin d away (the
// cancellation in b^2 - 4ac), so it reports hits just outside the exact
// sphere, on silhouettes; Embree calls the callback only for rays that
// cross a box, and with exact boxes 24 of the demo's 360000 pixels differed
// (by up to 102 levels). Rays from origins farther from a sphere than the
// camera can in principle still differ on a silhouette pixel, as can two
// spheres hit at exactly the same t (omp_tracer keeps the lower index,
// Embree the first it visits); the test states the tolerance.
//
// Build: RTC_BUILD_QUALITY_HIGH, once per call, timed apart from the render
// (the figure `clrt bench` compares). For user geometry (no spatial splits,
// which are for triangles) it measured the same as MEDIUM in build and
// render time at 10^4 and 10^5 spheres. Scene flags default (not ROBUST):
// the pad above also covers the traversal's box-test rounding. One million
// spheres: build ~0.5 s, ~360 MB peak for the whole process (2 cores).
#include "embree_tracer.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

#include "omp_tracer.hpp"
#include "util/timer.hpp"
#include "whitted_float.hpp"

namespace clrt_bench {
namespace {

// ---- user geometry callbacks ------------------------------------------------

struct UserSpheres {
  const Sph* spheres;
  const float* pad;  // per sphere, see the file comment
};

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* u = static_cast<const UserSpheres*>(args->geometryUserPtr);
  const Sph& s = u->spheres[args->primID];
  const float e = std::fabs(s.radius) + u->pad[args->primID];
  RTCBounds* b = args->bounds_o;
  b->lower_x = s.center.x - e;
  b->lower_y = s.center.y - e;
  b->lower_z = s.center.z - e;
  b->upper_x = s.center.x + e;
  b->upper_y = s.center.y + e;
  b->upper_z = s.center.z + e;
}

// Only rtcIntersect1/rtcOccluded1 are called, so N is 1 and the ray is an
// RTCRayHit / RTCRay. Like omp_tracer's closest(): each root replaces the
// current hit when tnear < t < tfar (tfar is the closest so far).
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  const auto* u = static_cast<const UserSpheres*>(args->geometryUserPtr);
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  RTCRay& ray = rh->ray;
  const V O = {ray.org_x, ray.org_y, ray.org_z}, D = {ray.dir_x, ray.dir_y, ray.dir_z};
  float t1, t2;
  intersect(O, D, u->spheres[args->primID], t1, t2);
  float t = ray.tfar;
  bool hit = false;
  if (t1 < t && ray.tnear < t1) t = t1, hit = true;
  if (t2 < t && ray.tnear < t2) t = t2, hit = true;
  if (!hit) return;
  ray.tfar = t;
  rh->hit.Ng_x = rh->hit.Ng_y = rh->hit.Ng_z = 0;  // unused: the tracer shades from the centre
  rh->hit.u = rh->hit.v = 0;
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

// omp_tracer's blocked(): any root strictly inside (tnear, tfar).
void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  const auto* u = static_cast<const UserSpheres*>(args->geometryUserPtr);
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  const V O = {ray->org_x, ray->org_y, ray->org_z}, D = {ray->dir_x, ray->dir_y, ray->dir_z};
  float t1, t2;
  intersect(O, D, u->spheres[args->primID], t1, t2);
  if ((ray->tnear < t1 && t1 < ray->tfar) || (ray->tnear < t2 && t2 < ray->tfar)) ray->tfar = -kInf;
}

// ---- Embree objects -----------------------------------------------------------

void check(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(int(e)) + ")");
}

struct DeviceHandle {
  RTCDevice d = rtcNewDevice(nullptr);
  ~DeviceHandle() {
    if (d) rtcReleaseDevice(d);
  }
};
struct SceneHandle {
  RTCScene s = nullptr;
  ~SceneHandle() {
    if (s) rtcReleaseScene(s);
  }
};

// ---- the tracer: omp_tracer's, with Embree queries ------------------------------

struct World : Scenery {
  RTCScene scene = nullptr;
};

// Embree's hit: the sphere's index, or the triangle's past the spheres and
// planes (whitted_float.hpp's ids); then the planes.
inline int closest(const World& w, V O, V D, float tmin, float tmax, float& t) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = O.x;
  rh.ray.org_y = O.y;
  rh.ray.org_z = O.z;
  rh.ray.tnear = tmin;
  rh.ray.dir_x = D.x;
  rh.ray.dir_y = D.y;
  rh.ray.dir_z = D.z;
  rh.ray.time = 0;
  rh.ray.tfar = tmax;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(w.scene, &ctx, &rh);
  int best = -1;
  t = kInf;
  if (rh.hit.geomID == 0) {
    t = rh.ray.tfar;
    best = int(rh.hit.primID);
  } else if (rh.hit.geomID == 1) {
    t = rh.ray.tfar;
    best = int(w.spheres.size() + w.planes.size() + rh.hit.primID);
  }
  closest_plane(w, O, D, tmin, tmax, t, best);
  return best;
}

inline bool blocked(const World& w, V O, V D, float tmin, float tmax) {
  if (plane_blocks(w, O, D, tmin, tmax)) return true;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray;
  ray.org_x = O.x;
  ray.org_y = O.y;
  ray.org_z = O.z;
  ray.tnear = tmin;
  ray.dir_x = D.x;
  ray.dir_y = D.y;
  ray.dir_z = D.z;
  ray.time = 0;
  ray.tfar = tmax;
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(w.scene, &ctx, &ray);
  return ray.tfar < 0;  // -inf on a hit
}

// The scene's triangles as Embree triangle geometry (geomID 1; primID =
// the triangle's index), three float vertices per face.
void attach_triangles(RTCDevice device, RTCScene scene, const clrt::Scene& source) {
  const size_t n = source.triangles.size();
  if (n == 0) return;
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* index = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  if (!v || !index) {
    rtcReleaseGeometry(g);
    check(device, "rtcSetNewGeometryBuffer");
    throw std::runtime_error("Embree: rtcSetNewGeometryBuffer returned no buffer");
  }
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const clrt::Triangle& tri = source.triangles[i];
    const clrt::Vec3* corner[3] = {&tri.v0, &tri.v1, &tri.v2};
    for (int c = 0; c < 3; ++c) {
      v[9 * i + 3 * c + 0] = float(corner[c]->x);
      v[9 * i + 3 * c + 1] = float(corner[c]->y);
      v[9 * i + 3 * c + 2] = float(corner[c]->z);
      index[3 * i + c] = unsigned(3 * i + c);
    }
  }
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene, g, 1);
  rtcReleaseGeometry(g);
}

// Builds the Embree scene, then renders into `out` (float RGB or RGBA8).
template <class Pixel>
int build_and_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<Pixel>& out,
                     EmbreeBuildInfo* info, EmbreeSpheres kind) {
  World w{scenery(scene)};
  const V O = fv(scene.camera.position);

  EmbreeBuildInfo local;
  local.spheres = w.spheres.size();
  local.triangles = scene.triangles.size();
  auto t0 = clrt::Clock::now();
  DeviceHandle device;
  check(device.d, "rtcNewDevice");
  local.device_ms = clrt::ms_since(t0);

  t0 = clrt::Clock::now();
  SceneHandle sc;
  sc.s = rtcNewScene(device.d);
  rtcSetSceneBuildQuality(sc.s, RTC_BUILD_QUALITY_HIGH);
  std::vector<float> pad;
  UserSpheres user{w.spheres.data(), nullptr};
  const unsigned n = unsigned(w.spheres.size());
  if (n > 0) {
    RTCGeometry g;
    if (kind == EmbreeSpheres::Builtin) {
      g = rtcNewGeometry(device.d, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n));
      if (!v) {
        rtcReleaseGeometry(g);
        check(device.d, "rtcSetNewGeometryBuffer");
        throw std::runtime_error("Embree: rtcSetNewGeometryBuffer returned no buffer");
      }
      for (unsigned i = 0; i < n; ++i) {
        v[4 * i + 0] = w.spheres[i].center.x;
        v[4 * i + 1] = w.spheres[i].center.y;
        v[4 * i + 2] = w.spheres[i].center.z;
        v[4 * i + 3] = w.spheres[i].radius;
      }
    } else {
      pad.resize(n);
      for (unsigned i = 0; i < n; ++i) {
        const Sph& s = w.spheres[i];
        const float r = std::fabs(s.radius);
        const float d = length(s.center - O) + r;
        const float c = std::max({std::fabs(s.center.x), std::fabs(s.center.y), std::fabs(s.center.z)});
        pad[i] = 4 * FLT_EPSILON * (d * d / r + d + c);
      }
      user.pad = pad.data();
      g = rtcNewGeometry(device.d, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, n);
      rtcSetGeometryUserData(g, &user);
      rtcSetGeometryBoundsFunction(g, sphere_bounds, nullptr);
      rtcSetGeometryIntersectFunction(g, sphere_intersect);
      rtcSetGeometryOccludedFunction(g, sphere_occluded);
    }
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(sc.s, g, 0);  // geomID 0; primID = sphere index
    rtcReleaseGeometry(g);
  }
  attach_triangles(device.d, sc.s, scene);
  rtcCommitScene(sc.s);
  check(device.d, "building the scene");
  w.scene = sc.s;
  local.build_ms = clrt::ms_since(t0);

  omp_warm_threads();  // (the build, on Embree's own threads, outlasts their spinning)
  t0 = clrt::Clock::now();
  const int threads = render_pixels(w, scene, width, height, depth, out);
  local.render_ms = clrt::ms_since(t0);
  local.threads = threads;
  check(device.d, "rendering");
  if (info) *info = local;
  return threads;
}

}  // namespace

int embree_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<float>& rgb,
                  EmbreeBuildInfo* info, EmbreeSpheres kind) {
  return build_and_render(scene, width, height, depth, rgb, info, kind);
}

int embree_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<uint8_t>& rgba8,
                  EmbreeBuildInfo* info, EmbreeSpheres kind) {
  return build_and_render(scene, width, height, depth, rgba8, info, kind);
}

}  // namespace clrt_bench

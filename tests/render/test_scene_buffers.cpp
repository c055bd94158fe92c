// test_scene_buffers.cpp - Scene (double) -> device layouts: hi/lo packing,
// camera-relative coordinates, light codes and the host's view of the
// layout field list. Host only: no OpenCL device is needed.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "render/scene_buffers.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_scene_buffers {

using namespace clrt;

namespace {

// Values a scene holds: book coordinates, thirds and tenths (not floats),
// large and small lengths within the accepted range (scene.hpp).
const double kValues[] = {
    0.1,   1.0 / 3, -2.0 / 3, 3.14159265358979324, 5000.123456789, -5001.000000001, 1e8 / 3, -99999999.987, 1.2345e-8,
    0.001, 0.6,     1e-3 / 7};

// Relative error of the float-float pair (hi, lo) as a value of `v`.
double pair_error(double v, float hi, float lo) {
  return std::abs((static_cast<double>(hi) + static_cast<double>(lo)) - v) / std::abs(v);
}

}  // namespace

TEST_CASE("hi + lo reproduces doubles far better than a float", "[buffers]") {
  for (double v : kValues) {
    INFO(v);
    float hi, lo;
    split_hi_lo(v, hi, lo);
    CHECK(hi == static_cast<float>(v));  // float builds read hi alone: the nearest float
    const double float_error = std::abs(static_cast<double>(hi) - v) / std::abs(v);
    CHECK(float_error > 0);  // none of these is a float
    // lo is what hi misses, rounded to 24 bits: ~48 bits together, and the
    // pair's error is at most 2^-24 of the float's.
    CHECK(pair_error(v, hi, lo) <= std::ldexp(1.0, -47));
    CHECK(pair_error(v, hi, lo) <= float_error * std::ldexp(1.0, -24));
    // lo is at most half an ulp of hi: it never changes hi's own rounding.
    const float ulp = std::nextafter(std::abs(hi), std::numeric_limits<float>::infinity()) - std::abs(hi);
    CHECK(std::abs(lo) <= ulp / 2);
  }
}

TEST_CASE("hi/lo is exact for floats and zero", "[buffers]") {
  for (double v : kValues) {
    const double as_float = static_cast<float>(v);
    float hi, lo;
    split_hi_lo(as_float, hi, lo);
    CHECK(static_cast<double>(hi) == as_float);
    CHECK(lo == 0);
  }
  float hi = 1, lo = 1;
  split_hi_lo(0.0, hi, lo);
  CHECK(hi == 0);
  CHECK(lo == 0);
}

TEST_CASE("pack_scene: counts, sizes, materials and light codes", "[buffers]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const SceneData d = pack_scene(demo, Precision::Naive, 640, 480, 3);
  CHECK(d.params.width == 640);
  CHECK(d.params.height == 480);
  CHECK(d.params.depth == 3);
  CHECK(d.params.spp == 1);  // the default: one ray per pixel
  CHECK(pack_scene(demo, Precision::Naive, 640, 480, 3, 4).params.spp == 4);
  CHECK(d.params.n_spheres == 4);
  CHECK(d.params.n_lights == 3);
  REQUIRE(d.spheres.size() == 4);
  REQUIRE(d.lights.size() == 3);
  CHECK(d.spheres[3].radius == 5000);
  CHECK(d.spheres[3].radius_lo == 0);
  CHECK(d.spheres[3].center[1] == -5001);
  CHECK(d.spheres[0].specular == 500);
  CHECK(d.spheres[1].reflective == 0.4f);
  CHECK(d.spheres[0].color[0] == 255);
  CHECK(d.params.epsilon == 0.001f);
  CHECK(d.params.epsilon + double(d.params.epsilon_lo) == Approx(0.001).epsilon(1e-14));
  CHECK(d.lights[0].type == CLRT_LIGHT_AMBIENT);
  CHECK(d.lights[1].type == CLRT_LIGHT_POINT);
  CHECK(d.lights[2].type == CLRT_LIGHT_DIRECTIONAL);
  CHECK(kernel_light_code(LightType::Ambient) == CLRT_LIGHT_AMBIENT);
  CHECK(kernel_light_code(LightType::Point) == CLRT_LIGHT_POINT);
  CHECK(kernel_light_code(LightType::Directional) == CLRT_LIGHT_DIRECTIONAL);
  CHECK(d.lights[1].intensity == 0.6f);
}

TEST_CASE("pack_scene: a triangle sink gets every triangle in order, in chunks, with the same digest", "[buffers]") {
  // More than two chunks, the last one short; two materials.
  Scene scene = clrt_test::load("scenes/cgfs-demo.json");
  const size_t count = 2 * kTriangleChunk + 123;
  for (size_t i = 0; i < count; ++i) {
    Triangle t;
    t.v0 = {double(i), 0, 1};
    t.v1 = {double(i) + 0.5, 1.0 / 3, 1};
    t.v2 = {double(i), 1, 2.0 / 3};
    t.material.color = {i % 2 ? 255.0 : 10.0, 0, 0};
    scene.triangles.push_back(t);
  }
  const SceneData kept = pack_scene(scene, Precision::Robust, 64, 48, 3);
  REQUIRE(kept.triangles.size() == count);
  std::vector<clrt_triangle> given;
  std::vector<clrt_triangle_lo> given_lo;
  std::vector<size_t> chunks;
  const SceneData sunk = pack_scene(scene, Precision::Robust, 64, 48, 3, {},
                                    {[&](const clrt_triangle* t, const clrt_triangle_lo* lo, size_t n) {
                                      chunks.push_back(n);
                                      given.insert(given.end(), t, t + n);
                                      given_lo.insert(given_lo.end(), lo, lo + n);
                                    }});
  CHECK(sunk.triangles.empty());
  CHECK(chunks == std::vector<size_t>{kTriangleChunk, kTriangleChunk, 123});
  REQUIRE(given.size() == count);
  CHECK(std::memcmp(given.data(), kept.triangles.data(), count * sizeof(clrt_triangle)) == 0);
  REQUIRE(given_lo.size() == count);
  REQUIRE(kept.triangles_lo.size() == count);
  CHECK(std::memcmp(given_lo.data(), kept.triangles_lo.data(), count * sizeof(clrt_triangle_lo)) == 0);
  // the lo parts are the hi parts' remainders: 1/3 is no float
  CHECK(kept.triangles_lo[5].v1_lo[1] != 0);
  CHECK(double(kept.triangles[5].v1[1]) + double(kept.triangles_lo[5].v1_lo[1]) == Approx(1.0 / 3).epsilon(1e-14));
  CHECK(kept.triangles[5].index == 5);
  CHECK(sunk.triangles_digest == kept.triangles_digest);
  CHECK(sunk.materials.size() == kept.materials.size());
  // straight into arrays (a mapped device buffer): the same triangles and
  // digest, also where the lo parts are not kept
  std::vector<clrt_triangle> placed(count);
  std::vector<clrt_triangle_lo> placed_lo(count);
  TriangleOutput in_place;
  in_place.triangles = placed.data();
  in_place.triangles_lo = placed_lo.data();
  const SceneData direct = pack_scene(scene, Precision::Robust, 64, 48, 3, {}, in_place);
  CHECK(direct.triangles.empty());
  CHECK(std::memcmp(placed.data(), kept.triangles.data(), count * sizeof(clrt_triangle)) == 0);
  CHECK(std::memcmp(placed_lo.data(), kept.triangles_lo.data(), count * sizeof(clrt_triangle_lo)) == 0);
  CHECK(direct.triangles_digest == kept.triangles_digest);
  in_place.triangles_lo = nullptr;
  std::fill(placed.begin(), placed.end(), clrt_triangle{});
  CHECK(pack_scene(scene, Precision::Robust, 64, 48, 3, {}, in_place).triangles_digest == kept.triangles_digest);
  CHECK(std::memcmp(placed.data(), kept.triangles.data(), count * sizeof(clrt_triangle)) == 0);
  // two materials, numbered in order of first use
  REQUIRE(kept.materials.size() == 2);
  CHECK(kept.materials[0].color[0] == 10.0f);
  CHECK(kept.triangles[1].material == 1);
  CHECK(kept.triangles[count - 1].material == (count - 1) % 2);
  // the digest sees a change in any triangle
  scene.triangles[count - 1].v2.z += 1;
  CHECK(pack_scene(scene, Precision::Robust, 64, 48, 3).triangles_digest != kept.triangles_digest);
}

TEST_CASE("pack_leaf_spheres: each sphere entry's centre and radius, the sign its compensation", "[buffers]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const SceneData d = pack_scene(demo, Precision::Robust, 64, 48, 3);
  const clrt_i32 triangle = CLRT_PRIMITIVE_TRIANGLE << CLRT_PRIMITIVE_KIND_SHIFT;
  const std::vector<clrt_i32> entries{3, triangle | 0, 1, 0, 2};
  const std::vector<clrt_leaf_sphere> leaves = pack_leaf_spheres(entries, d.spheres);
  REQUIRE(leaves.size() == entries.size());
  for (size_t k : {0, 2, 3, 4}) {
    const clrt_sphere& s = d.spheres[size_t(entries[k])];
    INFO(k);
    CHECK(std::memcmp(leaves[k].center, s.center, sizeof s.center) == 0);
    CHECK(std::fabs(leaves[k].radius) == s.radius);
    CHECK(std::signbit(leaves[k].radius) == (s.compensated != 0));
  }
  CHECK(d.spheres[3].compensated == 1);  // the floor (radius 5000): the sign is used
  CHECK(pack_leaf_spheres({triangle | 0, triangle | 1}, d.spheres).empty());  // no sphere entry: no copies
}

TEST_CASE("robust and fast are camera-relative, positions move, directions do not", "[buffers]") {
  CHECK(camera_relative(Precision::Robust));
  CHECK(camera_relative(Precision::Fast));
  CHECK_FALSE(camera_relative(Precision::Naive));
  CHECK_FALSE(camera_relative(Precision::Stable));
  CHECK_FALSE(camera_relative(Precision::Fp64));

  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  const Vec3 camera{1e6 + 0.1, -3, 2};
  s.camera.position = camera;
  const SceneData world = pack_scene(s, Precision::Naive, 8, 8, 1);
  const SceneData relative = pack_scene(s, Precision::Robust, 8, 8, 1);
  CHECK(world.params.origin[0] == static_cast<float>(camera.x));
  CHECK(relative.params.origin[0] == 0);
  CHECK(relative.params.origin_lo[0] == 0);
  // The sphere at x = 0 lies at -camera.x, rounded once, from the camera.
  CHECK(relative.spheres[0].center[0] == static_cast<float>(-camera.x));
  CHECK(relative.spheres[0].center[1] == static_cast<float>(s.spheres[0].center.y - camera.y));
  // The point light's position moves with the camera, the directional
  // light's direction does not.
  CHECK(relative.lights[1].vec[0] == static_cast<float>(s.lights[1].vec.x - camera.x));
  CHECK(world.lights[1].vec[0] == static_cast<float>(s.lights[1].vec.x));
  CHECK(std::memcmp(relative.lights[2].vec, world.lights[2].vec, sizeof world.lights[2].vec) == 0);
  // The camera-relative pair still carries the position to ~48 bits.
  const double x = relative.spheres[0].center[0] + double(relative.spheres[0].center_lo[0]);
  CHECK(std::abs(x - (s.spheres[0].center.x - camera.x)) < 1e-7);
}

TEST_CASE("the host's layout field list names every struct member once", "[buffers][layout]") {
  // The byte-for-byte checks are static_asserts (scene_buffers.cpp); the
  // kernel compares its view in the [opencl][layout] test.
  std::set<std::string> names;
  int bytes = 0;
  for (const LayoutField& f : kLayoutFields) {
    CHECK(names.insert(std::string(f.type) + "." + f.member).second);
    bytes += f.size;
  }
  CHECK(bytes == int(sizeof(clrt_sphere) + sizeof(clrt_light) + sizeof(clrt_params) + sizeof(clrt_material) +
                     sizeof(clrt_plane) + sizeof(clrt_triangle) + sizeof(clrt_ray_counts) + sizeof(clrt_bvh_node) +
                     sizeof(clrt_wide_node) + sizeof(clrt_leaf_sphere) + sizeof(clrt_triangle_lo)));
  CHECK(kLayoutFields[0].offset == 0);
  CHECK(std::string(kLayoutFields[0].type) == "clrt_sphere");
  CHECK(std::string(std::prev(std::end(kLayoutFields))->type) == "clrt_leaf_sphere");
  CHECK(std::string(std::prev(std::end(kLayoutFields))->member) == "radius");
}

}  // namespace test_scene_buffers

// test_conditioning.cpp - the per-sphere choice of compensated arithmetic
// (render/conditioning.hpp) and how it reaches the robust kernel: the
// sphere's flag and, in specialized builds, CLRT_COMPENSATED_SPHERES or
// CLRT_COMPENSATED_FLAGS.
// Host only: no OpenCL device is needed.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "render/build_options.hpp"
#include "render/conditioning.hpp"
#include "render/kernel_features.hpp"
#include "render/scene_buffers.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_conditioning {

using namespace clrt;

namespace {

// Every length times k, epsilon included (the stability suite's "scale").
Scene scaled(Scene s, double k) {
  s.camera.position = k * s.camera.position;
  s.epsilon *= k;
  for (auto& sphere : s.spheres) sphere.center = k * sphere.center, sphere.radius *= k;
  return s;
}

std::vector<bool> decisions(const Scene& s) {
  std::vector<bool> out;
  for (const Sphere& sphere : s.spheres) out.push_back(needs_compensation(sphere, s));
  return out;
}

Scene unit_sphere_at(Vec3 center) {
  Scene s;  // camera at the origin, epsilon 1e-3
  Sphere sphere;
  sphere.center = center;
  sphere.radius = 1;
  s.spheres = {sphere};
  return s;
}

bool has_prefix(const std::vector<std::string>& options, const std::string& prefix) {
  for (const auto& o : options)
    if (o.compare(0, prefix.size(), prefix) == 0) return true;
  return false;
}

bool has(const std::vector<std::string>& options, const std::string& option) {
  for (const auto& o : options)
    if (o == option) return true;
  return false;
}

}  // namespace

TEST_CASE("the demo's floor is compensated, the book's unit spheres are not", "[conditioning]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  REQUIRE(demo.spheres[3].radius == 5000);
  CHECK(decisions(demo) == std::vector<bool>{false, false, false, true});
  // Far from the threshold either way (conditioning.hpp: 19x over, 140x under).
  const Vec3 camera = demo.camera.position;
  CHECK(kCompensationSafety * uncompensated_error(demo.spheres[3], camera) > 10 * demo.epsilon);
  for (int i = 0; i < 3; ++i)
    CHECK(kCompensationSafety * uncompensated_error(demo.spheres[i], camera) < demo.epsilon / 100);
  // The floor's error alone, without the safety factor, is already above
  // epsilon: u (3 * 5000 + 5001) = 1.19e-3.
  CHECK(uncompensated_error(demo.spheres[3], camera) == Approx(0x1p-24 * 20001));
  // Every shipped scene is the book's: only its floor (glass.json stands on
  // a plane: nothing to compensate).
  for (const auto& path : clrt_test::shipped_scenes()) {
    INFO(path);
    const Scene s = load_scene(path);
    size_t flagged = 0;
    for (const Sphere& sphere : s.spheres) {
      CHECK(needs_compensation(sphere, s) == (sphere.radius >= 1000));
      flagged += needs_compensation(sphere, s);
    }
    const bool plane_floor = path.size() >= 10 && path.compare(path.size() - 10, 10, "glass.json") == 0;
    CHECK(flagged == (plane_floor ? 0u : 1u));
  }
}

TEST_CASE("the rule is scale- and translation-invariant", "[conditioning]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const std::vector<bool> expected = decisions(demo);
  for (double k : {1e-3, 1e-2, 1.0, 100.0, 1e4}) {
    INFO("scale " << k);
    CHECK(decisions(scaled(demo, k)) == expected);
  }
  // Moving everything, camera included: the rule sees camera-relative centres.
  for (double t : {100.0, 2e3, 1e5}) {
    INFO("translation " << t);
    Scene moved = demo;
    const Vec3 d = t * Vec3{0.48, 0.6, 0.64};
    moved.camera.position = moved.camera.position + d;
    for (auto& sphere : moved.spheres) sphere.center = sphere.center + d;
    CHECK(decisions(moved) == expected);
  }
}

TEST_CASE("a small sphere far from the camera is compensated, the same sphere near it is not", "[conditioning]") {
  // u (3 + Z) against epsilon / 16 = 6.25e-5: the threshold is Z ~ 1046.
  CHECK_FALSE(needs_compensation(unit_sphere_at({0, 0, 100}).spheres[0], unit_sphere_at({0, 0, 100})));
  CHECK_FALSE(needs_compensation(unit_sphere_at({0, 0, 1e3}).spheres[0], unit_sphere_at({0, 0, 1e3})));
  CHECK(needs_compensation(unit_sphere_at({0, 0, 1e4}).spheres[0], unit_sphere_at({0, 0, 1e4})));
  CHECK(needs_compensation(unit_sphere_at({3e3, -4e3, 0}).spheres[0], unit_sphere_at({3e3, -4e3, 0})));
  // Translated: far from the world origin, but 3 from the camera.
  Scene near = unit_sphere_at({1e5, 0, 3});
  near.camera.position = {1e5, 0, 0};
  CHECK_FALSE(needs_compensation(near.spheres[0], near));
  // A finer epsilon asks more of the same sphere; none at all, everything.
  Scene fine = unit_sphere_at({0, 0, 100});
  fine.epsilon = 1e-5;
  CHECK(needs_compensation(fine.spheres[0], fine));
  fine.epsilon = 0;
  CHECK(needs_compensation(unit_sphere_at({0, 0, 3}).spheres[0], fine));
}

TEST_CASE("the decision reaches the sphere buffer and the robust build options", "[conditioning][options]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  for (Precision p : all_precisions()) {
    const SceneData d = pack_scene(demo, p, 8, 8, 3);
    REQUIRE(d.spheres.size() == 4);
    CHECK(d.spheres[0].compensated == 0);
    CHECK(d.spheres[3].compensated == 1);
  }
  CHECK(kernel_features(demo, 3).compensated == std::vector<bool>{false, false, false, true});
  CHECK(kernel_features(demo, 3).compensated_spheres() == 1);

  KernelConfig robust;  // specialized
  // Mixed: each sphere's flag as a constant with the unrolled counts...
  const auto mixed = build_option_list(robust, kernel_features(demo, 3), false);
  CHECK(has(mixed, "-DCLRT_COMPENSATED_FLAGS=0,0,0,1"));
  CHECK_FALSE(has_prefix(mixed, "-DCLRT_COMPENSATED_SPHERES"));
  // ...and read at run time past the unroll bound.
  Scene big = demo;
  big.spheres.insert(big.spheres.begin(), kMaxUnrolledSpheres, demo.spheres[0]);
  const auto runtime = build_option_list(robust, kernel_features(big, 3), false);
  CHECK_FALSE(has_prefix(runtime, "-DCLRT_COMPENSATED"));
  Scene units = demo;
  units.spheres.pop_back();
  CHECK(has(build_option_list(robust, kernel_features(units, 3), false), "-DCLRT_COMPENSATED_SPHERES=0"));
  CHECK_FALSE(has_prefix(build_option_list(robust, kernel_features(units, 3), false), "-DCLRT_COMPENSATED_FLAGS"));
  Scene floor = demo;
  floor.spheres.erase(floor.spheres.begin(), floor.spheres.begin() + 3);
  CHECK(has(build_option_list(robust, kernel_features(floor, 3), false), "-DCLRT_COMPENSATED_SPHERES=1"));
  Scene empty = demo;
  empty.spheres.clear();
  CHECK(has(build_option_list(robust, kernel_features(empty, 3), false), "-DCLRT_COMPENSATED_SPHERES=0"));
  // Features differ when a flag does, so the program is rebuilt.
  CHECK(kernel_features(units, 3).compensated_spheres() == 0);
  Scene coarse = floor;
  coarse.epsilon = 1;  // the floor's error, 1.2e-3, far below it
  CHECK(kernel_features(coarse, 3).compensated_spheres() == 0);
  CHECK(kernel_features(coarse, 3) != kernel_features(floor, 3));

  // Only specialized robust builds get it: the generic one branches per
  // sphere, the other precisions ignore the flag.
  KernelConfig generic;
  generic.specialize = false;
  CHECK_FALSE(has_prefix(build_option_list(generic, kernel_features(demo, 3), false), "-DCLRT_COMPENSATED"));
  CHECK_FALSE(has_prefix(build_option_list(generic, kernel_features(units, 3), false), "-DCLRT_COMPENSATED"));
  for (Precision p : all_precisions()) {
    if (p == Precision::Robust) continue;
    KernelConfig other;
    other.precision = p;
    CHECK_FALSE(has_prefix(build_option_list(other, kernel_features(demo, 3), true), "-DCLRT_COMPENSATED"));
    CHECK_FALSE(has_prefix(build_option_list(other, kernel_features(units, 3), true), "-DCLRT_COMPENSATED"));
  }
}

}  // namespace test_conditioning

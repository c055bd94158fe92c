// test_random_scene.cpp - the random-sphere generator: the same settings give
// the same scene, the scene is valid, and it survives JSON exactly.
#include <catch2/catch.hpp>
#include <cmath>

#include "cli_run.hpp"
#include "scene/random_scene.hpp"
#include "scene/scene_json.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_random_scene {

using namespace clrt;

TEST_CASE("random scenes: N spheres plus the floor, the same for the same seed", "[scene][generate]") {
  RandomSceneSettings settings;
  settings.count = 500;
  settings.seed = 42;
  const Scene a = random_scene(settings), b = random_scene(settings);
  REQUIRE(a.spheres.size() == 501);
  CHECK(scene_to_json(a) == scene_to_json(b));
  settings.seed = 43;
  CHECK(scene_to_json(random_scene(settings)) != scene_to_json(a));
  for (const Sphere& s : a.spheres) {
    // Multiples of 1/64 (whole colours): JSON holds them exactly.
    CHECK(std::ldexp(s.center.x, 6) == std::round(std::ldexp(s.center.x, 6)));
    CHECK(std::ldexp(s.radius, 6) == std::round(std::ldexp(s.radius, 6)));
    CHECK(s.color.x == std::floor(s.color.x));
    CHECK(s.radius > 0);
  }
  // Valid, and the same after a round trip through compact JSON.
  const Scene back = parse_scene(scene_to_json(a, JsonStyle::Compact), "generated");
  CHECK(scene_to_json(back) == scene_to_json(a));
}

TEST_CASE("clrt generate writes a scene clrt reads, bad counts are bad input", "[cli][generate]") {
  clrt_test::TempDir dir;
  auto r = clrt_test::run_clrt({"generate", "--spheres", "50", "--seed", "3", "-o", dir / "g.json"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const Scene s = load_scene(dir / "g.json");
  CHECK(s.spheres.size() == 51);
  for (const char* bad : {"-1", "2000001", "many"}) {
    auto b = clrt_test::run_clrt({"generate", "--spheres", bad, "-o", dir / "h.json"});
    CHECK(b.status == 2);
    CHECK(b.one_line_error());
  }
  auto f = clrt_test::run_clrt({"generate", "--fill", "2", "-o", dir / "h.json"});
  CHECK(f.status == 2);
}

}  // namespace test_random_scene

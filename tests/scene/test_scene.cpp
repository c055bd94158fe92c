// test_scene.cpp - scene parsing, defaults and validation.
#include <catch2/catch.hpp>

#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

using namespace clrt;

TEST_CASE("demo scene parses with the book's values", "[scene]") {
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  REQUIRE(s.spheres.size() == 4);
  REQUIRE(s.lights.size() == 3);
  CHECK(s.recursion_depth == 3);
  CHECK(s.epsilon == 0.001);
  CHECK(s.spheres[3].radius == 5000);
  CHECK(s.spheres[3].center.y == -5001);
  CHECK(s.spheres[0].specular == 500);
  CHECK(s.spheres[1].reflective == 0.4);
  CHECK(s.lights[0].type == LightType::Ambient);
  CHECK(s.lights[1].type == LightType::Point);
  CHECK(s.lights[2].type == LightType::Directional);
  // The book's [1, 4, 4], rescaled by 2^-3 (exact; lighting ignores the length).
  CHECK(s.lights[2].vec.x == 0.125);
  CHECK(s.lights[2].vec.z == 0.5);
}

TEST_CASE("optional keys take their documented defaults", "[scene]") {
  Scene s = parse_scene(R"({"spheres": [{"center": [0,0,3], "radius": 1, "color": [1,2,3]}]})", "t");
  CHECK(s.camera.position.x == 0);
  CHECK(s.camera.rotation[0] == 1);
  CHECK(s.camera.rotation[4] == 1);
  CHECK(s.camera.rotation[1] == 0);
  CHECK(s.camera.viewport_w == 1);
  CHECK(s.camera.projection_plane_d == 1);
  CHECK(s.background.x == 0);
  CHECK(s.recursion_depth == 3);
  CHECK(s.epsilon == 0.001);
  CHECK(s.spheres[0].specular == -1);
  CHECK(s.spheres[0].reflective == 0);
  CHECK(s.lights.empty());
}

TEST_CASE("every shipped scene parses", "[scene]") {
  for (const char* f : {"scenes/cgfs-demo.json", "scenes/cgfs-book-ch4.json", "scenes/cgfs-camera.json"})
    CHECK_NOTHROW(clrt_test::load(f));
  Scene cam = clrt_test::load("scenes/cgfs-camera.json");
  CHECK(cam.camera.position.x == 3);
  CHECK(cam.camera.rotation[2] == Approx(-0.7071));
}

TEST_CASE("scene round-trips through JSON", "[scene]") {
  Scene a = clrt_test::load("scenes/cgfs-camera.json");
  Scene b = parse_scene(scene_to_json(a), "roundtrip");
  REQUIRE(b.spheres.size() == a.spheres.size());
  CHECK(b.camera.rotation == a.camera.rotation);
  CHECK(b.spheres[2].center.x == a.spheres[2].center.x);
  CHECK(b.lights[2].vec.y == a.lights[2].vec.y);
}

namespace {
std::string error_of(const std::string& json) {
  try {
    parse_scene(json, "bad.json");
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("invalid scenes are rejected with a message naming the problem", "[scene]") {
  using Catch::Matchers::Contains;
  CHECK_THAT(error_of("{"), Contains("bad.json: malformed JSON"));
  CHECK_THAT(error_of("[]"), Contains("expected an object"));
  CHECK_THAT(error_of(R"({"spheres": [], "foo": 1})"), Contains("unknown key \"foo\""));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0,3], "radius": -1, "color": [1,2,3]}]})"),
             Contains("spheres[0].radius: must be > 0"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0,3], "radius": 0, "color": [1,2,3]}]})"),
             Contains("spheres[0].radius: must be > 0"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0], "radius": 1, "color": [1,2,3]}]})"),
             Contains("spheres[0].center: expected an array of 3 numbers"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0,"x"], "radius": 1, "color": [1,2,3]}]})"),
             Contains("spheres[0].center[2]: expected a number"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0,1], "radius": 1, "color": [1,2,3], "reflective": 2}]})"),
             Contains("spheres[0].reflective: must be in [0, 1]"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0,1], "radius": 1, "color": [1,2,300]}]})"),
             Contains("spheres[0].color: color components must be in [0, 255]"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0,0,1], "radius": 1, "color": [1,2,3], "specular": -2}]})"),
             Contains("spheres[0].specular"));
  CHECK_THAT(error_of(R"({"lights": [{"type": "spot", "intensity": 1}]})"), Contains("unknown light type \"spot\""));
  CHECK_THAT(error_of(R"({"lights": [{"type": "directional", "intensity": 1, "direction": [0,0,0]}]})"),
             Contains("lights[0].direction: must not be the zero vector"));
  CHECK_THAT(error_of(R"({"lights": [{"type": "point", "intensity": 1}]})"), Contains("needs \"position\""));
  CHECK_THAT(error_of(R"({"lights": [{"type": "ambient", "intensity": 1, "position": [0,0,0]}]})"),
             Contains("unknown key \"position\""));
  CHECK_THAT(error_of(R"({"recursion_depth": 1000})"), Contains("recursion_depth: must be in [0, 64]"));
  CHECK_THAT(error_of(R"({"recursion_depth": 1.5})"), Contains("recursion_depth: expected an integer"));
  CHECK_THAT(error_of(R"({"camera": {"viewport": [0, 1]}})"), Contains("camera.viewport: sizes must be > 0"));
  CHECK_THAT(error_of(R"({"camera": {"rotation": [[1,0,0],[0,1,0]]}})"), Contains("camera.rotation"));
  // JSON has no NaN/Inf literals; an overflowing literal must not become inf.
  CHECK_THAT(error_of(R"({"epsilon": 1e400})"), Contains("bad.json"));
  CHECK_THAT(error_of(R"({"epsilon": NaN})"), Contains("malformed JSON"));
  // Strings from the file are echoed escaped: the message stays one line
  // (found by tests/fuzz/fuzz_scene.cpp).
  CHECK(error_of(R"({"a\nb": 1})") == R"(bad.json: unknown key "a\nb")");
  CHECK(error_of(R"({"lights": [{"type": "x\ty", "intensity": 1}]})") ==
        R"(bad.json: lights[0].type: unknown light type "x\ty" (expected ambient, point or directional))");
}

TEST_CASE("a missing scene file is a clear error", "[scene]") {
  try {
    load_scene("/nonexistent/scene.json");
    FAIL("no error");
  } catch (const UserError& e) {
    CHECK(std::string(e.what()) == "/nonexistent/scene.json: cannot open scene file: No such file or directory");
  }
}

// test_scene_overrides.cpp - `-D PATH=VALUE`: values set as if the scene
// file said so, checked by their keys' rules, each error kind one message
// naming the -D.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "scene/random_scene.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_scene_overrides {

using namespace clrt;

namespace {

const std::string& demo_text() {
  static const std::string text = clrt_test::slurp(clrt_test::source_path("scenes/cgfs-demo.json"));
  return text;
}

Scene with(const std::string& text, const std::vector<std::string>& overrides) {
  return parse_scene(text, "s.json", {}, parse_overrides(overrides));
}

// The error of reading `text` with `overrides` (parse_overrides' or the reader's).
std::string error_of(const std::string& text, const std::vector<std::string>& overrides) {
  try {
    with(text, overrides);
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}

// The scene file edited: `edit` applied to its JSON document.
template <class Edit>
Scene edited(const std::string& text, Edit&& edit) {
  nlohmann::json doc = nlohmann::json::parse(text);
  edit(doc);
  return parse_scene(doc.dump(), "edited.json");
}

}  // namespace

TEST_CASE("overrides set values as an edited scene file would, and add the keys a file leaves out", "[scene]") {
  const Scene a = with(demo_text(), {"recursion_depth=5", "camera.position=[0,1,-2]", "spheres.2.reflective=0.8",
                                     "lights.1.intensity=0.4", "spheres.0.transparency=0.5",
                                     "lights[2].direction=[-1, 2, 0.5]", "camera.aspect=\"image\""});
  const Scene b = edited(demo_text(), [](nlohmann::json& d) {
    d["recursion_depth"] = 5;
    d["camera"]["position"] = {0, 1, -2};
    d["spheres"][2]["reflective"] = 0.8;
    d["lights"][1]["intensity"] = 0.4;
    d["spheres"][0]["transparency"] = 0.5;
    d["lights"][2]["direction"] = {-1, 2, 0.5};
    d["camera"]["aspect"] = "image";
  });
  CHECK(scene_to_json(a) == scene_to_json(b));
  CHECK(a.recursion_depth == 5);
  CHECK(a.spheres[0].transparency == 0.5);
  CHECK(a.lights[2].scale_exponent == b.lights[2].scale_exponent);  // rescaled as the file's would be
  // Unchanged without -D.
  CHECK(scene_to_json(with(demo_text(), {})) == scene_to_json(parse_scene(demo_text(), "s.json")));
}

TEST_CASE("overrides add an object the file does not have, replace whole values, elements and arrays", "[scene]") {
  // No camera in the text: -D makes one, with the table's defaults for the rest.
  const Scene cam = with("{}", {"camera.viewport=[2, 1]"});
  CHECK(cam.camera.viewport_w == 2);
  CHECK(cam.camera.projection_plane_d == 1);
  // A whole element, and a key of it set again by a deeper -D (the deeper one wins).
  const Scene one = with(demo_text(), {R"(spheres.1={"center": [0, 0, 9], "radius": 2, "color": [1, 2, 3]})",
                                       "spheres.1.radius=3"});
  REQUIRE(one.spheres.size() == 4);
  CHECK(one.spheres[1].center.z == 9);
  CHECK(one.spheres[1].radius == 3);
  CHECK(one.spheres[1].specular == -1);  // the table's default: nothing of the file's sphere 1 is left
  // A whole array, also where the file has none.
  const Scene all = with(demo_text(), {R"(spheres=[{"center": [0, 0, 3], "radius": 1, "color": [9, 9, 9]}])",
                                       R"(planes=[{"point": [0, -1, 0], "normal": [0, 3, 0], "color": [1, 1, 1]}])"});
  REQUIRE(all.spheres.size() == 1);
  CHECK(all.spheres[0].color.x == 9);
  REQUIRE(all.planes.size() == 1);
  CHECK(all.planes[0].normal.y == 0.75);  // rescaled, as a file's normal is
  // A value the file has in error is replaced before it is read.
  CHECK(with(R"({"epsilon": -1})", {"epsilon=0.5"}).epsilon == 0.5);
}

TEST_CASE("an override of the last sphere of a large scene, read as it streams", "[scene]") {
  RandomSceneSettings settings;
  settings.count = 1999;
  const std::string text = scene_to_json(random_scene(settings), JsonStyle::Compact);
  const Scene s = with(text, {"spheres.1999.radius=0.25", "spheres.0.specular=7"});
  REQUIRE(s.spheres.size() == 2000);
  CHECK(s.spheres[1999].radius == 0.25);
  CHECK(s.spheres[0].specular == 7);
  CHECK(error_of(text, {"spheres.2000.radius=1"}) == "-D spheres.2000.radius=1: the scene has 2000 spheres");
}

TEST_CASE("each kind of bad -D is one message naming it", "[scene]") {
  const std::string& demo = demo_text();
  // A path the scene does not have: an index past the end, an array the file lacks.
  CHECK(error_of(demo, {"spheres.9.radius=1"}) == "-D spheres.9.radius=1: the scene has 4 spheres");
  CHECK(error_of(R"({"spheres": [{"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3]}]})",
                 {"spheres.1.radius=1"}) == "-D spheres.1.radius=1: the scene has 1 sphere");
  CHECK(error_of(demo, {"planes.0.normal=[0,1,0]"}) == "-D planes.0.normal=[0,1,0]: the scene has 0 planes");
  // A path the format does not have.
  CHECK(error_of(demo, {"spheres.0.radus=1"}) ==
        R"(-D spheres.0.radus=1: spheres[0]: unknown key "radus"; did you mean "radius"?)");
  CHECK(error_of(demo, {"colour=[1,2,3]"}) == R"(-D colour=[1,2,3]: unknown key "colour")");
  CHECK(error_of(demo, {"spheres.x.radius=1"}) ==
        R"(-D spheres.x.radius=1: spheres: expected an index into the array (0, 1, ...), got "x")");
  CHECK(error_of(demo, {"camera.position.1=5"}) ==
        "-D camera.position.1=5: camera.position: is one value, set whole (-D camera.position=...): it has no keys "
        "or elements of its own");
  CHECK(error_of(demo, {"spheres..radius=1"}) ==
        R"(-D spheres..radius=1: malformed path "spheres..radius" (keys and indices separated by dots: spheres.0.radius))");
  CHECK(error_of(demo, {"epsilon"}) ==
        "-D epsilon: expected PATH=VALUE (e.g. -D recursion_depth=5, -D spheres.0.radius=2)");
  CHECK(error_of(demo, {"epsilon=0.1", "epsilon=0.2"}) == "-D epsilon=0.2: epsilon is given twice");
  CHECK(error_of(demo, {"spheres.0.radius=1", "spheres[0].radius=2"}) ==
        "-D spheres[0].radius=2: spheres[0].radius is given twice");
  // A value that is not JSON.
  CHECK_THAT(error_of(demo, {"epsilon=0.1.2"}), Catch::Matchers::StartsWith("-D epsilon=0.1.2: the value is not JSON: "
                                                                            "malformed JSON: parse error"));
  CHECK_THAT(error_of(demo, {"camera.aspect=image"}),
             Catch::Matchers::EndsWith(R"( (a string is quoted: -D 'camera.aspect="image"'))"));
  CHECK_THAT(error_of(demo, {"epsilon=1e400"}),
             Catch::Matchers::StartsWith("-D epsilon=1e400: the value is not JSON: number out of range"));
  // A value its key's rules refuse: the reader's own texts.
  CHECK(error_of(demo, {"spheres.2.reflective=2"}) == "-D spheres.2.reflective=2: must be in [0, 1] (got 2)");
  CHECK(error_of(demo, {"camera.position=[0,1e9,0]"}) ==
        "-D camera.position=[0,1e9,0]: camera.position[1]: must be within ±1e+08, the range clrt renders in float32 "
        "(got 1e+09)");
  CHECK(error_of(demo, {"recursion_depth=1.5"}) == "-D recursion_depth=1.5: expected an integer, got number");
  CHECK(error_of(demo, {"spheres.0.color=\"red\""}) ==
        "-D spheres.0.color=\"red\": expected an array of 3 numbers");
  CHECK(error_of(demo, {"lights.0.type=\"spot\""}) ==
        R"(-D lights.0.type="spot": unknown light type "spot" (expected ambient, point or directional))");
  CHECK(error_of(demo, {"lights.0.direction=[1,1,1]"}) ==
        R"(-D lights.0.direction=[1,1,1]: lights[0]: unknown key "direction")");
  CHECK(error_of(demo, {"lights.1.type=\"directional\""}) ==
        R"(-D lights.1.type="directional": lights[1]: unknown key "position")");
  CHECK(error_of(demo, {"lights.2.direction=[0,0,0]"}) == "-D lights.2.direction=[0,0,0]: must not be the zero vector");
  CHECK(error_of(demo, {R"(spheres.1={"radius": 1})"}) == R"(-D spheres.1={"radius": 1}: missing "center")");
  CHECK(error_of(demo, {"spheres=[1]"}) == "-D spheres=[1]: spheres[0]: expected an object, got number");
  // A rule over the whole scene names the file: the scene is as if it said so.
  CHECK(error_of(demo, {"lights.0.intensity=1e30", "lights.1.intensity=1e30"}) ==
        "s.json: lights: the intensities add up to 2e+30, more than 1e+30 (colours would overflow float32)");
  // A -D that chose a light's type is named where the type makes a key unknown or missing.
  CHECK(error_of(demo, {"lights.0.type=\"point\""}) == R"(-D lights.0.type="point": lights[0]: point light needs "position")");
}

}  // namespace test_scene_overrides

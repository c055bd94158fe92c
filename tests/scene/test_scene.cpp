// test_scene.cpp - scene parsing, defaults and validation.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli_run.hpp"
#include "scene/random_scene.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_scene {

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

namespace {
// The error of loading `text` from a stream limited to `max_bytes`.
std::string stream_error_of(const std::string& text, size_t max_bytes = kMaxSceneBytes) {
  std::istringstream in(text);
  try {
    parse_scene(in, "bad.json", {max_bytes});
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("duplicate keys are rejected in every object, naming it", "[scene]") {
  const std::string sphere = R"({"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3]})";
  CHECK(error_of(R"({"epsilon": 0.1, "epsilon": 0.2})") == R"(bad.json: duplicate key "epsilon")");
  CHECK(error_of(R"({"spheres": [], "lights": [], "spheres": []})") == R"(bad.json: duplicate key "spheres")");
  CHECK(error_of(R"({"camera": {"position": [0, 0, 0], "viewport": [1, 1], "position": [0, 0, 1]}})") ==
        R"(bad.json: camera: duplicate key "position")");
  CHECK(error_of(R"({"spheres": [)" + sphere +
                 R"(, {"center": [0, 0, 3], "radius": 1, "radius": 2, "color": [1, 2, 3]}]})") ==
        R"(bad.json: spheres[1]: duplicate key "radius")");
  CHECK(error_of(R"({"lights": [{"type": "ambient", "intensity": 0.2, "type": "ambient"}]})") ==
        R"(bad.json: lights[0]: duplicate key "type")");
  CHECK(error_of(R"({"lights": [{"type": "point", "intensity": 0.2, "position": [0, 0, 0], "intensity": 0.3}]})") ==
        R"(bad.json: lights[0]: duplicate key "intensity")");
  // The streaming loader says the same.
  CHECK(stream_error_of(R"({"spheres": [)" + sphere + ", " + sphere + R"(], "spheres": []})") ==
        R"(bad.json: duplicate key "spheres")");
}

TEST_CASE("deep nesting is rejected at the first container the format does not have", "[scene]") {
  // The format nests 4 deep; the parser stops at the first array or object
  // anywhere else, so a million brackets cost neither memory nor time.
  const std::string deep(1000000, '[');
  CHECK(error_of(deep) == "bad.json: expected an object, got array");
  CHECK(error_of(R"({"spheres": )" + deep) == "bad.json: spheres[0]: expected an object, got array");
  CHECK(error_of(R"({"spheres": [{"center": )" + deep) ==
        "bad.json: spheres[0].center[0]: expected a number, got array");
  CHECK(error_of(R"({"camera": {"rotation": )" + deep) ==
        "bad.json: camera.rotation[0][0]: expected a number, got array");
  CHECK(error_of(R"({"lights": [{"intensity": )" + deep) ==
        "bad.json: lights[0].intensity: expected a number, got array");
  CHECK(error_of(R"({"epsilon": {"a": {"a": {"a": {"a": {"a": 1}}}}}})") ==
        "bad.json: epsilon: expected a number, got object");
  CHECK(error_of(R"({"camera": {"camera": {"camera": {}}}})") == R"(bad.json: camera: unknown key "camera")");
  CHECK(stream_error_of(R"({"spheres": [{"color": )" + deep) ==
        "bad.json: spheres[0].color[0]: expected a number, got array");
}

TEST_CASE("a scene file over the size limit is rejected, whatever it is", "[scene]") {
  clrt_test::TempDir dir;
  const std::string text = R"({"spheres": [{"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3]}]})";
  const std::string path = dir.write("s.json", text);
  CHECK(load_scene(path, {text.size()}).spheres.size() == 1);  // exactly at the limit
  try {
    load_scene(path, {text.size() - 1});
    FAIL("no error");
  } catch (const UserError& e) {
    CHECK(std::string(e.what()) == path + ": scene file is larger than " + std::to_string(text.size() - 1) + " bytes");
  }
  // A stream is counted as it is read (64 KiB chunks): a valid scene
  // followed by spaces, and an endless array of spheres.
  CHECK_THAT(stream_error_of(text + std::string(300000, ' '), 200000),
             Catch::Matchers::Equals("bad.json: scene file is larger than 200000 bytes"));
  std::string many = R"({"spheres": [)";
  while (many.size() < (3 << 20)) many += R"({"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3]},)";
  CHECK(stream_error_of(many, size_t(2) << 20) == "bad.json: scene file is larger than 2 MiB");
  CHECK_THAT(stream_error_of(many), Catch::Matchers::Contains("malformed JSON"));  // no limit: it just ends
  // A FIFO is read as a stream too.
  const std::string fifo = dir / "pipe.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << text << std::string(100000, ' '); });
  std::string error = "(no error)";
  try {
    load_scene(fifo, {70000});
  } catch (const UserError& e) {
    error = e.what();
  }
  writer.join();
  CHECK(error == fifo + ": scene file is larger than 70000 bytes");
  std::thread writer2([&] { std::ofstream(fifo, std::ios::binary) << text; });
  const Scene from_fifo = load_scene(fifo);
  writer2.join();
  CHECK(from_fifo.spheres.size() == 1);
  // Not a scene file: one clear error each.
  try {
    load_scene("/dev/zero");
    FAIL("no error");
  } catch (const UserError& e) {
    CHECK(std::string(e.what()) == "/dev/zero: malformed JSON: NUL byte at offset 0");
  }
  try {
    load_scene(dir.path().string());
    FAIL("no error");
  } catch (const UserError& e) {
    CHECK(std::string(e.what()) == dir.path().string() + ": cannot open scene file: is a directory");
  }
}

TEST_CASE("a NUL byte is an error wherever it is, in text and in streams", "[scene]") {
  const std::string text = std::string("{\"spheres\": []}\0{\"x\":1}", 24);
  CHECK(error_of(text) == "bad.json: malformed JSON: NUL byte at offset 15");
  CHECK(stream_error_of(text) == "bad.json: malformed JSON: NUL byte at offset 15");
  // Past the first chunk the stream reads.
  std::string late = "{\"epsilon\": 0.5" + std::string(100000, ' ') + "}";
  late[70000] = '\0';
  CHECK(stream_error_of(late) == "bad.json: malformed JSON: NUL byte at offset 70000");
}

TEST_CASE("a 2000-sphere random scene survives JSON exactly, from text, streams and files", "[scene]") {
  RandomSceneSettings settings;
  settings.count = 1999;
  settings.seed = 7;
  const Scene a = random_scene(settings);
  REQUIRE(a.spheres.size() == 2000);
  auto same = [&](const Scene& b) {
    REQUIRE(b.spheres.size() == a.spheres.size());
    for (size_t i = 0; i < a.spheres.size(); ++i) {
      const Sphere &x = a.spheres[i], &y = b.spheres[i];
      INFO("sphere " << i);
      CHECK((x.center.x == y.center.x && x.center.y == y.center.y && x.center.z == y.center.z));
      CHECK((x.color.x == y.color.x && x.color.y == y.color.y && x.color.z == y.color.z));
      CHECK(x.radius == y.radius);
      CHECK(x.specular == y.specular);
      CHECK(x.reflective == y.reflective);
    }
    REQUIRE(b.lights.size() == a.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) {
      CHECK(b.lights[i].type == a.lights[i].type);
      CHECK(b.lights[i].intensity == a.lights[i].intensity);
      CHECK((b.lights[i].vec.x == a.lights[i].vec.x && b.lights[i].vec.y == a.lights[i].vec.y &&
             b.lights[i].vec.z == a.lights[i].vec.z));
    }
    CHECK(b.camera.position.x == a.camera.position.x);
    CHECK(b.camera.position.z == a.camera.position.z);
    CHECK(b.recursion_depth == a.recursion_depth);
  };
  const std::string compact = scene_to_json(a, JsonStyle::Compact), pretty = scene_to_json(a);
  same(parse_scene(compact, "compact"));
  same(parse_scene(pretty, "pretty"));
  std::istringstream in(pretty);
  same(parse_scene(in, "stream"));
  clrt_test::TempDir dir;
  same(load_scene(dir.write("g.json", compact)));
  // Written back, the text is the same.
  CHECK(scene_to_json(parse_scene(compact, "again"), JsonStyle::Compact) == compact);
  CHECK(scene_to_json(parse_scene(pretty, "again")) == pretty);
}

TEST_CASE("error messages name the path of the value, in any order of keys", "[scene]") {
  RandomSceneSettings settings;
  settings.count = 1999;
  const Scene a = random_scene(settings);
  std::string text = scene_to_json(a, JsonStyle::Compact);
  // The last sphere, radius made negative.
  const size_t at = text.rfind("\"radius\":");
  text.insert(at + 9, "-");
  CHECK_THAT(error_of(text), Catch::Matchers::StartsWith("bad.json: spheres[1999].radius: must be > 0 (got -"));
  CHECK(error_of(R"({"spheres": [{"radius": 1, "color": [1, 2, 3]}]})") == R"(bad.json: spheres[0]: missing "center")");
  CHECK(error_of(R"({"spheres": [{"color": [1, 2, 3], "center": [0, 0, 1e9], "radius": 1}]})") ==
        "bad.json: spheres[0].center[2]: must be within ±1e+08, the range clrt renders in float32 (got 1e+09)");
  CHECK(error_of(R"({"camera": {"rotation": [[1, 0, 0], [0, 1], [0, 0, 1]]}})") ==
        "bad.json: camera.rotation[1]: expected an array of 3 numbers");
  CHECK(error_of(R"({"camera": {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]]}})") ==
        "bad.json: camera.rotation: expected a 3x3 array of numbers");
  CHECK(error_of(R"({"camera": {"viewport": [1, 1, 1]}})") ==
        "bad.json: camera.viewport: expected an array of 2 numbers");
  CHECK(error_of(R"({"background": [0, 0, 0, 0]})") == "bad.json: background: expected an array of 3 numbers");
  CHECK(error_of(R"({"background": [0, null, 0]})") == "bad.json: background[1]: expected a number, got null");
  CHECK(error_of(R"({"spheres": [{"center": [0, 0, 3], "radius": true, "color": [1, 2, 3]}]})") ==
        "bad.json: spheres[0].radius: expected a number, got boolean");
  CHECK(error_of(R"({"spheres": [1]})") == "bad.json: spheres[0]: expected an object, got number");
  CHECK(error_of(R"({"lights": {}})") == "bad.json: lights: expected an array, got object");
  CHECK(error_of(R"({"lights": [{"type": 1, "intensity": 1}]})") == "bad.json: lights[0].type: expected a string");
  CHECK(error_of(R"({"lights": [{"intensity": 1}]})") == R"(bad.json: lights[0]: missing "type")");
  CHECK(error_of(R"({"lights": [{"type": "point", "position": [0, 0, 0]}]})") ==
        R"(bad.json: lights[0]: missing "intensity")");
  // The type may come after the keys it decides on.
  CHECK(error_of(R"({"lights": [{"direction": [0, 0, 1], "intensity": 1, "type": "point"}]})") ==
        R"(bad.json: lights[0]: unknown key "direction")");
  CHECK(error_of(R"({"lights": [{"direction": [0, 0, 1], "intensity": 1, "type": "directional"}]})") == "(no error)");
  CHECK(error_of(R"({"lights": [{"type": "directional", "direction": [0, 0, 0], "intensity": 1}]})") ==
        "bad.json: lights[0].direction: must not be the zero vector");
  CHECK(error_of(R"({"recursion_depth": -1})") == "bad.json: recursion_depth: must be in [0, 64] (got -1)");
  CHECK(error_of(R"({"recursion_depth": "3"})") == "bad.json: recursion_depth: expected an integer, got string");
  CHECK(error_of("{} {}") ==
        "bad.json: malformed JSON: parse error at line 1, column 4: syntax error while parsing "
        "value - unexpected '{'; expected end of input");
  CHECK(error_of(R"({"epsilon": 1e400})") == "bad.json: number out of range: number overflow parsing '1e400'");
  // A malformed token is quoted cut short: the message stays one short line.
  const std::string unterminated = error_of("{\"" + std::string(100000, 'k'));
  CHECK_THAT(unterminated, Catch::Matchers::StartsWith("bad.json: malformed JSON: "));
  CHECK_THAT(unterminated, Catch::Matchers::Contains("kkk...' (100001 bytes); expected string literal"));
  CHECK(unterminated.size() < 300);
}

TEST_CASE("sphere and light counts are limited", "[scene]") {
  // 100 000 lights are a scene clrt renders (tests/app/test_hardening.cpp).
  std::string lights;
  for (size_t i = 0; i < 100000; ++i) lights += R"({"type": "ambient", "intensity": 0},)";
  lights.pop_back();
  CHECK(parse_scene(R"({"lights": [)" + lights + "]}", "many.json").lights.size() == 100000);
  // The limits, lowered.
  SceneLimits limits;
  limits.spheres = 3;
  limits.lights = 2;
  const std::string sphere = R"({"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3]})";
  const std::string light = R"({"type": "ambient", "intensity": 0.1})";
  CHECK(parse_scene("{\"spheres\": [" + sphere + "," + sphere + "," + sphere + "]}", "s.json", limits).spheres.size() ==
        3);
  std::istringstream four("{\"spheres\": [" + sphere + "," + sphere + "," + sphere + "," + sphere + "]}");
  CHECK_THROWS_WITH(parse_scene(four, "s.json", limits), "s.json: spheres: more than 3 spheres, the most clrt loads");
  CHECK_THROWS_WITH(parse_scene("{\"lights\": [" + light + "," + light + "," + light + "]}", "s.json", limits),
                    "s.json: lights: more than 2 lights, the most clrt loads");
  // Text is held to the size limit too.
  limits.bytes = 10;
  CHECK_THROWS_WITH(parse_scene(R"({"spheres": []})", "s.json", limits), "s.json: scene file is larger than 10 bytes");
}

}  // namespace test_scene

// test_viewport.cpp - the viewport against the image (scene/viewport.hpp):
// the book's stretch by default, a fitted viewport with "aspect": "image"
// or --aspect image, the scene key, and the warning for non-square pixels.
#include <catch2/catch.hpp>
#include <string>

#include "cli_run.hpp"
#include "scene/scene_json.hpp"
#include "scene/viewport.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_viewport {

using namespace clrt;
using Catch::Matchers::Contains;

TEST_CASE("the book's viewport is kept unless the camera asks for the image's aspect", "[scene][viewport]") {
  Camera book;  // viewport 1 x 1
  const Camera same = camera_for_image(book, 1920, 1080);
  CHECK(same.viewport_w == 1);
  CHECK(same.viewport_h == 1);
  CHECK_FALSE(square_pixels(same, 1920, 1080));
  CHECK(pixel_aspect(same, 1920, 1080) == Approx(1080.0 / 1920.0));
  CHECK(square_pixels(same, 600, 600));
}

TEST_CASE("\"aspect\": \"image\" keeps the viewport's larger side and fits the other", "[scene][viewport]") {
  Camera c;
  c.aspect_from_image = true;
  const Camera landscape = camera_for_image(c, 1920, 1080);
  CHECK(landscape.viewport_w == 1);
  CHECK(landscape.viewport_h == Approx(0.5625));
  CHECK(square_pixels(landscape, 1920, 1080));
  const Camera portrait = camera_for_image(c, 1080, 1920);
  CHECK(portrait.viewport_h == 1);
  CHECK(portrait.viewport_w == Approx(0.5625));
  CHECK(square_pixels(portrait, 1080, 1920));
  // a wide viewport on a square image: its larger side on both axes
  c.viewport_w = 2;
  const Camera square = camera_for_image(c, 100, 100);
  CHECK(square.viewport_w == 2);
  CHECK(square.viewport_h == 2);
  // the rest of the camera is untouched
  CHECK(square.projection_plane_d == c.projection_plane_d);
}

TEST_CASE("the scene's camera key \"aspect\": parsed, checked, round-tripped", "[scene][viewport]") {
  const Scene fitted = parse_scene(R"({"camera": {"aspect": "image"}})", "a.json");
  CHECK(fitted.camera.aspect_from_image);
  CHECK_FALSE(parse_scene(R"({"camera": {"aspect": "viewport"}})", "a.json").camera.aspect_from_image);
  CHECK_FALSE(parse_scene(R"({"camera": {}})", "a.json").camera.aspect_from_image);
  CHECK(parse_scene(scene_to_json(fitted), "again").camera.aspect_from_image);
  auto error_of = [](const std::string& text) {
    try {
      (void)parse_scene(text, "bad.json");
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK_THAT(error_of(R"({"camera": {"aspect": "wide"}})"),
             Contains("camera.aspect: unknown aspect \"wide\" (expected viewport or image)"));
  CHECK_THAT(error_of(R"({"camera": {"aspect": 1.5}})"), Contains("camera.aspect: expected a string"));
  CHECK_THAT(error_of(R"({"camera": {"aspect": "image", "aspect": "image"}})"), Contains("duplicate"));
}

TEST_CASE("clrt warns about non-square pixels, and --aspect image fits the viewport", "[scene][viewport][cli]") {
  clrt_test::TempDir dir;
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json"), out = dir / clrt_test::image_name("a");
  auto stretched = clrt_test::run_clrt({"render", scene, "--width", "64", "--height", "36", "-o", out});
  REQUIRE(stretched.status == 0);
  CHECK_THAT(stretched.err, Contains("clrt: warning: pixels are not square (0.562:1)"));
  auto fitted =
      clrt_test::run_clrt({"render", scene, "--width", "64", "--height", "36", "--aspect", "image", "-o", out});
  REQUIRE(fitted.status == 0);
  CHECK_THAT(fitted.err, !Contains("warning"));
  // both engines see the fitted camera: the kernel matches the reference
  auto compared = clrt_test::run_clrt(
      {"compare", scene, "--width", "64", "--height", "36", "--aspect", "image", "--fail-percent", "0.05"});
  CHECK(compared.status == 0);
  CHECK_THAT(compared.err, !Contains("warning"));
  auto bad = clrt_test::run_clrt({"render", scene, "--aspect", "wide", "-o", out});
  CHECK(bad.status == 2);
  CHECK(bad.one_line_error());
}

}  // namespace test_viewport

// test_reference.cpp - the reference renderer against values computed by hand
// from the book's formulas (not by running another renderer).
#include <catch2/catch.hpp>
#include <cmath>

#include "edge_scene.hpp"
#include "image/image.hpp"
#include "reference/reference.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_reference {

using namespace clrt;

namespace {
// Pixel (col, row) of an image, channel k.
double px(const Image& img, int col, int row, int k) {
  return img.rgb[(size_t(row) * img.width + col) * 3 + k];
}

Scene single_sphere(const char* extra_sphere, const char* lights, const char* background = "[0,0,0]") {
  std::string j = std::string(R"({"background": )") + background +
                  R"(, "spheres": [{"center": [0,0,5], "radius": 1, "color": [100,50,20])" + extra_sphere +
                  "}], \"lights\": [" + lights + "]}";
  return parse_scene(j, "inline");
}
}  // namespace

TEST_CASE("centre pixel of the demo scene, by hand", "[reference]") {
  // Canvas (0,0) is pixel (300, 299); its ray D = (0,0,1) touches the top of
  // the red sphere (centre (0,-1,3), r 1) at P = (0,0,3), N = (0,1,0), with
  // an exactly zero discriminant in double (b = -6, c = 9).
  //   ambient 0.2
  //   point (2,1,0): L = (2,1,-3), N.L = 1, |L| = sqrt(14), R.V < 0 (no specular)
  //   directional (1,4,4): N.L = 4, |L| = sqrt(33), specular (4/sqrt(33))^500
  // Reflection: R = (0,0,1) from P escapes to the black background.
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  const double i = 0.2 + 0.6 / std::sqrt(14.0) + 0.2 * 4 / std::sqrt(33.0) + 0.2 * std::pow(4 / std::sqrt(33.0), 500);
  Image d0 = render_reference(s, 600, 600, 0);
  CHECK(px(d0, 300, 299, 0) == Approx(255 * i).epsilon(1e-12));
  CHECK(px(d0, 300, 299, 1) == 0);
  CHECK(to_u8(px(d0, 300, 299, 0)) == 127);
  Image d3 = render_reference(s, 600, 600, 3);
  CHECK(px(d3, 300, 299, 0) == Approx(0.8 * 255 * i).epsilon(1e-12));
  CHECK(to_u8(px(d3, 300, 299, 0)) == 102);
  CHECK(d3.hit[size_t(299) * 600 + 300] == 0);
}

TEST_CASE("ambient light only gives the flat sphere colour", "[reference]") {
  Scene s = single_sphere("", R"({"type": "ambient", "intensity": 0.5})");
  Image img = render_reference(s, 64, 64, 3);
  // Centre ray hits; a corner ray (direction (-0.5,0.5,1)) misses.
  CHECK(px(img, 32, 31, 0) == 50);
  CHECK(px(img, 32, 31, 1) == 25);
  CHECK(px(img, 32, 31, 2) == 10);
  CHECK(px(img, 0, 0, 0) == 0);
  CHECK(img.hit[0] == -1);
}

TEST_CASE("point light at the eye: diffuse 1 plus specular 1", "[reference]") {
  // P = (0,0,4), N = (0,0,-1), L = (0,0,-4): N.L/|L| = 1 and R = L, so
  // R.V/(|R||V|) = 1 and the specular term is 1 for any exponent.
  Scene s = single_sphere(R"(, "specular": 37)", R"({"type": "point", "intensity": 1, "position": [0,0,0]})");
  Image img = render_reference(s, 64, 64, 0);
  CHECK(px(img, 32, 31, 0) == Approx(200).epsilon(1e-12));
  CHECK(px(img, 32, 31, 1) == Approx(100).epsilon(1e-12));
  CHECK(px(img, 32, 31, 2) == Approx(40).epsilon(1e-12));
  CHECK(to_u8(img.rgb[(size_t(31) * 64 + 32) * 3]) == 200);
  Scene matte = single_sphere("", R"({"type": "point", "intensity": 1, "position": [0,0,0]})");
  Image m = render_reference(matte, 64, 64, 0);
  CHECK(px(m, 32, 31, 0) == Approx(100).epsilon(1e-12));
}

TEST_CASE("reflection blends local and reflected colour by `reflective`", "[reference]") {
  // The centre ray reflects straight back (R = (0,0,-1)) and escapes to the
  // background (0,0,200): colour = (1-r) * local + r * background.
  Scene s = single_sphere(R"(, "reflective": 0.25)", R"({"type": "ambient", "intensity": 1})", "[0,0,200]");
  Image d1 = render_reference(s, 64, 64, 1);
  CHECK(px(d1, 32, 31, 0) == Approx(0.75 * 100).epsilon(1e-12));
  CHECK(px(d1, 32, 31, 2) == Approx(0.75 * 20 + 0.25 * 200).epsilon(1e-12));
  Image d0 = render_reference(s, 64, 64, 0);  // depth 0: no reflection
  CHECK(px(d0, 32, 31, 2) == Approx(20).epsilon(1e-12));
}

TEST_CASE("shadow rays: point lights only up to the light, directional to infinity", "[reference]") {
  // A blocker sphere between the hit point and the light, and one beyond it.
  const char* base = R"({"spheres": [
      {"center": [0,-1001,0], "radius": 1000, "color": [200,200,200]},
      {"center": [0,1,4], "radius": 0.5, "color": [0,0,0]}],
    "lights": [LIGHT]})";
  auto with = [&](const std::string& light) {
    std::string j = base;
    j.replace(j.find("LIGHT"), 5, light);
    return parse_scene(j, "inline");
  };
  // Row 599 of 600 looks down at the floor below the camera near z ~ 2.
  // Point light at (0,3,4): the blocker at (0,1,4) lies between floor and light.
  Image blocked = render_reference(with(R"({"type": "point", "intensity": 1, "position": [0,3,4]})"), 100, 100, 0);
  // Point light below the blocker (0,0.2,4): blocker is beyond the light.
  Image lit = render_reference(with(R"({"type": "point", "intensity": 1, "position": [0,0.2,4]})"), 100, 100, 0);
  // Find a floor pixel right below the blocker: ray through canvas (0, y).
  // Floor point (0,-1,4) is seen at canvas y = -1/4 * 100 = -25 -> row 74.
  size_t p = size_t(74) * 100 + 50;
  REQUIRE(blocked.hit[p] == 0);
  CHECK(blocked.shadowed[p] == 1);
  CHECK(px(blocked, 50, 74, 0) == 0);
  CHECK(lit.shadowed[p] == 0);
  CHECK(px(lit, 50, 74, 0) > 0);
}

TEST_CASE("supersampling: spp 1 is the book's one ray per pixel, bit for bit", "[reference][spp]") {
  // The default is spp 1, and its sample offset is exactly 0: x + 0.0 == x,
  // so every ray, colour and classification is the single-ray render's.
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  const Image a = render_reference(s, 61, 47, 3), b = render_reference(s, 61, 47, 3, 1);
  CHECK(a.rgb == b.rgb);
  CHECK(a.hit == b.hit);
  CHECK(a.shadowed == b.shadowed);
  // The centre pixel by hand (see "centre pixel of the demo scene"), at spp 1.
  const double i = 0.2 + 0.6 / std::sqrt(14.0) + 0.2 * 4 / std::sqrt(33.0) + 0.2 * std::pow(4 / std::sqrt(33.0), 500);
  CHECK(px(render_reference(s, 600, 600, 0, 1), 300, 299, 0) == Approx(255 * i).epsilon(1e-12));
}

TEST_CASE("supersampling: a pixel cut by a silhouette is the exact mean of its samples", "[reference][spp]") {
  using clrt_test::EdgeScene;
  const Scene s = EdgeScene::scene();
  for (int n = 1; n <= 5; ++n) {
    INFO("spp " << n);
    REQUIRE(EdgeScene::hits(n) >= 0);
    const Image img = render_reference(s, EdgeScene::kWidth, EdgeScene::kHeight, 3, n);
    const int row = EdgeScene::row();
    for (int c = 0; c < 3; ++c) {
      // k of N^2 samples on the sphere: exactly (k c + (N^2 - k) bg) / N^2.
      CHECK(px(img, EdgeScene::col(EdgeScene::kEdgeX), row, c) == EdgeScene::expected(n, c));
      // Well inside and well outside the disc: every sample alike.
      CHECK(px(img, EdgeScene::col(10), row, c) == EdgeScene::kColour[c]);
      CHECK(px(img, EdgeScene::col(25), row, c) == EdgeScene::kBackground[c]);
    }
    // The classification is sample 0's, at offset (o_0, o_0): left of the
    // edge, on the sphere.
    CHECK(img.hit[size_t(row) * img.width + EdgeScene::col(EdgeScene::kEdgeX)] == 0);
  }
  // What the test rests on: 1, 2, 6, 8 and 15 of 1, 4, 9, 16 and 25 samples.
  CHECK(EdgeScene::hits(1) == 1);
  CHECK(EdgeScene::hits(2) == 2);
  CHECK(EdgeScene::hits(3) == 6);
  CHECK(EdgeScene::hits(4) == 8);
  CHECK(EdgeScene::hits(5) == 15);
}

TEST_CASE("supersampling: the classification is the first sample's", "[reference][spp]") {
  // Every sample of pixel (kEdgeX + 1, 0) lies right of the edge and misses.
  // Pixel (-kEdgeX, 0) mirrors the edge pixel: at spp 4 its two right
  // sample columns hit the sphere, and sample 0 (the lower left) misses.
  using clrt_test::EdgeScene;
  const Image img = render_reference(EdgeScene::scene(), EdgeScene::kWidth, EdgeScene::kHeight, 3, 4);
  const size_t row = size_t(EdgeScene::row()) * img.width;
  CHECK(img.hit[row + EdgeScene::col(EdgeScene::kEdgeX + 1)] == -1);
  CHECK(img.hit[row + EdgeScene::col(-EdgeScene::kEdgeX)] == -1);
  CHECK(px(img, EdgeScene::col(-EdgeScene::kEdgeX), EdgeScene::row(), 0) > 0);
}

}  // namespace test_reference

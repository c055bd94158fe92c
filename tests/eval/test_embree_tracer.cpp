// test_embree_tracer.cpp - the Embree comparison tracer (bench/
// embree_tracer.hpp) renders the OpenMP comparison tracer's image, so the
// bench ratio between them times the same work, and eval/bench's pixel
// agreement (compare_rgb) notices when it does not.
//
// Tolerance: no pixel differs by more than one level of 255. Both tracers
// run the same float code per ray-sphere test and per shading step, built
// with the same flags, so their floats are equal (measured: every float of
// these images); Embree only changes which spheres a ray is tested against.
// What could still differ, and why the tolerance is not "bit for bit": the
// compiler may contract a*b+c into an FMA differently in the two files (one
// level at most), and on a silhouette a ray from an origin farther from a
// sphere than the camera, or two spheres hit at exactly the same t, could
// pick another sphere (embree_tracer.cpp) - a single pixel in a scene, more
// than one level, which these scenes do not have.
#include <catch2/catch.hpp>
#include <stdexcept>

#include "embree_tracer.hpp"
#include "eval/bench.hpp"
#include "omp_tracer.hpp"
#include "reference/reference.hpp"
#include "scene/random_scene.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_embree_tracer {

namespace {

using clrt_bench::EmbreeSpheres;

struct Both {
  std::vector<float> omp, embree;
  clrt_bench::EmbreeBuildInfo info;
  clrt::PixelAgreement agree;
  size_t equal_floats = 0;
};

Both render_both(const clrt::Scene& scene, int w, int h, int depth, EmbreeSpheres kind = EmbreeSpheres::User) {
  Both b;
  clrt_bench::omp_render(scene, w, h, depth, b.omp);
  clrt_bench::embree_render(scene, w, h, depth, b.embree, &b.info, kind);
  b.agree = clrt::compare_rgb(b.embree, b.omp);
  for (size_t i = 0; i < b.omp.size() && i < b.embree.size(); ++i) b.equal_floats += b.omp[i] == b.embree[i];
  return b;
}

void check_same_image(const Both& b, size_t values) {
  INFO("pixels differing by > 1 level: " << b.agree.differ << ", largest difference " << b.agree.max_levels
                                         << " levels, equal floats " << b.equal_floats << " of " << values);
  REQUIRE(b.embree.size() == values);
  CHECK(b.agree.differ == 0);
  CHECK(b.agree.max_levels <= 1);
}

}  // namespace

TEST_CASE("embree tracer renders the OpenMP tracer's image of the book's demo scene", "[embree][bench]") {
  const clrt::Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const Both b = render_both(demo, 600, 600, 3);
  check_same_image(b, 600 * 600 * 3);
  CHECK(b.info.spheres == demo.spheres.size());
  CHECK(b.info.threads >= 1);
  CHECK(b.info.build_ms >= 0);
  CHECK(b.info.render_ms > 0);
}

TEST_CASE("embree tracer renders the OpenMP tracer's image of a rotated camera", "[embree][bench]") {
  const clrt::Scene scene = clrt_test::load("scenes/cgfs-camera.json");
  check_same_image(render_both(scene, 200, 150, 3), 200 * 150 * 3);
}

TEST_CASE("embree tracer renders the OpenMP tracer's image of 200 random spheres", "[embree][bench]") {
  clrt::RandomSceneSettings rs;
  rs.count = 200;
  rs.seed = 11;
  const clrt::Scene scene = clrt::random_scene(rs);
  check_same_image(render_both(scene, 320, 240, 3), 320 * 240 * 3);
  // Depth 0 (no reflection rays) and a scene without spheres.
  check_same_image(render_both(scene, 64, 48, 0), 64 * 48 * 3);
  clrt::Scene empty = scene;
  empty.spheres.clear();
  empty.background = {10, 20, 30};
  const Both e = render_both(empty, 16, 8, 3);
  check_same_image(e, 16 * 8 * 3);
  CHECK(e.embree[0] == 10);
  CHECK(e.embree[2] == 30);
}

TEST_CASE("embree tracer renders the OpenMP tracer's image of planes and transparent spheres", "[embree][bench]") {
  // Chapter 5 in both tracers (whitted_float.hpp): refraction through
  // nested glass spheres, and the shipped mesh scene without its meshes (a
  // reflective plane, a transparent sphere).
  const clrt::Scene glass = clrt_test::load("scenes/glass.json");
  check_same_image(render_both(glass, 160, 120, 4), 160 * 120 * 3);
  clrt::Scene flat = clrt_test::load("scenes/large/mesh.json");
  REQUIRE(!flat.planes.empty());
  flat.triangles.clear();
  check_same_image(render_both(flat, 160, 120, 3), 160 * 120 * 3);
}

// Embree's own triangles (the OpenMP tracer does not trace meshes) against
// the double reference, which tests every triangle watertight. Tolerance:
// 0.5% of the pixels may differ by more than one level. Float against
// double moves hit points by ~1e-7 of the distance, which tips a shadow,
// reflection or refraction ray on a silhouette or edge to the other side;
// measured on this scene at 96 x 96: DIFFER_MEASURED (the bench check
// against clrt's image: none at 320 x 180, docs/results/meshes.md).
TEST_CASE("embree tracer's triangles render the reference's image of the shipped mesh scene", "[embree][bench]") {
  const clrt::Scene scene = clrt_test::load("scenes/large/mesh.json");
  REQUIRE(scene.triangles.size() > 1000);
  std::vector<float> embree;
  clrt_bench::EmbreeBuildInfo info;
  clrt_bench::embree_render(scene, 96, 96, 3, embree, &info);
  CHECK(info.triangles == scene.triangles.size());
  const clrt::Image reference = clrt::render_reference(scene, 96, 96, 3);
  const std::vector<float> reference_rgb(reference.rgb.begin(), reference.rgb.end());
  const clrt::PixelAgreement a = clrt::compare_rgb(embree, reference_rgb);
  INFO("pixels differing by > 1 level: " << a.differ << ", largest difference " << a.max_levels);
  CHECK(a.differ <= 0.005);
  // The OpenMP tracer has no triangle test: it refuses rather than time a
  // picture without them.
  std::vector<float> omp;
  CHECK_THROWS_AS(clrt_bench::omp_render(scene, 8, 8, 3, omp), std::invalid_argument);
  // And the check notices a different picture: without the meshes.
  clrt::Scene bare = scene;
  bare.triangles.clear();
  clrt_bench::embree_render(bare, 96, 96, 3, embree);
  CHECK(clrt::compare_rgb(embree, reference_rgb).differ > 0.05);
}

TEST_CASE("the agreement check notices an image that is not the OpenMP tracer's", "[embree][bench]") {
  const clrt::Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  // One reflection less is a different picture of the same scene.
  std::vector<float> omp, embree;
  clrt_bench::omp_render(demo, 120, 120, 3, omp);
  clrt_bench::embree_render(demo, 120, 120, 2, embree);
  CHECK(clrt::compare_rgb(embree, omp).differ > 0.01);
  // Embree's built-in sphere (not what bench uses) runs, and its image is
  // not the OpenMP tracer's: its intersection formula moves the floor's hit
  // points by more than the book's epsilon (embree_tracer.cpp: 4.3% of the
  // demo's pixels at 600x600). Not asserted: a property of Embree's version.
  const Both builtin = render_both(demo, 120, 120, 3, EmbreeSpheres::Builtin);
  INFO("built-in spheres: " << 100 * builtin.agree.differ << "% of pixels differ by > 1 level");
  CHECK(builtin.embree.size() == omp.size());
}

TEST_CASE("compare_rgb clamps and rounds like every output, then counts pixels", "[embree][bench]") {
  // Two pixels: the first differs only above 255 and by half a level; the
  // second by two levels in blue.
  const std::vector<float> a = {300, 10.2f, 0, 5, 5, 5}, b = {255, 9.8f, -4, 5, 5, 7};
  const clrt::PixelAgreement p = clrt::compare_rgb(a, b);
  CHECK(p.differ == Approx(0.5));
  CHECK(p.max_levels == 2);
  CHECK(clrt::compare_rgb(a, b, 2).differ == 0);
  CHECK(clrt::compare_rgb(a, a).differ == 0);
  CHECK(clrt::compare_rgb(a, {1, 2, 3}).differ == 1);  // sizes differ: nothing agrees
}

}  // namespace test_embree_tracer

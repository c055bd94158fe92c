// test_layers.cpp - the AOV layers (image/layers.hpp): the kernel's against
// the reference's and against values worked out by hand, their names, and
// the build option that only frames with layers get.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "eval/layer_compare.hpp"
#include "flat_scene.hpp"
#include "image/layers.hpp"
#include "reference/reference.hpp"
#include "render/build_options.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_layers {

using namespace clrt;

namespace {

// One frame on the test device with `layers`; the image into *img.
FrameLayers render_layers(const Scene& scene, int width, int height, unsigned layers, KernelConfig cfg = {},
                          Sampling sampling = {}, Image* img = nullptr) {
  cfg.output = FrameContents{PixelFormat::Float, true, uint8_t(layers)};
  Renderer r({clrt_test::test_device()}, RenderSettings{cfg, {}, {}});
  r.prepare(scene, width, height, scene.recursion_depth, sampling);
  Image frame = r.render();
  if (img) *img = frame;
  return r.layers();
}

// The kernel's layers against the reference's, at the tolerances compare
// states (eval/layer_compare.hpp).
LayerComparison against_reference(const Scene& scene, int width, int height, const FrameLayers& test) {
  std::vector<float> incidence;
  const FrameLayers ref = render_reference_layers(scene, width, height, kAllLayers, {}, &incidence);
  return compare_layers(test, ref, &incidence);
}

}  // namespace

TEST_CASE("layer names: parsed, listed and named as EXR channels", "[aov]") {
  CHECK(parse_layers("depth,normal,albedo,id") == kAllLayers);
  CHECK(parse_layers("id,depth") == (kLayerId | kLayerDepth));
  CHECK(layer_list(kLayerId | kLayerDepth) == "depth,id");
  CHECK(layer_channels(kAllLayers) ==
        std::vector<std::string>{"Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "id"});
  CHECK_THROWS_WITH(parse_layers("depth,colour"), Catch::Contains("unknown layer \"colour\""));
  CHECK_THROWS_WITH(parse_layers("id,depth,id"), Catch::Contains("\"id\" is listed twice"));
  CHECK_THROWS_AS(parse_layers(""), UserError);
  CHECK_THROWS_AS(parse_layers("depth,"), UserError);
}

TEST_CASE("only frames with layers build the kernel with them", "[aov][output]") {
  const Scene scene = clrt_test::load("scenes/glass.json");
  KernelConfig cfg;
  cfg.output = FrameContents{PixelFormat::Float, false};
  const std::string plain = build_options(cfg, scene, 3, false);
  CHECK(plain.find("CLRT_OUT_LAYERS") == std::string::npos);
  cfg.output.layers = kLayerDepth;
  const std::string depth = build_options(cfg, scene, 3, false);
  CHECK(depth.find("-DCLRT_OUT_LAYERS") != std::string::npos);
  // one program for every set of layers
  cfg.output.layers = kAllLayers;
  CHECK(build_options(cfg, scene, 3, false) == depth);
}

TEST_CASE("layers of one sphere straight ahead: the values worked out by hand", "[opencl][aov]") {
  // The camera at the origin looks down +z through a 1 x 1 viewport at
  // d = 1; a sphere of radius 1 at z = 5. Canvas point (0, 0) is the pixel
  // of column W/2 = 2 and row H/2 - 1 = 1 of a 5 x 5 frame (y = H/2 - 1 -
  // row): its ray hits the sphere at z = 4, distance 4, normal (0, 0, -1).
  // The corner pixels' rays (canvas x = +-2, y = 1 or -3: directions
  // (+-0.4, 0.2 or -0.6, 1)) pass it by at 2 or more from its centre.
  const Scene scene = parse_scene(R"({"spheres": [{"center": [0, 0, 5], "radius": 1, "color": [255, 51, 0]}],
      "lights": [{"type": "ambient", "intensity": 1}]})",
                                  "one sphere");
  const FrameLayers reference = render_reference_layers(scene, 5, 5, kAllLayers);
  const FrameLayers kernel = render_layers(scene, 5, 5, kAllLayers);
  for (const FrameLayers* f : {&reference, &kernel}) {
    const size_t centre = 1 * 5 + 2;
    // Float32: 4 to a few ulps; the normal's z exactly -1 (it is -1 / 1).
    CHECK(f->depth[centre] == Approx(4.0).epsilon(1e-6));
    CHECK(f->normal[centre * 3 + 0] == Approx(0.0).margin(1e-6));
    CHECK(f->normal[centre * 3 + 1] == Approx(0.0).margin(1e-6));
    CHECK(f->normal[centre * 3 + 2] == Approx(-1.0).epsilon(1e-6));
    CHECK(f->albedo[centre * 3 + 0] == Approx(1.0).epsilon(1e-6));
    CHECK(f->albedo[centre * 3 + 1] == Approx(0.2).epsilon(1e-6));
    CHECK(f->albedo[centre * 3 + 2] == 0.0f);
    CHECK(f->id[centre] == 0);
    for (size_t corner : {size_t(0), size_t(4), size_t(20), size_t(24)}) {
      CHECK(std::isinf(f->depth[corner]));
      CHECK(f->depth[corner] > 0);
      CHECK(f->id[corner] == -1);
      for (int c = 0; c < 3; ++c) {
        CHECK(f->normal[corner * 3 + c] == 0.0f);
        CHECK(f->albedo[corner * 3 + c] == 0.0f);
      }
    }
  }
}

TEST_CASE("the kernel's layers match the reference's within compare's tolerances", "[opencl][aov]") {
  // Spheres, glass, planes and triangles, with the hierarchy (the flat
  // scene's triangles) and without; and one 16-lane build, but only where
  // every_build() holds: on rusticl's llvmpipe (1 lane by default) a 16-lane
  // program with layers built cold in 150-160 s (demo, glass; 4-5 s at 1
  // lane), and this case alone took 408 of the every-device run's 544 s.
  struct Case {
    const char* name;
    Scene scene;
  };
  const std::vector<Case> cases{{"demo", clrt_test::load("scenes/cgfs-demo.json")},
                                {"glass", clrt_test::load("scenes/glass.json")},
                                {"flat", clrt_test::flat_scene()}};
  for (const Case& c : cases) {
    for (const int lanes : {0, 16}) {
      if (lanes == 16 && !clrt_test::every_build()) continue;
      INFO(c.name << ", lanes " << lanes);
      KernelConfig cfg;
      cfg.lanes = lanes;
      const FrameLayers kernel = render_layers(c.scene, 64, 48, kAllLayers, cfg);
      const LayerComparison cmp = against_reference(c.scene, 64, 48, kernel);
      INFO(cmp.failures());
      CHECK(cmp.pass());
      CHECK(cmp.same_hit > 1000);  // the layers were compared on hits
      CHECK(cmp.id_differ_inside == 0);
    }
  }
}

TEST_CASE("layers of a frame whose lane count the timed probe chooses: the forced lane count's", "[opencl][aov]") {
  // With the hierarchy and no --lanes, prepare() times the candidate lane
  // counts on tiles of the frame (render/lane_choice.hpp) before the frame
  // has named where its layers go: the probe's tiles store theirs aside
  // (before, that stopped the render with an internal error).
  const Scene flat = clrt_test::flat_scene();
  KernelConfig probed;
  probed.accel = Accel::Bvh;  // (lanes 0 and probe_lanes: the probe runs on CPUs)
  const FrameLayers chosen = render_layers(flat, 64, 48, kAllLayers, probed);
  const LayerComparison cmp = against_reference(flat, 64, 48, chosen);
  INFO(cmp.failures());
  CHECK(cmp.pass());
  CHECK(cmp.same_hit > 1000);
}

TEST_CASE("layers are those of the pixel centre's ray whatever the sampling, and leave the colour alone",
          "[opencl][aov]") {
  const Scene scene = clrt_test::load("scenes/cgfs-demo.json");
  Image plain_colour, layered_colour;
  const FrameLayers plain = render_layers(scene, 40, 30, kAllLayers, {}, {}, &layered_colour);
  {
    KernelConfig cfg;
    cfg.output = FrameContents{PixelFormat::Float, true};
    Renderer r({clrt_test::test_device()}, RenderSettings{cfg, {}, {}});
    r.prepare(scene, 40, 30, scene.recursion_depth);
    plain_colour = r.render();
    CHECK(r.layers().layers == 0);
  }
  CHECK(layered_colour.rgb == plain_colour.rgb);  // the layers' ray changes no pixel
  CHECK(layered_colour.hit == plain_colour.hit);
  // Supersampled and subsampled frames: the same layers, bit for bit.
  for (const Sampling& sampling : {Sampling(3, -1, Subsample::Off), Sampling(1, -1, Subsample::Interpolate),
                                   Sampling(1, -1, Subsample::Shade)}) {
    INFO("spp " << sampling.spp << ", subsample " << int(sampling.subsample));
    const FrameLayers sampled = render_layers(scene, 40, 30, kAllLayers, {}, sampling);
    CHECK(sampled.depth == plain.depth);
    CHECK(sampled.normal == plain.normal);
    CHECK(sampled.albedo == plain.albedo);
    CHECK(sampled.id == plain.id);
  }
  // Only the layers asked for are kept.
  const FrameLayers depth_only = render_layers(scene, 40, 30, kLayerDepth);
  CHECK(depth_only.depth == plain.depth);
  CHECK(depth_only.normal.empty());
  CHECK(depth_only.id.empty());
}

TEST_CASE("compare_layers catches a wrong hit, a depth off the surface and a wrong normal", "[aov]") {
  const Scene scene = clrt_test::load("scenes/cgfs-demo.json");
  std::vector<float> incidence;
  const FrameLayers ref = render_reference_layers(scene, 32, 24, kAllLayers, {}, &incidence);
  CHECK(compare_layers(ref, ref, &incidence).pass());
  // A pixel well inside a sphere (its 4-neighbours hit the same one).
  size_t inside = 0;
  for (size_t p = 33; p + 33 < ref.pixels() && !inside; ++p)
    if (ref.id[p] >= 0 && ref.id[p - 1] == ref.id[p] && ref.id[p + 1] == ref.id[p] && ref.id[p - 32] == ref.id[p] &&
        ref.id[p + 32] == ref.id[p] && incidence[p] > 0.5f)
      inside = p;
  REQUIRE(inside > 0);
  FrameLayers wrong = ref;
  wrong.id[inside] = ref.id[inside] + 1;
  CHECK(compare_layers(wrong, ref, &incidence).id_differ_inside == 1);
  wrong = ref;
  wrong.depth[inside] *= 1.001f;  // 1e-3 relative at cos > 0.5: over 1e-4
  CHECK(compare_layers(wrong, ref, &incidence).depth_over == 1);
  wrong = ref;
  wrong.normal[inside * 3] += 0.001f;
  CHECK(compare_layers(wrong, ref, &incidence).normal_over == 1);
  wrong = ref;
  wrong.albedo[inside * 3] += 1.0f / 255;
  CHECK(compare_layers(wrong, ref, &incidence).albedo_differ == 1);
}

}  // namespace test_layers

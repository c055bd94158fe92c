// test_layer_file.cpp - render --aov: one multi-layer EXR whose channels
// OpenImageIO (and oiiotool, where installed) read back by name, compare
// --aov on it and on OpenCL, and the errors of the option.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/options.hpp"
#include "cli_run.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "image/layers.hpp"
#include "reference/reference.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_layer_file {

using Catch::Matchers::Contains;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;

namespace {

std::string glass() {
  return clrt_test::source_path("scenes/glass.json");
}

RunResult render(const std::vector<std::string>& extra) {
  std::vector<std::string> args{"render", glass(), "--width", "24", "--height", "18", "--aspect", "image"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_clrt(args);
}

}  // namespace

TEST_CASE("render --aov writes one EXR with the layers' channels, as the reference gives them", "[cli][aov]") {
  TempDir dir;
  // The reference engine: the file's layers must be the reference's, exactly.
  const RunResult r = render({"--engine", "reference", "--aov", "depth,normal,albedo,id", "-o", dir / "g.exr"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::string err;
  auto in = clrt::imageio::module().open(dir / "g.exr", &err);
  REQUIRE(in);
  CHECK(in->channels() == 12);
  std::vector<std::string> names = in->channel_names();
  std::sort(names.begin(), names.end());  // (OpenEXR stores them sorted; the order is the reader's)
  CHECK(names == std::vector<std::string>{"A", "B", "G", "N.X", "N.Y", "N.Z", "R", "Z", "albedo.B", "albedo.G",
                                          "albedo.R", "id"});
  CHECK(in->attribute("clrt:aov") == "depth,normal,albedo,id");
  const clrt::FrameLayers file = clrt::read_layers(dir / "g.exr", 24, 18);
  clrt::ImageOptions image;
  image.width = 24, image.height = 18, image.aspect = "image";
  const clrt::Scene scene = image.load_scene(glass(), false);
  const clrt::FrameLayers ref = clrt::render_reference_layers(scene, 24, 18, clrt::kAllLayers);
  CHECK(file.layers == clrt::kAllLayers);
  CHECK(file.depth == ref.depth);  // float32 both ways: bit for bit (+inf on a miss included)
  CHECK(file.normal == ref.normal);
  CHECK(file.albedo == ref.albedo);
  CHECK(file.id == ref.id);
  bool misses = false, hits = false;
  for (int32_t id : ref.id) (id < 0 ? misses : hits) = true;
  CHECK((misses && hits));
  // The colour is the plain render's.
  const RunResult plain = render({"--engine", "reference", "-o", dir / "plain.exr"});
  REQUIRE(plain.status == 0);
  const clrt::Image a = clrt::read_image(dir / "g.exr", 100, 10000), b = clrt::read_image(dir / "plain.exr", 100, 10000);
  CHECK(a.rgb == b.rgb);
  // Only the layers asked for.
  REQUIRE(render({"--engine", "reference", "--aov", "id", "-o", dir / "id.exr"}).status == 0);
  CHECK(clrt::read_layers(dir / "id.exr", 24, 18).layers == clrt::kLayerId);
}

TEST_CASE("compare --aov reports each layer against the reference, from OpenCL and from an EXR",
          "[cli][aov][opencl]") {
  TempDir dir;
  const RunResult r = render({"--aov", "depth,normal,albedo,id", "-o", dir / "g.exr"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  for (const std::vector<std::string>& source : {std::vector<std::string>{}, {"--image", dir / "g.exr"}}) {
    std::vector<std::string> args{"compare", glass(), "--width", "24", "--height", "18", "--aspect", "image",
                                  "--aov", "depth,normal,albedo,id"};
    args.insert(args.end(), source.begin(), source.end());
    const RunResult c = run_clrt(args);
    INFO(c.out << c.err);
    CHECK(c.status == 0);
    for (const char* line : {"layer id ", "layer depth ", "layer normal ", "layer albedo "})
      CHECK_THAT(c.out, Contains(line));
    CHECK_THAT(c.out, Contains("within tolerance"));
    args.push_back("--json");
    const RunResult j = run_clrt(args);
    CHECK(j.status == 0);
    CHECK_THAT(j.out, Contains("\"aov\":"));
    CHECK_THAT(j.out, Contains("\"depth_max_relative_error\""));
  }
  // An EXR of the depth alone: compared where the reference's id says.
  REQUIRE(render({"--aov", "depth", "-o", dir / "depth.exr"}).status == 0);
  const RunResult depth = run_clrt({"compare", glass(), "--aspect", "image", "--aov", "depth", "--image",
                                    dir / "depth.exr"});
  INFO(depth.out << depth.err);
  CHECK(depth.status == 0);
  CHECK_THAT(depth.out, Contains("layer id       n/a"));
  CHECK_THAT(depth.out, Contains("layer depth "));
  // An EXR without layers cannot be compared layer by layer.
  REQUIRE(render({"-o", dir / "plain.exr"}).status == 0);
  const RunResult none = run_clrt({"compare", glass(), "--aspect", "image", "--aov", "depth", "--image",
                                   dir / "plain.exr"});
  CHECK(none.status == 2);
  CHECK(none.one_line_error());
  CHECK_THAT(none.err, Contains("plain.exr"));
}

TEST_CASE("oiiotool lists the layers' channels", "[cli][aov]") {
  if (std::system("command -v oiiotool >/dev/null 2>&1") != 0) {
    WARN("oiiotool not installed: the oiiotool check is skipped");
    return;
  }
  TempDir dir;
  REQUIRE(render({"--engine", "reference", "--aov", "depth,normal,albedo,id", "-o", dir / "g.exr"}).status == 0);
  const RunResult info = clrt_test::run_command_line("oiiotool --info -v " + clrt_test::shell_quote(dir / "g.exr"));
  INFO(info.out << info.err);
  REQUIRE(info.status == 0);
  for (const char* channel : {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "id"})
    CHECK_THAT(info.out, Contains(std::string(channel)));
  CHECK_THAT(info.out, Contains("12 channel"));
}

TEST_CASE("render with layers refuses 8-bit and colour-only formats, unknown and repeated layers, several frames",
          "[cli][aov]") {
  TempDir dir;
  struct Case {
    std::vector<std::string> args;
    const char* says;
  };
  const std::vector<Case> cases{
      {{"--aov", "depth", "-o", dir / "x.png"}, ".png holds 8-bit colour only"},
      {{"--aov", "depth", "-o", dir / "x.ppm"}, ".ppm holds 8-bit colour only"},
      {{"--aov", "depth", "-o", dir / "x.pfm"}, ".pfm holds float RGB only"},
      {{"--aov", "depth", "-o", "-"}, "8-bit colour only"},
      {{"--aov", "depth,colour", "-o", dir / "x.exr"}, "unknown layer \"colour\""},
      {{"--aov", "id,id", "-o", dir / "x.exr"}, "\"id\" is listed twice"},
      {{"--aov", "", "-o", dir / "x.exr"}, "no layer named"},
      {{glass(), "--aov", "depth", "-o", dir / "f_#.exr"}, "one SCENE"},
  };
  for (const Case& c : cases) {
    const RunResult r = render(c.args);
    INFO(clrt_test::clrt_command(c.args) << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK(r.err.rfind("clrt: error: ", 0) == 0);
    CHECK_THAT(r.err, Contains(c.says));
    CHECK(r.out.empty());
  }
  CHECK(dir.entries().empty());  // nothing written
}

}  // namespace test_layer_file

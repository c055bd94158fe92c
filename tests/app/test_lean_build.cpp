// test_lean_build.cpp - the lean build's own checks (CMakeLists.txt builds
// this file only with CLRT_LEAN=ON; docs/guide/lean.md): the clrt binary
// needs none of the libraries a lean build leaves out; it renders PPM and
// PFM that read back as the reference's image; every other image format,
// --plot, OBJ meshes and the comparison tracers are refused, saying why.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "image/image_file.hpp"
#include "test_util.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_lean_build {

using clrt_test::run_clrt;
using clrt_test::source_path;

namespace {

// The stdout of a shell command (and whether it exited 0).
std::string command_output(const std::string& cmd, bool* ok) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) {
    *ok = false;
    return out;
  }
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  *ok = ::pclose(p) == 0;
  return out;
}

const std::vector<std::string> kLeftOut{"libOpenImageIO", "libplplot", "libembree", "libgomp", "libtinyobjloader"};

}  // namespace

static_assert(clrt::kLeanBuild, "test_lean_build.cpp is built in a lean build only");

TEST_CASE("a lean clrt needs no OpenImageIO, PLplot, Embree, OpenMP or tinyobjloader", "[lean]") {
  const std::string clrt = clrt_test::shell_quote(CLRT_BINARY);
  // Its own NEEDED entries (readelf), then every library the loader maps (ldd).
  bool ok = false;
  const std::string needed = command_output("readelf -d " + clrt, &ok);
  REQUIRE(ok);
  INFO("readelf -d:\n" << needed);
  CHECK(needed.find("libOpenCL") != std::string::npos);
  const std::string mapped = command_output("ldd " + clrt, &ok);
  REQUIRE(ok);
  INFO("ldd:\n" << mapped);
  for (const auto& lib : kLeftOut) {
    INFO(lib);
    CHECK(needed.find(lib) == std::string::npos);
    CHECK(mapped.find(lib) == std::string::npos);
  }
  // And no imaging module beside it to dlopen.
  CHECK_FALSE(std::filesystem::exists(std::filesystem::path(CLRT_BINARY).parent_path() / "clrt_imageio.so"));
}

TEST_CASE("a lean render to .ppm and .pfm is the reference's image", "[lean][cli][compare][opencl]") {
  clrt_test::TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  for (const std::string name : {"demo.ppm", "demo.pfm"}) {
    INFO(name);
    const auto r = run_clrt({"render", demo, "--width", "64", "--height", "48", "-o", dir / name});
    INFO(r.err);
    REQUIRE(r.status == 0);
    const std::string bytes = clrt_test::slurp(dir / name);
    CHECK(bytes.rfind(name == "demo.ppm" ? "P6\n" : "PF\n", 0) == 0);
    // Read back by clrt (compare --image): within the limit of the other
    // render-vs-reference tests (eval/test_compare_gate.cpp).
    const auto same = run_clrt({"compare", demo, "--image", dir / name, "--fail-percent", "1"});
    INFO(same.out << same.err);
    CHECK(same.status == 0);
    CHECK(same.out.find("64x48") != std::string::npos);
    // Another scene's image is another image: the pixels were read.
    const auto other_render = run_clrt({"render", source_path("scenes/cgfs-camera.json"), "--width", "64", "--height",
                                        "48", "-o", dir / ("other" + name.substr(4))});
    REQUIRE(other_render.status == 0);
    CHECK(run_clrt({"compare", demo, "--image", dir / ("other" + name.substr(4)), "--fail-percent", "1"}).status == 1);
  }
  // PPM's header carries the render's metadata as comments, read back.
  const auto meta = clrt::read_metadata(dir / "demo.ppm", {"clrt:white"});
  REQUIRE(meta.size() == 1);
  CHECK(meta[0].second == "255");
}

TEST_CASE("a lean build reads back what it writes, and refuses what is not PPM or PFM", "[lean][image]") {
  clrt_test::TempDir dir;
  clrt::Image img(3, 2);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = double((i * 37) % 256);
  clrt::write_image(img, dir / "a.ppm", {{"clrt:scene", "s.json"}});
  const clrt::Image back = clrt::read_image(dir / "a.ppm", 64, 4096);
  REQUIRE(back.width == 3);
  REQUIRE(back.height == 2);
  CHECK(back.rgb == img.rgb);
  // A file that is not one, or is cut short, is a UserError naming it.
  CHECK_THROWS_AS(clrt::read_image(dir.write("x.ppm", "P6\n3 2\n255\nabc"), 64, 4096), clrt::UserError);
  CHECK_THROWS_AS(clrt::read_image(dir.write("x.png", "\x89PNG\r\n\x1a\n"), 64, 4096), clrt::UserError);
  CHECK_THROWS_AS(clrt::read_image(dir.write("y.ppm", "P6\n99999999999 2\n255\n"), 64, 4096), clrt::UserError);
  CHECK_THROWS_AS(clrt::check_output_format(dir / "x.exr"), clrt::UserError);
}

TEST_CASE("a lean clrt refuses -o x.png with exit 2 before rendering, and writes PPM to stdout", "[lean][cli]") {
  clrt_test::TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  for (const std::string name : {"x.png", "x.exr", "x.jpg"}) {
    const auto r = run_clrt({"render", demo, "--width", "8", "--height", "8", "-o", dir / name});
    INFO(name << ": status " << r.status << ", stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK(r.err.rfind("clrt: error: ", 0) == 0);
    CHECK(r.err.find("CLRT_LEAN=ON") != std::string::npos);
    CHECK(r.err.find(".ppm or .pfm") != std::string::npos);
  }
  CHECK(dir.entries().empty());  // nothing left behind
  // No extension (standard output): PPM.
  const auto out = run_clrt({"render", demo, "--engine", "reference", "--width", "8", "--height", "8", "-o", "-"});
  INFO(out.err);
  CHECK(out.status == 0);
  CHECK(out.out.rfind("P6\n", 0) == 0);
}

TEST_CASE("a lean clrt refuses --aov, which needs OpenImageIO's EXR, saying so", "[lean][cli][aov]") {
  clrt_test::TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  for (const std::string name : {"x.ppm", "x.pfm", "x.exr"}) {
    const auto r = run_clrt({"render", demo, "--width", "8", "--height", "8", "--aov", "depth", "-o", dir / name});
    INFO(name << ": status " << r.status << ", stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK(r.err.rfind("clrt: error: ", 0) == 0);
    CHECK(r.err.find("OpenImageIO") != std::string::npos);
  }
  CHECK(dir.entries().empty());
}

TEST_CASE("a lean clrt refuses plots, OBJ meshes and the comparison tracers, saying why", "[lean][cli]") {
  clrt_test::TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  const auto plot = run_clrt({"accuracy", demo, "--width", "8", "--height", "8", "--plot", dir / "p.png"});
  INFO(plot.err);
  CHECK(plot.status == 2);
  CHECK(plot.one_line_error());
  CHECK(plot.err.find("no plots") != std::string::npos);
  CHECK(plot.out.empty());  // nothing measured
  dir.write("tri.obj", "v 0 0 5\nv 1 0 5\nv 0 1 5\nf 1 2 3\n");
  const std::string scene = dir.write(
      "mesh.json",
      R"({"meshes": [{"file": "tri.obj", "color": [1, 1, 1]}], "lights": [{"type": "ambient", "intensity": 1}]})");
  const auto mesh = run_clrt({"render", scene, "--width", "8", "--height", "8", "-o", dir / "m.ppm"});
  INFO(mesh.err);
  CHECK(mesh.status == 2);
  CHECK(mesh.one_line_error());
  CHECK(mesh.err.find("no OBJ meshes") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "m.ppm"));
}

TEST_CASE("a lean clrt bench runs without the comparison tracers and says so", "[lean][cli][bench][opencl]") {
  const auto r =
      run_clrt({"bench", source_path("scenes/cgfs-demo.json"), "--width", "32", "--height", "24", "--repeat", "1"});
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK(r.out.find("CLRT_LEAN=ON") != std::string::npos);
}

}  // namespace test_lean_build

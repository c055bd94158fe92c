// test_multidevice.cpp - one frame across several devices, and tiling on one
// device, must give exactly the single-launch image.
#include <catch2/catch.hpp>
#include <tuple>

#include "cli_run.hpp"
#include "image/image_file.hpp"
#include "render/renderer.hpp"
#include "test_util.hpp"
#include "util/build_features.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_multidevice {

using namespace clrt;

namespace {

// A float format, so that equal pixels are equal kernel output, bit for bit:
// EXR, or PFM in a lean build (no OpenImageIO). Read back by clrt: float x 255
// is exact in double, so equal values read means equal floats stored.
const std::string kFloatExt = kLeanBuild ? ".pfm" : ".exr";

std::vector<double> read_float_pixels(const std::string& path) {
  return read_image(path, 4096, 4096LL * 4096).rgb;
}

size_t count_lines_with(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("two PoCL devices render the same bytes as one", "[opencl][multidevice]") {
  // POCL_DEVICES is read when the OpenCL platform initializes, so each
  // configuration runs in its own clrt process. EXR (PFM in a lean build)
  // keeps the float colour, so equality here is equality of the kernel's
  // output, bit for bit. Only PoCL's ICD is loaded: `--device all` must mean
  // these two devices, not another driver's too (CI also installs Mesa
  // rusticl, whose compiler rounds some pixels differently).
  clrt_test::TempDir dir;
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json");
  auto single =
      clrt_test::run_clrt({"render", scene, "--width", "320", "--height", "240", "-o", dir / ("single" + kFloatExt)});
  REQUIRE(single.status == 0);
  const auto want = read_float_pixels(dir / ("single" + kFloatExt));
  for (const char* devices : {"pthread pthread", "pthread basic"}) {
    for (const char* band : {"0", "7"}) {  // adaptive bands, and many small fixed ones
      INFO("POCL_DEVICES=" << devices << " --band-rows " << band);
      std::string out = dir / (std::string("multi-") + band + kFloatExt);
      auto r = clrt_test::run_clrt(
          {"render", scene, "--width", "320", "--height", "240", "--device", "all", "--band-rows", band, "-o", out},
          "OCL_ICD_VENDORS=/etc/OpenCL/vendors/pocl.icd POCL_DEVICES=" + clrt_test::shell_quote(devices));
      INFO(r.out << r.err);
      REQUIRE(r.status == 0);
      CHECK(count_lines_with(r.out, "  device ") == 2);  // one share line per device
      CHECK(read_float_pixels(out) == want);
    }
  }
}

TEST_CASE("two contexts on one device share a frame exactly", "[opencl][multidevice]") {
  DeviceInfo dev = clrt_test::test_device();
  Scene s = clrt_test::load("scenes/cgfs-camera.json");
  Image want = clrt_test::render_cl(s, 200, 150, 3, KernelConfig{});
  Renderer multi({dev, dev}, RenderSettings{KernelConfig{}, TilePolicy{0, 5}, {}});
  multi.prepare(s, 200, 150, 3);
  Image got = multi.render();
  CHECK(got.rgb == want.rgb);
  CHECK(got.hit == want.hit);
  CHECK(got.shadowed == want.shadowed);
  const auto& shares = multi.stats().shares;
  REQUIRE(shares.size() == 2);
  CHECK(shares[0].rows + shares[1].rows == 150);
  CHECK(shares[0].tiles + shares[1].tiles == 30);  // 150 rows / 5
}

TEST_CASE("a launch-time limit splits one device's frame into bands", "[opencl]") {
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  Renderer whole = clrt_test::renderer(KernelConfig{}, TilePolicy{0, 0});  // no limit on any device type
  whole.prepare(s, 160, 120, 2);
  Image want = whole.render();
  CHECK(whole.stats().launches == 1);
  // A limit far below any real launch: after the 16-row calibration band
  // every band shrinks to one row.
  Renderer limited = clrt_test::renderer(KernelConfig{}, TilePolicy{1e-6, 0});
  limited.prepare(s, 160, 120, 2);
  Image got = limited.render();
  CHECK(limited.stats().launches == 1 + (120 - 16));
  CHECK(got.rgb == want.rgb);
  CHECK(got.hit == want.hit);
}

TEST_CASE("mapped and read results, fresh and reused images: the same bytes", "[opencl][multidevice]") {
  DeviceInfo dev = clrt_test::test_device();
  const Scene camera = clrt_test::load("scenes/cgfs-camera.json");
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  // Bands of 7 rows: tiles of several sizes go through the buffers.
  RenderSettings mapped{KernelConfig{}, TilePolicy{0, 7}, {}};
  RenderSettings read = mapped;
  read.map_results = false;
  Renderer a({dev}, mapped), b({dev}, read);
  Image reused;
  for (const auto& [scene, width, height] : {std::tuple{&camera, 120, 90}, std::tuple{&demo, 64, 40},
                                             std::tuple{&demo, 64, 40}, std::tuple{&camera, 33, 61}}) {
    INFO(width << "x" << height);
    a.prepare(*scene, width, height, 3);
    b.prepare(*scene, width, height, 3);
    const Image want = b.render();
    a.render_into(reused);  // reuses, resizes, reuses, resizes
    CHECK(reused.width == width);
    CHECK(reused.height == height);
    CHECK(reused.rgb == want.rgb);
    CHECK(reused.hit == want.hit);
    CHECK(reused.shadowed == want.shadowed);
  }
}

}  // namespace test_multidevice

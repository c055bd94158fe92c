// test_accuracy.cpp - `clrt accuracy`: rows with sane metrics, the variants'
// error ordering on the demo, the CSV/JSON/plot outputs.

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cl/device.hpp"
#include "cli_run.hpp"
#include "eval/accuracy.hpp"
#include "image/image_file.hpp"
#include "render/precision_support.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_accuracy {

using namespace clrt;

TEST_CASE("accuracy rows on the demo scene (200x200)", "[accuracy][opencl][slow]") {
  AccuracySettings s;
  s.width = s.height = 200;
  s.repeat = 3;
  std::vector<NamedScene> scenes{{"cgfs-demo.json", clrt_test::load("scenes/cgfs-demo.json")}};
  const DeviceInfo dev = clrt_test::test_device();
  auto rows = measure_accuracy(scenes, dev, s);
  REQUIRE(rows.size() == default_accuracy_variants().size());
  const AccuracyRow *naive = nullptr, *robust = nullptr, *shade = nullptr, *interpolate = nullptr;
  for (const auto& r : rows) {
    INFO(r.variant);
    CHECK(r.depth == 3);
    if (r.variant == "fp64" && !dev.fp64) {
      CHECK_FALSE(r.supported);  // reported, not a crash
      continue;
    }
    REQUIRE(r.supported);
    CHECK(r.kernel_ms.size() == 3);
    CHECK(r.median_ms > 0);
    CHECK(r.error.pixels == 40000);
    CHECK(r.error.nan_inf == 0);
    CHECK(r.error.rmse_8bit >= 0);
    CHECK(r.error.psnr_8bit > 20);  // every variant renders the scene, not noise
    if (r.variant == "naive") naive = &r;
    if (r.variant == "robust") robust = &r;
    if (r.variant == "robust+subsample-shade") shade = &r;
    if (r.variant == "robust+subsample-interpolate") interpolate = &r;
    if (r.variant == "fp64") {
      // fp64 rebuilds the scene's doubles from float hi+lo pairs (~48 bits):
      // no pixel may be off by more than rounding.
      CHECK(r.error.off_by_gt1 == 0);
      CHECK(r.error.rmse_8bit < 0.05);
    }
  }
  REQUIRE(naive);
  REQUIRE(robust);
  // Naive's floor self-shadowing (docs/reference/precision.md: ~1.9% of pixels off by
  // > 1) against robust's few grazing silhouette pixels (<= 0.05%).
  CHECK(naive->error.percent_off_by_gt1() > 1.0);
  CHECK(robust->error.percent_off_by_gt1() <= 0.05);
  CHECK(naive->error.rmse_8bit > 5 * robust->error.rmse_8bit);
  CHECK(naive->error.shadow_flips + naive->error.hit_flips >= robust->error.shadow_flips + robust->error.hit_flips);
  // Subsampling against the exact reference: the shade mode only errs where
  // something narrower than two pixels hides (nothing on the demo's four
  // large spheres), so it stays within robust's tolerance; interpolation
  // changes highlights, shadow edges and reflections.
  REQUIRE(shade);
  REQUIRE(interpolate);
  CHECK(shade->error.percent_off_by_gt1() <= 0.05);
  CHECK(interpolate->error.percent_off_by_gt1() > shade->error.percent_off_by_gt1());
  CHECK(interpolate->error.rmse_8bit > robust->error.rmse_8bit);
}

TEST_CASE("accuracy variants: names and subsampling modes", "[accuracy]") {
  for (const AccuracyVariant& v : default_accuracy_variants()) CHECK(parse_accuracy_variant(v.name()) == v);
  CHECK(parse_accuracy_variant("fp64+subsample-interpolate").precision == Precision::Fp64);
  CHECK(parse_accuracy_variant("naive+subsample-shade").subsample == Subsample::Shade);
  CHECK_THROWS_AS(parse_accuracy_variant("robust+subsample-half"), UserError);
  CHECK_THROWS_AS(parse_accuracy_variant("robust+subsample-"), UserError);
  CHECK_THROWS_AS(parse_accuracy_variant("+subsample-shade"), UserError);
}

TEST_CASE("clrt accuracy writes table, JSON, CSV and a non-empty plot", "[accuracy][cli][opencl]") {
  clrt_test::TempDir dir;
  const std::string csv = dir / "a.csv", png = dir / "a.png";
  auto r =
      clrt_test::run_clrt({"accuracy", clrt_test::source_path("scenes/cgfs-demo.json"), "--width", "64", "--height",
                           "48", "--repeat", "1", "--variants", "naive,robust", "--json", "--csv", csv, "--plot", png});
  INFO(r.err);
  REQUIRE(r.status == 0);
  auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["rows"].size() == 2);
  CHECK(j["rows"][0]["variant"] == "naive");
  CHECK(j["rows"][1]["kernel_ms"].size() == 1);
  CHECK(j["rows"][1]["pixels"] == 64 * 48);
  std::string text = clrt_test::slurp(csv);
  CHECK(std::count(text.begin(), text.end(), '\n') == 3);   // header + 2 rows
  CHECK(clrt::read_image(png, 4096, 1 << 24).width > 100);  // (through clrt's imaging module)

  auto t = clrt_test::run_clrt({"accuracy", clrt_test::source_path("scenes/cgfs-demo.json"), "--width", "32",
                                "--height", "32", "--repeat", "1", "--variants", "robust"});
  REQUIRE(t.status == 0);
  CHECK(t.out.find("robust") != std::string::npos);
  CHECK(t.out.find("RMSE") != std::string::npos);

  auto bad = clrt_test::run_clrt({"accuracy", clrt_test::source_path("scenes/cgfs-demo.json"), "--variants", "fp32"});
  CHECK(bad.status == 2);
  CHECK(bad.last_error_line().find("unknown precision") != std::string::npos);
}

TEST_CASE("fp64 is unsupported on a device without cl_khr_fp64, the rest are supported", "[accuracy]") {
  DeviceInfo no_fp64;
  no_fp64.fp64 = false;
  CHECK(unsupported_reason(Precision::Fp64, no_fp64).find("cl_khr_fp64") != std::string::npos);
  for (Precision p : {Precision::Naive, Precision::Stable, Precision::Robust, Precision::Fast})
    CHECK(unsupported_reason(p, no_fp64).empty());
  DeviceInfo with_fp64;
  with_fp64.fp64 = true;
  CHECK(unsupported_reason(Precision::Fp64, with_fp64).empty());
}

}  // namespace test_accuracy

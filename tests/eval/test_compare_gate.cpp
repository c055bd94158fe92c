// test_compare_gate.cpp - `clrt compare` as a gate: thresholds, exit codes
// (0 within, 1 outside, 2 bad input), the worst pixel, comparing an image
// file; and exit 1 for the other checks that ran and failed.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "eval/compare.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_compare_gate {

using namespace clrt;
using clrt_test::run_clrt;
using clrt_test::source_path;

TEST_CASE("the worst pixel is located and reported with both values", "[compare]") {
  Image ref(5, 4), test(5, 4);
  test.rgb[(2 * 5 + 3) * 3 + 1] = 9.0;  // (3, 2): green off by 9
  test.rgb[(3 * 5 + 0) * 3 + 0] = 4.0;  // (0, 3): red off by 4
  Comparison c = compare_images(test, ref);
  CHECK(c.max_abs_8bit == 9);
  CHECK(c.worst_x == 3);
  CHECK(c.worst_y == 2);
  CHECK(int(c.worst_test[1]) == 9);
  CHECK(int(c.worst_reference[1]) == 0);
  CHECK(c.off_by_gt1 == 2);
}

TEST_CASE("thresholds: pass, fail on each limit, NaN always fails", "[compare]") {
  Image ref(10, 10), test(10, 10);
  test.rgb[0] = 5;  // one pixel of 100 off by 5 levels: 1%
  Comparison c = compare_images(test, ref);
  CHECK(judge(c, Thresholds{}).pass);        // no limits: a report, never a fail
  CHECK(judge(c, Thresholds{1.0, 5}).pass);  // exactly at both limits
  Verdict p = judge(c, Thresholds{0.5, -1});
  CHECK_FALSE(p.pass);
  CHECK(p.reason.find("--fail-percent") != std::string::npos);
  Verdict m = judge(c, Thresholds{-1, 4});
  CHECK_FALSE(m.pass);
  CHECK(m.reason.find("--fail-max") != std::string::npos);
  test.rgb[3] = std::nan("");
  CHECK_FALSE(judge(compare_images(test, ref), Thresholds{100, 255}).pass);
}

TEST_CASE("clrt compare exit codes: 0 within the limits, 1 outside, 2 bad input", "[cli][compare][opencl]") {
  const std::string demo = source_path("scenes/cgfs-demo.json");
  // Robust float32 on the demo: a handful of silhouette pixels at most.
  auto pass = run_clrt({"compare", demo, "--width", "80", "--height", "80", "--fail-percent", "1"});
  INFO(pass.err);
  CHECK(pass.status == 0);
  CHECK(pass.out.find("verdict        PASS") != std::string::npos);
  // Naive float32 shows the floor acne (~2% of pixels, tens of levels): fails
  // --fail-max 1, with one "check failed" line on stderr.
  auto fail = run_clrt({"compare", demo, "--width", "80", "--height", "80", "--precision", "naive", "--fail-max", "1"});
  CHECK(fail.status == 1);
  CHECK(fail.out.find("verdict        FAIL") != std::string::npos);
  CHECK(fail.out.find("worst pixel") != std::string::npos);
  CHECK(fail.one_line_error());
  CHECK(fail.err.rfind("clrt: check failed: compare: ", 0) == 0);
  // JSON carries the verdict and the worst pixel.
  auto json = run_clrt(
      {"compare", demo, "--width", "80", "--height", "80", "--precision", "naive", "--fail-max", "1", "--json"});
  CHECK(json.status == 1);
  auto j = nlohmann::json::parse(json.out);
  CHECK(j["verdict"] == "fail");
  CHECK(j["fail_max_8bit"] == 1);
  CHECK(j["worst_pixel"]["x"].get<int>() >= 0);
  CHECK(j["max_abs_8bit"].get<int>() > 1);
  // Bad limits are bad input.
  for (std::vector<std::string> bad : {std::vector<std::string>{"--fail-percent", "101"},
                                       {"--fail-percent", "-1"},
                                       {"--fail-max", "256"},
                                       {"--fail-max", "x"}}) {
    std::vector<std::string> args{"compare", demo, "--width", "8", "--height", "8"};
    args.insert(args.end(), bad.begin(), bad.end());
    auto r = run_clrt(args);
    INFO(bad[0] << " " << bad[1] << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
  }
}

TEST_CASE("clrt compare --image: a rendered file against the reference", "[cli][compare][opencl]") {
  clrt_test::TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  REQUIRE(
      run_clrt({"render", demo, "--width", "64", "--height", "48", "-o", dir / clrt_test::image_name("demo")}).status ==
      0);
  REQUIRE(run_clrt({"render", source_path("scenes/cgfs-camera.json"), "--width", "64", "--height", "48", "-o",
                    dir / clrt_test::image_name("other")})
              .status == 0);
  // The image's size is the comparison's size.
  auto same = run_clrt({"compare", demo, "--image", dir / clrt_test::image_name("demo"), "--fail-percent", "1"});
  INFO(same.err);
  CHECK(same.status == 0);
  CHECK(same.out.find("64x48") != std::string::npos);
  CHECK(same.out.find("flips          n/a") != std::string::npos);
  // Another scene's image fails.
  auto other = run_clrt({"compare", demo, "--image", dir / clrt_test::image_name("other"), "--fail-percent", "1"});
  CHECK(other.status == 1);
  // A missing or non-image file is bad input.
  auto missing = run_clrt({"compare", demo, "--image", dir / clrt_test::image_name("nope")});
  CHECK(missing.status == 2);
  CHECK(missing.one_line_error());
  auto text = run_clrt({"compare", demo, "--image", dir.write(clrt_test::image_name("x"), "not a png")});
  CHECK(text.status == 2);
  CHECK(text.one_line_error());
}

TEST_CASE("devices --check exits 1 when a device fails its self-test", "[cli][compare][opencl]") {
  // fp64 on a device without cl_khr_fp64 (Mesa rusticl's llvmpipe) fails the
  // self-test; the check ran, so the status is 1, not 2.
  const std::string rusticl = "RUSTICL_ENABLE=${RUSTICL_ENABLE:-swrast}";  // Mesa's llvmpipe device
  auto list = run_clrt({"devices"}, rusticl);
  REQUIRE(list.status == 0);
  if (list.out.find("rusticl") == std::string::npos) {
    WARN("no device without fp64 (rusticl) installed; skipped");
    return;
  }
  auto r = run_clrt({"devices", "--check", "--precision", "fp64"}, rusticl);
  CHECK(r.status == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
  CHECK(r.err.find("clrt: check failed: ") != std::string::npos);
}

}  // namespace test_compare_gate

// test_stability.cpp - the stiff/extreme suite (`clrt stability`): the
// default float32 variant passes every stable-suite case, naive fails where
// the floor breaks it, fp64 passes everything it runs; robust's specialized
// builds give the generic kernel's images; supersampling the reference
// changes only edge pixels and converges.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cl/device.hpp"
#include "cli_run.hpp"
#include "eval/compare.hpp"
#include "eval/stability.hpp"
#include "reference/reference.hpp"
#include "render/kernel_features.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_stability {

using namespace clrt;

TEST_CASE("stability verdict: 0.05% of pixels off by > 1 and no NaN", "[stability]") {
  Comparison c;
  c.pixels = 100000;
  c.off_by_gt1 = 50;  // exactly 0.05%
  CHECK(within_tolerance(c));
  c.off_by_gt1 = 51;
  CHECK_FALSE(within_tolerance(c));
  c.off_by_gt1 = 0;
  c.nan_inf = 1;  // a single NaN pixel fails
  CHECK_FALSE(within_tolerance(c));
}

TEST_CASE("the suite covers the issue's families with stable and extreme cases", "[stability]") {
  auto cases = stability_suite();
  auto has = [&](const std::string& name) {
    for (const auto& c : cases)
      if (c.name() == name) return true;
    return false;
  };
  for (const char* n : {"floor radius 5e3",
                        "floor radius 5e5",
                        "floor radius 5e6",
                        "translation 100",
                        "translation 2e3",
                        "translation 1e5",
                        "scale 1e-3",
                        "scale 1e4",
                        "distant sphere 100",
                        "distant sphere 1e6",
                        "grazing camera height 1e-3",
                        "grazing light elevation 1e-4",
                        "camera inside sphere radius 20",
                        "facing mirrors depth 10",
                        "specular exponent 1e-2",
                        "specular exponent 1e5",
                        "light sum 3",
                        "light above surface 1e-2",
                        "spp 1 vs 16 convergence demo 1spp",
                        "spp 1 vs 16 convergence demo 16spp",
                        "spp 1 vs 16 convergence grazing floor 16spp",
                        "spp 1 vs 16 convergence small sphere 16spp",
                        "zero lights",
                        "empty scene"}) {
    INFO(n);
    CHECK(has(n));
  }
  for (const auto& c : cases) {
    INFO(c.name());
    // The requirement: floor radius up to 5e5 and translation up to
    // 2e3 are in the stable suite.
    if (c.family == "floor radius") CHECK(c.stable == (c.param != "5e6"));
    if (c.family == "translation") CHECK(c.stable == (c.param == "100" || c.param == "1e3" || c.param == "2e3"));
    if (c.stable) CHECK(c.expectation(Precision::Robust) == Expect::Pass);
    // Supersampled cases come in pairs: N = 4 (16 samples) and its twin at
    // 1 sample, the same scene and depth, stable for robust and fp64 alike.
    if (c.family == "spp 1 vs 16 convergence") {
      CHECK(c.stable);
      CHECK(c.expectation(Precision::Fp64) == Expect::Pass);
      CHECK(c.sampling.spp == (c.baseline.empty() ? 1 : 4));
      CHECK_FALSE(c.sampling.adaptive());
    }
    if (!c.baseline.empty()) {
      size_t twins = 0;
      for (const auto& t : cases)
        if (t.name() == c.baseline) {
          ++twins;
          CHECK(t.sampling.spp == 1);
          CHECK(t.depth == c.depth);
        }
      CHECK(twins == 1);
    }
  }
}

TEST_CASE("supersampling the reference changes only edge pixels and converges", "[stability]") {
  // What `clrt stability` reports for each 16-sample case: its reference
  // against the twin's at 1 sample (reference only, no device).
  size_t pairs = 0;
  for (const auto& c : stability_suite()) {
    if (c.baseline.empty()) continue;
    ++pairs;
    INFO(c.name());
    const Image one = render_reference(c.scene, 160, 120, c.depth);
    const Image sixteen = render_reference(c.scene, 160, 120, c.depth, c.sampling);
    const SamplingConvergence change = sampling_change(sixteen, one);
    INFO("mean abs " << change.mean_abs_8bit << ", " << change.change.differ << " changed, " << change.change.off_by_gt1
                     << " by > 1, " << change.changed_off_edges << " off edges");
    // Supersampling does change the image (measured at 160x120: 14%, 9.6%
    // and 1.1% of the pixels for demo, grazing floor, small sphere)...
    CHECK(change.change.off_by_gt1 > 0);
    // ...but only at edges. Tolerance 0: a pixel whose 3x3 neighbourhood in
    // the 1-sample image is flat (one primitive, one shadow mask, every
    // neighbour within one 8-bit level, so within 2 levels in float) has a
    // colour whose second difference is below 4 levels per pixel^2 where it
    // is smooth; the 4x4 grid's mean moves from the centre's value by that
    // curvature times the grid's mean squared offset, 5/64 per axis, halved:
    // under 0.32 levels, and an 8-bit value moves by more than one level only
    // when the float moves by more than one. Only a feature smaller than the
    // pixel spacing could change a flat pixel, and these scenes have none at
    // 160x120 (measured: 0 in each).
    CHECK(change.changed_off_edges == 0);
    // The edges are a minority of the pixels, so the image as a whole moves
    // by under one level on average (measured 0.32, 0.40, 0.04).
    CHECK(change.mean_abs_8bit < 1);
    // Converges: 16 samples are much closer than 1 to an image of 64 samples
    // per pixel (--spp 8). Stratified 4x4 sampling resolves a straight edge
    // in steps of a quarter pixel: for a grid-aligned edge at a random offset
    // its RMS error is 0.25/sqrt(12) = 0.07 of the contrast against 0.29 at
    // one sample, a factor 4. A scene's few edges sit at fixed offsets, so
    // the measured factor varies (RMSE float: demo 2.10 -> 0.30, grazing
    // floor 3.08 -> 0.43, small sphere 0.74 -> 0.33, where the floor's
    // horizon crosses a row of pixels between the 4 rows of samples and the
    // 8 rows of the finer image); 1.5 keeps the claim with room for that.
    const Image converged = render_reference(c.scene, 160, 120, c.depth, Sampling(8));
    const double from_one = compare_images(one, converged).rmse_float;
    const double from_sixteen = compare_images(sixteen, converged).rmse_float;
    INFO("RMSE against 64 samples: 1 sample " << from_one << ", 16 samples " << from_sixteen);
    CHECK(from_sixteen * 1.5 < from_one);
  }
  CHECK(pairs == 3);
}

TEST_CASE("every variant meets its expectations on the whole suite (160x120)", "[stability][opencl][slow]") {
  // Tolerance: the verdict above (0.05% of 19,200 pixels = 9 pixels off by
  // more than one level, zero NaN/Inf). Robust is required to pass every
  // stable case; naive and stable must FAIL every floor radius (measured
  // 1.9% to 27% off by > 1, far beyond 0.05%, so this is not marginal: it
  // shows the verdict can fail); fp64 must pass every stable case.
  const auto cases = stability_suite();
  DeviceInfo dev = clrt_test::test_device();
  const StabilityRun run = run_stability(cases, all_precisions(), 160, 120, dev, KernelConfig{});
  const auto& results = run.results;
  REQUIRE(results.size() == cases.size() * all_precisions().size());
  size_t naive_floor_fails = 0;
  for (const auto& r : results) {
    const auto& c = cases[r.case_index];
    INFO(c.name() << " / " << precision_name(r.variant) << ": " << r.error.percent_off_by_gt1() << "% off by > 1, "
                  << r.error.nan_inf << " NaN");
    CHECK(r.as_expected());
    if (r.variant == Precision::Robust) {
      // Zero NaN/Inf on every case, extreme ones included.
      CHECK(r.error.nan_inf == 0);
      if (c.stable) CHECK(r.pass);
    }
    if (r.variant == Precision::Naive && c.family == "floor radius") {
      CHECK_FALSE(r.pass);
      naive_floor_fails += !r.pass;
    }
    if (r.variant == Precision::Fp64) {
      CHECK(r.supported == dev.fp64);
      // fp64 runs the book's formulas in double: it passes every case it runs
      // (measured: all of them, worst 0.03% = 6 silhouette pixels at distant
      // sphere 1e4, against the 0.05% allowance).
      if (r.supported) CHECK(r.pass);
    }
  }
  CHECK(naive_floor_fails == 4);
  auto summary = family_outcomes(cases, results);
  CHECK(summary.size() > 5);
  // One measure per 16-sample case, against its twin's reference (the
  // bounds on it: the test before).
  REQUIRE(run.convergence.size() == 3);
  for (const auto& sc : run.convergence) {
    INFO(cases[sc.case_index].name());
    CHECK(cases[sc.case_index].baseline == sc.baseline);
    CHECK(sc.change.pixels == 160 * 120);
    CHECK(sc.change.differ > 0);
    CHECK(sc.changed_off_edges == 0);
  }
}

TEST_CASE("clrt stability --json reports every case x variant and the summary", "[stability][cli][opencl][slow]") {
  // Tiny images: only the report's structure is checked here (verdicts at
  // this size are not meaningful: one pixel is 0.08%).
  auto r = clrt_test::run_clrt({"stability", "--json", "--width", "40", "--height", "30"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["results"].size() == stability_suite().size() * all_precisions().size());
  CHECK(j["max_pixels_off_by_gt1_percent"] == kTolerancePercentOffByGt1);
  CHECK(j["max_nan_inf_pixels"] == kToleranceNanInfPixels);
  CHECK(j["clrt_version"].is_string());
  CHECK(nlohmann::ordered_json::parse(r.out).begin().key() == "clrt_version");  // the report header first
  CHECK(j["summary"].size() > 5);
  CHECK(j["results"][0]["case"] == "floor radius 5e3");
  CHECK(j["results"][0]["variant"] == "naive");
  CHECK(j["results"][0]["spp"] == 1);
  // How far supersampling moves the reference, one entry per 16-sample case.
  const auto& change = j["reference_supersampling_change"];
  REQUIRE(change.size() == 3);
  CHECK(change[0]["case"] == "spp 1 vs 16 convergence demo 16spp");
  CHECK(change[0]["baseline"] == "spp 1 vs 16 convergence demo 1spp");
  CHECK(change[0]["spp"] == 4);
  CHECK(change[0]["pixels"] == 40 * 30);
  for (const char* key : {"mean_abs_8bit", "pixels_differ", "pixels_changed_percent", "pixels_off_by_gt1",
                          "max_abs_8bit", "pixels_changed_off_edges"}) {
    INFO(key);
    CHECK(change[0].contains(key));
  }
}

TEST_CASE("robust: every case gives the generic kernel's image when specialized",
          "[stability][opencl][specialize][per-case-builds][slow]") {
  // The suite runs the generic kernel, which decides per sphere at run time
  // between compensated and cheap arithmetic (clrt_sphere.compensated). A
  // specialized build compiles out the path no sphere of the scene takes
  // (CLRT_COMPENSATED_SPHERES=0 or 1) or, when they differ, makes each
  // sphere's flag a constant (CLRT_COMPENSATED_FLAGS); each sphere must get
  // the same arithmetic, so the same hits, shadows and
  // 8-bit colours. (Not the same floats everywhere: the two builds' shading
  // rounds differently on a few of these scenes, by up to 0.002 of a level.)
  // The suite has scenes of all three kinds.
  DeviceInfo dev = clrt_test::test_device();
  KernelConfig generic;
  generic.specialize = false;
  Renderer generic_renderer({dev}, RenderSettings{generic, {}, {}});
  Renderer special_renderer({dev}, RenderSettings{KernelConfig{}, {}, {}});
  size_t none = 0, all = 0, mixed = 0;
  for (const auto& c : stability_suite()) {
    INFO(c.name());
    const KernelFeatures f = kernel_features(c.scene, c.depth);
    none += f.compensated_spheres() == 0;
    all += f.compensated_spheres() > 0 && f.compensated_spheres() == f.sphere_count;
    mixed += f.compensated_spheres() > 0 && f.compensated_spheres() < f.sphere_count;
    generic_renderer.prepare(c.scene, 160, 120, c.depth);
    special_renderer.prepare(c.scene, 160, 120, c.depth);
    const Comparison d = compare_images(special_renderer.render(), generic_renderer.render());
    CHECK(d.off_by_gt1 == 0);
    CHECK(d.max_abs_float < 0.01);
    CHECK(d.hit_flips == 0);
    CHECK(d.shadow_flips == 0);
  }
  CHECK(none > 0);   // e.g. distant sphere 100, empty scene
  CHECK(all > 0);    // distant sphere 1e4 and beyond
  CHECK(mixed > 0);  // the demo's floor with its unit spheres
}

}  // namespace test_stability

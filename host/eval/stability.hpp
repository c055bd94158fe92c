// stability.hpp - a generated suite of stiff and extreme scenes, each run
// through every precision variant against the double reference, with a
// pass/fail verdict per variant (`clrt stability`). The verdict is
// within_tolerance (compare.hpp).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "eval/compare.hpp"
#include "render/build_options.hpp"
#include "render/precision.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"
#include "util/progress.hpp"

namespace clrt {

enum class Expect { Any, Pass, Fail };

struct StabilityCase {
  std::string family;  // e.g. "floor radius"
  std::string param;   // e.g. "5e5"
  Scene scene;
  int depth = 3;
  // Samples per pixel (N x N, --spp N): both engines render the case with
  // it, so the verdict compares like with like.
  Sampling sampling;
  // For a case rendered with N > 1: the name of its twin at 1 sample per
  // pixel (the same scene and depth). The report measures how far
  // supersampling moves the reference image from the twin's ("" = none).
  std::string baseline;
  // Part of the stable suite: the default (robust) variant must pass it.
  bool stable = true;
  std::map<Precision, Expect> expect;  // missing = Any
  std::string note;                    // what the case stresses
  std::string name() const { return param.empty() ? family : family + " " + param; }
  Expect expectation(Precision p) const {
    auto it = expect.find(p);
    return it == expect.end() ? Expect::Any : it->second;
  }
};

// Every case, families in a fixed order, each family's parameter from mild to
// extreme.
std::vector<StabilityCase> stability_suite();

struct StabilityResult {
  size_t case_index = 0;
  Precision variant = Precision::Robust;
  bool supported = true;
  Comparison error;
  bool pass = false;
  bool as_expected() const;
  Expect expected = Expect::Any;
};

// How far supersampling moves the reference: a case's reference image at
// N x N samples per pixel against its baseline twin's at 1 sample.
// Averaging samples changes a pixel only where the colour varies within it:
// silhouettes, shadow and reflection borders, highlights.
struct SamplingConvergence {
  size_t case_index = 0;     // the N x N case
  std::string baseline;      // the 1-sample case it is measured against
  Comparison change;         // reference(N x N) against reference(1): pixels changed, max, RMSE
  double mean_abs_8bit = 0;  // mean |8-bit difference| over every channel of every pixel
  // Pixels changed by more than one level although the 1-sample image is
  // flat around them: every pixel of their 3 x 3 neighbourhood shows the
  // same primitive and shadow mask, within one level of the pixel's colour.
  // The claim "supersampling changes only edge pixels" counts these.
  size_t changed_off_edges = 0;
  double percent_changed() const { return change.pixels ? 100.0 * change.differ / change.pixels : 0.0; }
};

struct StabilityRun {
  std::vector<StabilityResult> results;          // variant by variant, each over every case
  std::vector<SamplingConvergence> convergence;  // one per case with a baseline, in the suite's order
};

// Runs each case on each variant (generic, unspecialized kernels: one build
// per variant for the whole suite) at width x height on one device, and
// measures each supersampled case's reference against its baseline's.
// `progress` (optional): the references, then each case of each variant.
StabilityRun run_stability(const std::vector<StabilityCase>& cases, const std::vector<Precision>& variants, int width,
                           int height, const DeviceInfo& device, const KernelConfig& base,
                           const ProgressFn& progress = {});

// Reference(N x N) against reference(1) for one supersampled case (exposed
// for the tests: the measure behind SamplingConvergence).
SamplingConvergence sampling_change(const Image& supersampled, const Image& single);

// Results whose verdict differs from the case's expectation.
size_t count_unmet(const std::vector<StabilityResult>& results);

// Where one variant passes and where it breaks within one family of cases.
struct FamilyOutcome {
  Precision variant = Precision::Robust;
  std::string family;
  bool supported = true;
  std::vector<std::string> passed, failed;  // the cases' params, mild to extreme ("" for a case without one)
};

// One per variant (in the results' order) and family (in the suite's order).
std::vector<FamilyOutcome> family_outcomes(const std::vector<StabilityCase>& cases,
                                           const std::vector<StabilityResult>& results);

}  // namespace clrt

// stability.hpp - a generated suite of stiff and extreme scenes, each run
// through every precision variant against the double reference, with a
// pass/fail verdict per variant (`clrt stability`).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "render/build_options.hpp"
#include "eval/compare.hpp"
#include "render/precision.hpp"
#include "scene/scene.hpp"

namespace clrt {

// The verdict, in one place: a variant passes a case when at most this share
// of pixels is off by more than one 8-bit level and no pixel is NaN/Inf.
constexpr double kStabilityMaxPercentOffByGt1 = 0.05;
constexpr size_t kStabilityMaxNanPixels = 0;
bool stability_pass(const Comparison& c);

enum class Expect { Any, Pass, Fail };

struct StabilityCase {
  std::string family;  // e.g. "floor radius"
  std::string param;   // e.g. "5e5"
  Scene scene;
  int depth = 3;
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

// Runs each case on each variant (generic, unspecialized kernels: one build
// per variant for the whole suite) at width x height on one device.
std::vector<StabilityResult> run_stability(const std::vector<StabilityCase>& cases,
                                           const std::vector<Precision>& variants, int width, int height,
                                           const std::string& device, const KernelConfig& base);

// One line per variant and family: where the variant passes and breaks, e.g.
// "naive   floor radius: fails from 5e3 (all)".
std::vector<std::string> stability_summary(const std::vector<StabilityCase>& cases,
                                           const std::vector<StabilityResult>& results);

}  // namespace clrt

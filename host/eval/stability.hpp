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
#include "scene/scene.hpp"

namespace clrt {

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
                                           const DeviceInfo& device, const KernelConfig& base);

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

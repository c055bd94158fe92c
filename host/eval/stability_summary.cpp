// stability_summary.cpp - what a stability run says: the verdicts that
// differ from the expectations, and where each variant breaks per family.
#include <string>
#include <vector>

#include "eval/stability.hpp"

namespace clrt {

bool StabilityResult::as_expected() const {
  if (!supported) return true;
  return expected == Expect::Any || (expected == Expect::Pass) == pass;
}

size_t count_unmet(const std::vector<StabilityResult>& results) {
  size_t unmet = 0;
  for (const auto& r : results) unmet += !r.as_expected();
  return unmet;
}

std::vector<FamilyOutcome> family_outcomes(const std::vector<StabilityCase>& cases,
                                           const std::vector<StabilityResult>& results) {
  std::vector<Precision> variants;
  for (const auto& r : results)
    if (variants.empty() || variants.back() != r.variant) variants.push_back(r.variant);
  std::vector<std::string> families;
  for (const auto& c : cases)
    if (families.empty() || families.back() != c.family) families.push_back(c.family);
  std::vector<FamilyOutcome> out;
  for (Precision p : variants)
    for (const auto& family : families) {
      FamilyOutcome o;
      o.variant = p;
      o.family = family;
      for (const auto& r : results) {
        if (r.variant != p || cases[r.case_index].family != family) continue;
        o.supported &= r.supported;
        (r.pass ? o.passed : o.failed).push_back(cases[r.case_index].param);
      }
      out.push_back(o);
    }
  return out;
}

}  // namespace clrt

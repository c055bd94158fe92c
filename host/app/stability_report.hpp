// stability_report.hpp - how `clrt stability` shows its results: a table with
// a verdict per case and variant, one JSON object, the summary of where each
// variant breaks, and how far supersampling moves the reference.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/stability.hpp"

namespace clrt {

// One line per variant and family, e.g. "naive   floor radius: fails all
// (5e3, 5e4, 5e5, 5e6)".
std::vector<std::string> stability_summary(const std::vector<FamilyOutcome>& outcomes);

nlohmann::ordered_json stability_json(const std::string& device, int width, int height,
                                      const std::vector<StabilityCase>& cases, const StabilityRun& run);
void print_stability(const std::string& device, int width, int height, const std::vector<StabilityCase>& cases,
                     const StabilityRun& run);

}  // namespace clrt

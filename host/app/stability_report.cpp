// stability_report.cpp - the stability suite's table, JSON and summary.
#include "app/stability_report.hpp"

#include <algorithm>
#include <cstdio>

#include "app/compare_report.hpp"
#include "app/report_header.hpp"

namespace clrt {
namespace {

const char* expect_name(Expect e) {
  return e == Expect::Pass ? "pass" : e == Expect::Fail ? "fail" : "any";
}

std::string join(const std::vector<std::string>& params) {
  std::string out;
  for (const auto& p : params) out += (out.empty() ? "" : ", ") + p;
  return out;
}

std::string summary_line(const FamilyOutcome& o) {
  const std::string name = precision_name(o.variant);
  const std::string passed = join(o.passed), failed = join(o.failed);
  std::string line = name + std::string(8 - std::min<size_t>(7, name.size()), ' ') + o.family + ": ";
  if (!o.supported)
    line += "unsupported on this device";
  else if ((passed + failed).empty())  // one case without a parameter
    line += o.failed.empty() ? "passes" : "fails";
  else if (o.failed.empty())
    line += "passes all (" + passed + ")";
  else if (o.passed.empty())
    line += "fails all (" + failed + ")";
  else
    line += "passes " + passed + "; fails " + failed;
  return line;
}

}  // namespace

std::vector<std::string> stability_summary(const std::vector<FamilyOutcome>& outcomes) {
  std::vector<std::string> lines;
  for (const auto& o : outcomes) lines.push_back(summary_line(o));
  return lines;
}

nlohmann::ordered_json stability_json(const std::string& device, int width, int height,
                                      const std::vector<StabilityCase>& cases, const StabilityRun& run) {
  const auto& results = run.results;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const auto& res : results) {
    const auto& c = cases[res.case_index];
    nlohmann::ordered_json j = {{"case", c.name()},           {"family", c.family},
                                {"param", c.param},           {"spp", c.sampling.spp},
                                {"stable", c.stable},         {"variant", precision_name(res.variant)},
                                {"supported", res.supported}, {"expected", expect_name(res.expected)}};
    if (res.supported) {
      j["pass"] = res.pass;
      j["as_expected"] = res.as_expected();
      j.update(comparison_json(res.error));
    }
    rows.push_back(j);
  }
  nlohmann::ordered_json convergence = nlohmann::ordered_json::array();
  for (const auto& sc : run.convergence) {
    const auto& c = cases[sc.case_index];
    nlohmann::ordered_json j = {{"case", c.name()},
                                {"baseline", sc.baseline},
                                {"spp", c.sampling.spp},
                                {"mean_abs_8bit", sc.mean_abs_8bit},
                                {"pixels_changed_percent", sc.percent_changed()},
                                {"pixels_changed_off_edges", sc.changed_off_edges}};
    j.update(comparison_json(sc.change));
    convergence.push_back(j);
  }
  nlohmann::ordered_json out = header_json(report_header(device));
  out.update(nlohmann::ordered_json{{"device", device},
                                    {"width", width},
                                    {"height", height},
                                    {"max_pixels_off_by_gt1_percent", kTolerancePercentOffByGt1},
                                    {"max_nan_inf_pixels", kToleranceNanInfPixels},
                                    {"results", rows},
                                    {"summary", stability_summary(family_outcomes(cases, results))},
                                    {"reference_supersampling_change", convergence},
                                    {"unmet_expectations", count_unmet(results)}});
  return out;
}

void print_stability(const std::string& device, int width, int height, const std::vector<StabilityCase>& cases,
                     const StabilityRun& run) {
  const auto& results = run.results;
  std::printf("device %s, %dx%d; pass = at most %.2f%% of pixels off by > 1 level and %zu NaN/Inf pixels\n",
              device.c_str(), width, height, kTolerancePercentOffByGt1, kToleranceNanInfPixels);
  std::printf("%-44s %-7s %10s %6s %9s %9s  %-7s %s\n", "case", "variant", "% off >1", "NaN", "hit flip", "shad flip",
              "verdict", "expected");
  for (const auto& res : results) {
    const auto& c = cases[res.case_index];
    std::string name = c.name() + (c.stable ? "" : " *");
    if (!res.supported) {
      std::printf("%-44s %-7s %10s\n", name.c_str(), precision_name(res.variant).c_str(), "unsupported");
      continue;
    }
    const auto& e = res.error;
    std::printf("%-44s %-7s %10.4f %6zu %9zu %9zu  %-7s %s%s\n", name.c_str(), precision_name(res.variant).c_str(),
                e.percent_off_by_gt1(), e.nan_inf, e.hit_flips, e.shadow_flips, res.pass ? "pass" : "FAIL",
                expect_name(res.expected), res.as_expected() ? "" : "  <-- unexpected");
  }
  std::printf(
      "(* = extreme case, outside the stable suite the default variant must pass)\n\nwhere each variant breaks:\n");
  for (const auto& l : stability_summary(family_outcomes(cases, results))) std::printf("  %s\n", l.c_str());
  if (!run.convergence.empty()) {
    std::printf(
        "\nthe reference supersampled against itself at 1 sample per pixel (edge = not flat in the 1-sample "
        "image's 3x3 neighbourhood):\n");
    std::printf("  %-44s %8s %14s %14s %8s %10s\n", "case", "mean abs", "pixels changed", "off by > 1", "max",
                "off edges");
    for (const auto& sc : run.convergence) {
      const auto& e = sc.change;
      std::printf("  %-44s %8.3f %7zu %5.2f%% %7zu %5.2f%% %8d %10zu\n", cases[sc.case_index].name().c_str(),
                  sc.mean_abs_8bit, e.differ, sc.percent_changed(), e.off_by_gt1, e.percent_off_by_gt1(),
                  e.max_abs_8bit, sc.changed_off_edges);
    }
  }
  const size_t unmet = count_unmet(results);
  std::printf("\nexpectations: %s\n", unmet ? (std::to_string(unmet) + " not met").c_str() : "all met");
}

}  // namespace clrt

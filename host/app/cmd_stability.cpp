// cmd_stability.cpp - `clrt stability`: the stiff/extreme suite on every
// variant, with verdicts and where each variant breaks.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli_common.hpp"
#include "eval/compare_json.hpp"
#include "cl/device.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"
#include "eval/stability.hpp"

namespace clrt {

namespace {
const char* expect_name(Expect e) {
  return e == Expect::Pass ? "pass" : e == Expect::Fail ? "fail" : "any";
}
}  // namespace

void add_stability_command(CLI::App& app) {
  struct Opts {
    int width = 160, height = 120;
    std::string device;
    bool json = false, check = false, no_ftz = false;
    std::string kernel_dir;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand("stability", "Run the generated stiff/extreme suite on every precision variant");
  cmd->add_option("--width", o->width, "Image width in pixels (default 160)");
  cmd->add_option("--height", o->height, "Image height in pixels (default 120)");
  cmd->add_option("--device", o->device, "Device index or name/type substring (default: first GPU, else first)");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->add_flag("--check", o->check, "Exit with status 1 if a result differs from its declared expectation");
  cmd->add_flag("--no-ftz", o->no_ftz, "Do not build with -cl-denorms-are-zero");
  cmd->add_option("--kernel-dir", o->kernel_dir, "Read kernels from this directory instead of the embedded copies");
  cmd->callback([o] {
    RenderOptions r;
    r.width = o->width;
    r.height = o->height;
    r.no_ftz = o->no_ftz;
    r.kernel_dir = o->kernel_dir;
    r.validate();
    const auto cases = stability_suite();
    const auto& variants = all_precisions();
    const std::string device = select_device(o->device).name;
    const auto results = run_stability(cases, variants, o->width, o->height, o->device, r.kernel_config());
    const auto summary = stability_summary(cases, results);
    size_t unmet = 0;
    for (const auto& res : results) unmet += !res.as_expected();

    if (o->json) {
      nlohmann::json rows = nlohmann::json::array();
      for (const auto& res : results) {
        const auto& c = cases[res.case_index];
        nlohmann::json j = {{"case", c.name()},
                            {"family", c.family},
                            {"param", c.param},
                            {"stable", c.stable},
                            {"variant", precision_name(res.variant)},
                            {"supported", res.supported},
                            {"expected", expect_name(res.expected)}};
        if (res.supported) {
          j["pass"] = res.pass;
          j["as_expected"] = res.as_expected();
          j.update(comparison_json(res.error));
        }
        rows.push_back(j);
      }
      nlohmann::json out = {{"device", device},
                            {"width", o->width},
                            {"height", o->height},
                            {"max_percent_off_by_gt1", kStabilityMaxPercentOffByGt1},
                            {"max_nan_pixels", kStabilityMaxNanPixels},
                            {"results", rows},
                            {"summary", summary},
                            {"unmet_expectations", unmet}};
      std::printf("%s\n", json_text(out).c_str());
    } else {
      std::printf("device %s, %dx%d; pass = at most %.2f%% of pixels off by > 1 level and %zu NaN/Inf pixels\n",
                  device.c_str(), o->width, o->height, kStabilityMaxPercentOffByGt1, kStabilityMaxNanPixels);
      std::printf("%-32s %-7s %10s %6s %9s %9s  %-7s %s\n", "case", "variant", "% off >1", "NaN", "hit flip",
                  "shad flip", "verdict", "expected");
      for (const auto& res : results) {
        const auto& c = cases[res.case_index];
        std::string name = c.name() + (c.stable ? "" : " *");
        if (!res.supported) {
          std::printf("%-32s %-7s %10s\n", name.c_str(), precision_name(res.variant).c_str(), "unsupported");
          continue;
        }
        const auto& e = res.error;
        std::printf("%-32s %-7s %10.4f %6zu %9zu %9zu  %-7s %s%s\n", name.c_str(), precision_name(res.variant).c_str(),
                    e.percent_off_by_gt1(), e.nan_inf, e.hit_flips, e.shadow_flips, res.pass ? "pass" : "FAIL",
                    expect_name(res.expected), res.as_expected() ? "" : "  <-- unexpected");
      }
      std::printf(
          "(* = extreme case, outside the stable suite the default variant must pass)\n\nwhere each variant breaks:\n");
      for (const auto& l : summary) std::printf("  %s\n", l.c_str());
      std::printf("\nexpectations: %s\n", unmet ? (std::to_string(unmet) + " not met").c_str() : "all met");
    }
    if (o->check && unmet)
      throw CheckFailure("stability: " + std::to_string(unmet) + " result(s) differ from expectation");
  });
}

}  // namespace clrt

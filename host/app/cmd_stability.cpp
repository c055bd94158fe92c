// cmd_stability.cpp - `clrt stability`: the stiff/extreme suite on every
// variant, with verdicts and where each variant breaks.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/options.hpp"
#include "app/stability_report.hpp"
#include "cl/device.hpp"
#include "eval/stability.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"
#include "util/progress.hpp"

namespace clrt {

namespace {
// The suite's default size: 160 x 120.
ImageOptions stability_image() {
  ImageOptions image;
  image.width = 160;
  image.height = 120;
  return image;
}
}  // namespace

void add_stability_command(CLI::App& app) {
  struct Opts {
    ImageOptions image = stability_image();
    DeviceOptions device;
    KernelOptions kernel;
    bool json = false, check = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand("stability", "Run the generated stiff/extreme suite on every precision variant");
  o->image.add(cmd, /*with_depth=*/false, /*with_spp=*/false);  // each case has its own depth and sampling
  o->device.add(cmd, /*several=*/false);
  o->kernel.add(cmd, /*with_variant=*/false, /*with_specialize=*/false);  // the suite runs every variant, generic
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->add_flag("--check", o->check, "Exit with status 1 if a result differs from its declared expectation");
  cmd->callback([o] {
    o->image.validate();
    const int width = o->image.width, height = o->image.height;
    const auto cases = stability_suite();
    const DeviceInfo dev = o->device.one();
    const StabilityRun run = run_stability(cases, all_precisions(), width, height, dev, o->kernel.config(),
                                           stderr_progress());  // on a terminal only, not with --quiet
    if (o->json)
      std::printf("%s\n", json_text(stability_json(dev.name, width, height, cases, run)).c_str());
    else
      print_stability(dev.name, width, height, cases, run);
    const size_t unmet = count_unmet(run.results);
    if (o->check && unmet)
      throw CheckFailure("stability: " + std::to_string(unmet) + " result(s) differ from expectation");
  });
}

}  // namespace clrt

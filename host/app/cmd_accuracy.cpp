// cmd_accuracy.cpp - `clrt accuracy SCENE...`: error against kernel time for
// every precision variant.
#include <cstdio>
#include <memory>
#include <sstream>

#include "app/accuracy_report.hpp"
#include "app/options.hpp"
#include "cl/device.hpp"
#include "eval/accuracy.hpp"
#include "image/image_file.hpp"
#include "image/plot.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

namespace clrt {

namespace {
std::string default_variant_list() {
  std::string list;
  for (const AccuracyVariant& v : default_accuracy_variants()) list += (list.empty() ? "" : ",") + v.name();
  return list;
}

std::vector<AccuracyVariant> parse_variants(const std::string& list) {
  std::vector<AccuracyVariant> out;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ','))
    if (!name.empty()) out.push_back(parse_accuracy_variant(name));
  if (out.empty()) throw UserError("--variants: empty list");
  return out;
}
}  // namespace

void add_accuracy_command(CLI::App& app) {
  struct Opts {
    std::vector<std::string> scenes;
    ImageOptions image;
    DeviceOptions device;
    KernelOptions kernel;
    int repeat = 7;
    std::string variants = default_variant_list();
    std::string csv, plot;
    bool json = false, markdown = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "accuracy",
      "Kernel time (median of --repeat after a warm-up) against error vs the reference, per variant x scene");
  cmd->add_option("scenes", o->scenes, "Scene files (JSON)")->required()->expected(1, -1);
  o->image.add(cmd, /*with_depth=*/true, /*with_spp=*/true, /*with_subsample=*/false);  // a variant here
  o->device.add(cmd, /*several=*/false);
  o->kernel.add(cmd, /*with_variant=*/false);
  add_repeat_option(cmd, o->repeat, "Timed kernel runs per variant after one warm-up");
  cmd->add_option("--variants", o->variants,
                  "Comma list of variants: precisions, each optionally +subsample (the book's subsampling)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print one JSON object instead of the table");
  cmd->add_flag("--markdown", o->markdown, "Print the table as Markdown");
  cmd->add_option("--csv", o->csv, "Also write the rows as CSV to this file");
  cmd->add_option("--plot", o->plot, "Also write an error-vs-time chart (log-log) here: .png, .svg or .pdf");
  cmd->callback([o] {
    o->image.validate();
    if (!o->plot.empty()) check_plot_output(o->plot);    // fail before measuring
    if (!o->csv.empty()) check_writable(o->csv, "CSV");  // fail before measuring, not after
    AccuracySettings s;
    s.width = o->image.width;
    s.height = o->image.height;
    s.depth = o->image.depth;
    s.spp = o->image.spp;
    s.adaptive = o->image.adaptive;
    s.repeat = o->repeat;
    s.base = o->kernel.config();
    s.variants = parse_variants(o->variants);
    std::vector<NamedScene> scenes;
    for (const auto& p : o->scenes) scenes.push_back({p, o->image.load_scene(p)});
    const DeviceInfo dev = o->device.one();
    const std::string device = dev.name;
    s.progress = stderr_progress();  // on a terminal only, not with --quiet
    auto rows = measure_accuracy(scenes, dev, s);
    if (!o->csv.empty()) write_accuracy_csv(rows, o->csv, device);
    if (!o->plot.empty())
      write_accuracy_plot(
          rows, o->plot,
          "Error vs kernel time, " + std::to_string(s.width) + "x" + std::to_string(s.height) + ", " + device);
    if (o->json) {
      std::printf("%s\n", accuracy_json(rows, s, device).c_str());
      return;
    }
    std::printf("device %s, %dx%d, %dx%d samples per pixel, kernel time = median of %d runs after a warm-up\n",
                device.c_str(), s.width, s.height, s.spp, s.spp, s.repeat);
    std::printf("%s", o->markdown ? accuracy_markdown(rows).c_str() : accuracy_table(rows).c_str());
  });
}

}  // namespace clrt

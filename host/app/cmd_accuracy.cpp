// cmd_accuracy.cpp - `clrt accuracy SCENE...`: error against kernel time for
// every precision variant.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <sstream>

#include "app/accuracy_report.hpp"
#include "app/options.hpp"
#include "cl/device.hpp"
#include "dist/communicator.hpp"
#include "dist/eval_grids.hpp"
#include "dist/job.hpp"
#include "eval/accuracy.hpp"
#include "image/image_file.hpp"
#include "image/plot.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

namespace clrt {

namespace {

void report_accuracy(const std::vector<AccuracyRow>& rows, const AccuracyOptions& o, const AccuracySettings& s,
                     const std::string& device, const dist::GridStats* grid) {
  const int ranks = grid ? int(grid->ranks.size()) : 1;
  if (!o.csv.empty()) write_accuracy_csv(rows, o.csv, device);
  if (!o.plot.empty())
    write_accuracy_plot(
        rows, o.plot,
        "Error vs kernel time, " + std::to_string(s.width) + "x" + std::to_string(s.height) + ", " + device);
  if (o.json) {
    std::printf("%s\n", accuracy_json(rows, s, device, o.image.overrides, ranks).c_str());
    return;
  }
  std::fprintf(report_stream(), "device %s, %dx%d, %dx%d samples per pixel, kernel time = median of %d runs after a warm-up\n",
              device.c_str(), s.width, s.height, s.spp, s.spp, s.repeat);
  if (grid)
    std::fprintf(report_stream(), 
        "%d MPI ranks: each (scene, variant) timed on the rank that ran it, its runs back to back; ranks on "
        "one machine contend for its cores, so the times are not comparable with a one-process run\n",
        ranks);
  std::fprintf(report_stream(), "%s", o.markdown ? accuracy_markdown(rows).c_str() : accuracy_table(rows).c_str());
  if (grid) std::fprintf(report_stream(), "%s", dist::grid_share_lines(*grid).c_str());
}

// `clrt accuracy` launched by mpirun with several ranks: rank 0 checks the
// options and outputs, reads the scenes and selects the device; every rank
// gets them (no shared file system is assumed) and measures the cells rank
// 0 hands it (dist/eval_grids.hpp); rank 0 reports.
void accuracy_across_ranks(const AccuracyOptions& o) {
  dist::Communicator& comm = dist::world();
  DeviceInfo dev;
  const dist::Bytes bytes = dist::share_from_root(comm, [&] {
    o.check();
    dist::AccuracyInput in;
    for (const auto& p : o.scenes) in.scenes.push_back({p, o.image.load_scene(p)});
    dev = o.device.one();
    in.device = dist::device_label(dev);
    return dist::encode_accuracy_input(in);
  });
  const dist::AccuracyInput in = dist::decode_accuracy_input(bytes);
  AccuracySettings s = o.settings();  // (as on rank 0, where it passed)
  s.progress = stderr_progress();
  // Rank 0's device is the one it selected; the others select their own.
  const auto local = [&] { return comm.rank() == 0 ? dev : o.device.one(); };
  dist::GridStats stats;
  auto rows = dist::accuracy_across_ranks(comm, in, local, s, &stats);
  if (comm.rank() == 0) report_accuracy(rows, o, s, in.device.name, &stats);
}

}  // namespace

void add_accuracy_command(CLI::App& app) {
  auto o = std::make_shared<AccuracyOptions>();
  auto* cmd = app.add_subcommand(
      "accuracy",
      "Kernel time (median of --repeat after a warm-up) against error vs the reference, per variant x scene");
  cmd->add_option("scenes", o->scenes, "Scene files (JSON)")->required()->expected(1, -1);
  o->image.add(cmd, /*with_depth=*/true, /*with_spp=*/true, /*with_subsample=*/false);  // a variant here
  o->image.add_ray_budget(cmd);
  add_mpi_timeout_option(cmd);
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
    if (dist::world().distributed()) return accuracy_across_ranks(*o);
    o->check();
    AccuracySettings s = o->settings();
    std::vector<NamedScene> scenes;
    for (const auto& p : o->scenes) scenes.push_back({p, o->image.load_scene(p)});
    const DeviceInfo dev = o->device.one();
    s.progress = stderr_progress();  // on a terminal only, not with --quiet
    report_accuracy(measure_accuracy(scenes, dev, s), *o, s, dev.name, nullptr);
  });
}

}  // namespace clrt

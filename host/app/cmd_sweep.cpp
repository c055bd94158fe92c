// cmd_sweep.cpp - `clrt sweep SCENE --depths A:B`: bench per depth and device.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/options.hpp"
#include "app/report_header.hpp"
#include "app/sweep_report.hpp"
#include "dist/communicator.hpp"
#include "dist/eval_grids.hpp"
#include "dist/job.hpp"
#include "eval/sweep.hpp"
#include "image/image_file.hpp"
#include "image/plot.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

namespace clrt {

namespace {

// What a sweep reports, in one process or across ranks.
struct SweepOutputs {
  std::string csv, plot;
  bool json = false;
};

void report_sweep(const std::vector<SweepRow>& rows, const RenderOptions& o, const SweepOutputs& out,
                  const dist::GridStats* grid) {
  const std::string& scene_path = o.scene_path;
  const int ranks = grid ? int(grid->ranks.size()) : 1;
  if (!out.json) {
    if (grid)
      std::fprintf(report_stream(), 
          "%d MPI ranks: each (depth, device) timed on the rank that ran it; ranks on one machine contend "
          "for its cores, so the times are not comparable with a one-process sweep\n",
          ranks);
    print_sweep(rows);
  }
  // With --json, standard output holds the JSON object alone.
  if (!out.csv.empty()) {
    write_text_atomic(out.csv, sweep_csv(rows), "CSV");
    if (!out.json) std::fprintf(report_stream(), "wrote %s\n", out.csv.c_str());
  }
  if (!out.plot.empty()) {
    std::string second = plot_sweep(rows, out.plot, scene_path);
    if (!out.json) std::fprintf(report_stream(), "wrote %s and %s\n", out.plot.c_str(), second.c_str());
  }
  if (out.json)
    std::printf("%s\n", json_text(sweep_json(rows, scene_path, overrides_json(o.image.overrides), ranks)).c_str());
  if (grid && !out.json) std::fprintf(report_stream(), "%s", dist::grid_share_lines(*grid).c_str());
}

// Outputs checked before measuring (both plots).
void check_sweep_outputs(const SweepOutputs& out) {
  if (!out.plot.empty()) {
    check_plot_output(out.plot);
    check_plot_output(rays_plot_path(out.plot));
  }
  if (!out.csv.empty()) check_writable(out.csv, "CSV");
  std::vector<NamedOutput> all;
  if (!out.csv.empty()) all.push_back({out.csv, "CSV"});
  if (!out.plot.empty()) all.push_back({out.plot, "plot"}), all.push_back({rays_plot_path(out.plot), "rays plot"});
  if (out.json) all.push_back({"-", "JSON"});
  check_distinct_outputs(all);
  claim_stdout_if_dash(out.csv);
}

// `clrt sweep` launched by mpirun with several ranks: rank 0 checks the
// options and outputs, reads the scene and selects the devices; every rank
// gets them (no shared file system is assumed) and measures the cells rank
// 0 hands it (dist/eval_grids.hpp); rank 0 reports.
// The image options at the sweep's deepest depth: the scene's ray tree is
// checked there (ray budget, warning), not at --depth, which a sweep ignores.
ImageOptions deepest(const ImageOptions& image, int depth) {
  ImageOptions at = image;
  at.depth = depth;
  return at;
}

void sweep_across_ranks(const RenderOptions& o, const std::string& depths, const std::string& devices,
                        const SweepSettings& base, const SweepOutputs& out) {
  dist::Communicator& comm = dist::world();
  const std::string spec = devices.empty() ? o.device.device : devices;
  std::vector<DeviceInfo> devs;
  const dist::Bytes bytes = dist::share_from_root(comm, [&] {
    o.validate();
    dist::SweepInput in;
    parse_depth_range(depths, in.depth_from, in.depth_to);
    check_sweep_outputs(out);  // fail before any rank measures
    in.scene = deepest(o.image, in.depth_to).load_scene(o.scene_path);
    devs = select_devices(spec);
    for (const auto& d : devs) in.devices.push_back(dist::device_label(d));
    return dist::encode_sweep_input(in);
  });
  const dist::SweepInput in = dist::decode_sweep_input(bytes);
  SweepSettings s = base;
  s.depth_from = in.depth_from, s.depth_to = in.depth_to;
  // Rank 0's devices are those it selected; the others select their own.
  const auto local = [&] { return comm.rank() == 0 ? devs : select_devices(spec); };
  dist::GridStats stats;
  auto rows = dist::sweep_across_ranks(comm, in, local, o.settings(), s, &stats);
  if (comm.rank() == 0) report_sweep(rows, o, out, &stats);
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto depths = std::make_shared<std::string>("0:10");
  auto devices = std::make_shared<std::string>();
  auto csv = std::make_shared<std::string>();
  auto plot = std::make_shared<std::string>();
  auto repeat = std::make_shared<int>(3);
  auto omp = std::make_shared<bool>(false);
  auto as_json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("sweep", "Bench figures and error vs reference per recursion depth (and device)");
  o->add(cmd, /*with_engine=*/false);
  add_mpi_timeout_option(cmd);
  cmd->add_option("--depths", *depths, "Depth range A:B, inclusive")->capture_default_str();
  cmd->add_option("--devices", *devices,
                  "Devices: index, P:D, list (0,1), 'all', or name substring; unset: those of --device");
  cmd->add_option("--csv", *csv, "Write the table as CSV to this file");
  cmd->add_option("--plot", *plot,
                  "Write time and error per depth here, .png, .svg or .pdf (and rays per depth to NAME-rays.EXT)");
  add_repeat_option(cmd, *repeat, "Timed kernel launches per depth after a warm-up");
  cmd->add_flag("--omp", *omp, "Also time the OpenMP float tracer at each depth");
  cmd->add_flag("--json", *as_json, "Print one JSON object instead of the table");
  cmd->callback([o, depths, devices, csv, plot, repeat, omp, as_json] {
    const SweepOutputs out{*csv, *plot, *as_json};
    SweepSettings s = sweep_settings(*o, *repeat, *omp);
    s.progress = stderr_progress();  // on a terminal only, not with --quiet
    if (dist::world().distributed()) return sweep_across_ranks(*o, *depths, *devices, s, out);
    o->validate();
    parse_depth_range(*depths, s.depth_from, s.depth_to);
    check_sweep_outputs(out);  // fail before measuring
    Scene scene = deepest(o->image, s.depth_to).load_scene(o->scene_path);
    auto devs = select_devices(devices->empty() ? o->device.device : *devices);
    report_sweep(run_sweep(scene, devs, o->settings(), s), *o, out, nullptr);
  });
}

}  // namespace clrt

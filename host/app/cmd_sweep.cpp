// cmd_sweep.cpp - `clrt sweep SCENE --depths A:B`: bench per depth and device.
#include <cstdio>
#include <memory>

#include "app/options.hpp"
#include "app/sweep_report.hpp"
#include "eval/sweep.hpp"
#include "image/image_file.hpp"
#include "image/plot.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

namespace clrt {

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
    o->validate();
    SweepSettings s;
    parse_depth_range(*depths, s.depth_from, s.depth_to);
    if (!plot->empty()) {  // both plots, before measuring
      check_plot_output(*plot);
      check_plot_output(rays_plot_path(*plot));
    }
    if (!csv->empty()) check_writable(*csv, "CSV");  // fail before measuring
    Scene scene = o->image.load_scene(o->scene_path);
    s.bench.width = o->image.width;
    s.bench.height = o->image.height;
    s.bench.spp = o->image.spp;
    s.bench.subsample = o->image.subsample;
    s.bench.adaptive = o->image.adaptive;
    s.bench.repeat = *repeat;
    s.bench.omp = *omp;
    s.bench.embree = false;  // (bench's comparison; the sweep reports OpenMP only)
    s.bench.builds = false;
    s.progress = stderr_progress();  // on a terminal only, not with --quiet
    auto devs = select_devices(devices->empty() ? o->device.device : *devices);
    auto rows = run_sweep(scene, devs, o->settings(), s);
    if (!*as_json) print_sweep(rows);
    // With --json, standard output holds the JSON object alone.
    if (!csv->empty()) {
      write_text_atomic(*csv, sweep_csv(rows), "CSV");
      if (!*as_json) std::printf("wrote %s\n", csv->c_str());
    }
    if (!plot->empty()) {
      std::string second = plot_sweep(rows, *plot, o->scene_path);
      if (!*as_json) std::printf("wrote %s and %s\n", plot->c_str(), second.c_str());
    }
    if (*as_json) std::printf("%s\n", json_text(sweep_json(rows, o->scene_path)).c_str());
  });
}

}  // namespace clrt

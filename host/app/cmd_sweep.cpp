// cmd_sweep.cpp - `clrt sweep SCENE --depths A:B`: bench per depth and device.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "app/cli_common.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "image/image.hpp"
#include "eval/sweep.hpp"

namespace clrt {

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto depths = std::make_shared<std::string>("0:10");
  auto devices = std::make_shared<std::string>();
  auto csv = std::make_shared<std::string>();
  auto plot = std::make_shared<std::string>();
  auto repeat = std::make_shared<int>(3);
  auto omp = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("sweep", "Bench figures and error vs reference per recursion depth (and device)");
  add_render_options(cmd, *o, /*with_engine=*/false);
  cmd->add_option("--depths", *depths, "Depth range A:B, inclusive (default 0:10)");
  cmd->add_option("--devices", *devices, "Devices: index, list (0,1), 'all', or name substring (default: --device)");
  cmd->add_option("--csv", *csv, "Write the table as CSV to this file");
  cmd->add_option("--plot", *plot, "Write a PNG of time per depth here (and rays per depth to NAME-rays.EXT)");
  cmd->add_option("--repeat", *repeat, "Timed kernel launches per depth after a warm-up (default 3)");
  cmd->add_flag("--omp", *omp, "Also time the OpenMP float tracer at each depth");
  cmd->callback([o, depths, devices, csv, plot, repeat, omp] {
    o->validate();
    if (*repeat < 1 || *repeat > 1000) throw UserError("--repeat must be in [1, 1000]");
    SweepSettings s;
    parse_depth_range(*depths, s.depth_from, s.depth_to);
    if (!plot->empty()) {  // both plots, before measuring
      check_output_format(*plot);
      check_output_format(rays_plot_path(*plot));
    }
    if (!csv->empty()) check_writable(*csv, "CSV");  // fail before measuring
    Scene scene = load_scene(o->scene_path);
    s.bench.width = o->width;
    s.bench.height = o->height;
    s.bench.repeat = *repeat;
    s.bench.omp = *omp;
    s.bench.builds = false;
    s.bench.policy = o->tile_policy();
    parse_local_size(o->local_size, s.bench.local_x, s.bench.local_y);
    s.progress = isatty(STDERR_FILENO);
    auto devs = select_devices(devices->empty() ? o->device : *devices);
    auto rows = run_sweep(scene, devs, o->kernel_config(), s);
    print_sweep(rows);
    if (!csv->empty()) {
      write_text_atomic(*csv, sweep_csv(rows), "CSV");
      std::printf("wrote %s\n", csv->c_str());
    }
    if (!plot->empty()) {
      std::string second = plot_sweep(rows, *plot, o->scene_path);
      std::printf("wrote %s and %s\n", plot->c_str(), second.c_str());
    }
  });
}

}  // namespace clrt

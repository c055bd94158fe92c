// cmd_bench.cpp - `clrt bench SCENE`: timings, rays and speedups (host/bench.hpp).
#include <cstdio>
#include <memory>

#include "eval/bench.hpp"
#include "app/cli_common.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"

namespace clrt {

void add_bench_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto repeat = std::make_shared<int>(5);
  auto as_json = std::make_shared<bool>(false);
  auto no_omp = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("bench", "Benchmark the OpenCL renderer against the reference and an OpenMP tracer");
  add_render_options(cmd, *o, /*with_engine=*/false);
  cmd->add_option("--repeat", *repeat, "Timed kernel launches after one warm-up (default 5)");
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  cmd->add_flag("--no-omp", *no_omp, "Skip the OpenMP comparison");
  cmd->callback([o, repeat, as_json, no_omp] {
    o->validate();
    if (*repeat < 1 || *repeat > 1000) throw UserError("--repeat must be in [1, 1000]");
    Scene scene = load_scene(o->scene_path);
    BenchSettings s;
    s.width = o->width;
    s.height = o->height;
    s.depth = o->effective_depth(scene);
    s.repeat = *repeat;
    s.omp = !*no_omp;
    s.policy = o->tile_policy();
    parse_local_size(o->local_size, s.local_x, s.local_y);
    BenchResult r = run_bench(scene, select_devices(o->device), o->kernel_config(), s);
    if (*as_json) {
      nlohmann::json j = bench_json(r);
      j["scene"] = o->scene_path;
      j["precision"] = o->precision;
      std::printf("%s\n", json_text(j).c_str());
    } else {
      std::printf("scene          %s, precision %s\n", o->scene_path.c_str(), o->precision.c_str());
      print_bench(r);
    }
  });
}

}  // namespace clrt

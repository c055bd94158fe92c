// cmd_bench.cpp - `clrt bench SCENE`: timings, rays and speedups (eval/bench.hpp).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/bench_report.hpp"
#include "app/options.hpp"
#include "app/report_header.hpp"
#include "eval/bench.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"
#include "util/progress.hpp"

namespace clrt {

void add_bench_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto repeat = std::make_shared<int>(5);
  auto as_json = std::make_shared<bool>(false);
  auto no_omp = std::make_shared<bool>(false);
  auto no_embree = std::make_shared<bool>(false);
  auto no_reference = std::make_shared<bool>(false);
  auto float_frames = std::make_shared<bool>(false);
  auto no_map = std::make_shared<bool>(false);
  auto no_overlap = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand(
      "bench", "Benchmark the OpenCL renderer against the reference, an OpenMP tracer and an Embree tracer");
  o->add(cmd, /*with_engine=*/false);
  add_repeat_option(cmd, *repeat, "Timed rounds after one warm-up");
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  cmd->add_flag("--no-omp", *no_omp, "Skip the OpenMP comparison");
  cmd->add_flag("--no-embree", *no_embree, "Skip the Embree comparison");
  cmd->add_flag("--no-reference", *no_reference,
                "Skip the scalar double reference (it tests every sphere: hours on large scenes)");
  cmd->add_flag("--float", *float_frames,
                "Time frames of float colour (what .exr outputs get) instead of 8-bit RGBA (.png and other 8-bit "
                "outputs); the OpenMP and Embree tracers write the same format");
  add_transfer_flags(cmd, *no_map, *no_overlap);
  cmd->callback([o, repeat, as_json, no_omp, no_embree, no_reference, float_frames, no_map, no_overlap] {
    o->validate();
    Scene scene = o->image.load_scene(o->scene_path);
    BenchSettings s;
    s.width = o->image.width;
    s.height = o->image.height;
    s.depth = o->image.effective_depth(scene);
    s.spp = o->image.spp;
    s.subsample = o->image.subsample;
    s.adaptive = o->image.adaptive;
    s.repeat = *repeat;
    s.omp = !*no_omp;
    s.embree = !*no_embree;
    s.reference = !*no_reference;
    s.progress = stderr_progress();  // on a terminal only, not with --quiet
    // Frames in an output's format, without the per-pixel classification
    // that only comparisons with the reference read.
    RenderSettings settings = o->settings();
    settings.kernel.output = {*float_frames ? PixelFormat::Float : PixelFormat::Rgba8, /*classes=*/false};
    settings.map_results = !*no_map;
    settings.overlap_downloads = !*no_overlap;
    BenchResult r = run_bench(scene, o->device.devices(), settings, s);
    if (*as_json) {
      nlohmann::ordered_json j = bench_json(r);
      j["scene"] = o->scene_path;
      j["overrides"] = overrides_json(o->image.overrides);
      j["precision"] = o->kernel.precision;
      std::printf("%s\n", json_text(j).c_str());
    } else {
      std::printf("scene          %s, precision %s\n", o->scene_path.c_str(), o->kernel.precision.c_str());
      print_bench(r);
    }
  });
}

}  // namespace clrt

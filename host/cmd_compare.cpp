// cmd_compare.cpp - `clrt compare SCENE`: OpenCL against the reference.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "compare.hpp"
#include "compare_json.hpp"
#include "engine.hpp"
#include "error.hpp"

namespace clrt {

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto diff = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("compare", "Render with both engines and report the error of OpenCL vs reference");
  add_render_options(cmd, *o, /*with_engine=*/false);
  cmd->add_option("--diff", *diff, "Write a difference image (x16; magenta = hit flips, cyan = shadow flips)");
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  cmd->callback([o, diff, as_json] {
    o->validate();
    if (!diff->empty()) check_output_format(*diff);
    Scene scene = load_scene(o->scene_path);
    int depth = o->effective_depth(scene);
    EngineRun ref_run, cl_run;
    Image ref = run_engine("reference", scene, *o, depth, &ref_run);
    Image img = run_engine("opencl", scene, *o, depth, &cl_run);
    Comparison c = compare_images(img, ref);
    if (!diff->empty()) write_rgb8(diff_image(img, ref), img.width, img.height, *diff);
    if (*as_json) {
      nlohmann::json j = {{"scene", o->scene_path},
                          {"width", o->width},
                          {"height", o->height},
                          {"depth", depth},
                          {"precision", o->precision},
                          {"device", cl_run.device},
                          {"build_options", cl_run.options},
                          {"reference_ms", ref_run.wall_ms},
                          {"opencl_kernel_ms", cl_run.cl.kernel_ms},
                          {"opencl_build_ms", cl_run.cl.build_ms},
                          {"opencl_build_cached", cl_run.cl.build_cached},
                          {"opencl_total_ms", cl_run.wall_ms}};
      j.update(comparison_json(c));
      std::printf("%s\n", j.dump(2).c_str());
      return;
    }
    std::printf("scene          %s  %dx%d  depth %d  precision %s\n", o->scene_path.c_str(), o->width, o->height, depth,
                o->precision.c_str());
    std::printf("device         %s\n", cl_run.device.c_str());
    std::printf("pixels differ  %zu of %zu (%.4f%%)\n", c.differ, c.pixels, c.pixels ? 100.0 * c.differ / c.pixels : 0.0);
    std::printf("off by > 1     %zu (%.4f%%)\n", c.off_by_gt1, c.percent_off_by_gt1());
    std::printf("max abs error  %d levels (8-bit), %.4f (float)\n", c.max_abs_8bit, c.max_abs_float);
    std::printf("RMSE / PSNR    8-bit %.4f / %s dB, float %.4f / %s dB\n", c.rmse_8bit, format_psnr(c.psnr_8bit).c_str(),
                c.rmse_float, format_psnr(c.psnr_float).c_str());
    std::printf("flips          hit %zu, shadow %zu, NaN/Inf pixels %zu\n", c.hit_flips, c.shadow_flips, c.nan_inf);
    std::printf("time           reference %.1f ms; opencl kernel %.2f ms, build %.1f ms%s, render total %.1f ms\n",
                ref_run.wall_ms, cl_run.cl.kernel_ms, cl_run.cl.build_ms, cl_run.cl.build_cached ? " (cached)" : "",
                cl_run.wall_ms);
  });
}

}  // namespace clrt

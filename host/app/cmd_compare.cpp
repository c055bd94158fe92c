// cmd_compare.cpp - `clrt compare SCENE`: OpenCL (or an image file) against
// the reference, with optional pass/fail thresholds (exit 1 on a fail).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/compare_report.hpp"
#include "app/engine.hpp"
#include "app/image_metadata.hpp"
#include "app/options.hpp"
#include "app/report_header.hpp"
#include "cl/launch_timing.hpp"
#include "eval/compare.hpp"
#include "image/image_file.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"

#include "util/output_file.hpp"

namespace clrt {

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto diff = std::make_shared<std::string>();
  auto image = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  auto limits = std::make_shared<Thresholds>();
  auto* cmd = app.add_subcommand("compare", "Render with both engines and report the error of OpenCL vs reference");
  o->add(cmd, /*with_engine=*/false);
  o->image.add_ray_cut_flag(cmd);
  cmd->add_option("--diff", *diff, "Write a difference image (x16; magenta = hit flips, cyan = shadow flips)");
  cmd->add_option("--image", *image,
                  "Compare this image file (e.g. written by clrt render) instead of rendering with OpenCL; its size "
                  "sets --width/--height");
  cmd->add_option("--fail-percent", limits->fail_percent,
                  "Exit 1 if more than P percent of pixels are off by more than one 8-bit level")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--fail-max", limits->fail_max, "Exit 1 if any 8-bit channel differs by more than L levels")
      ->check(CLI::Range(0, 255));
  add_aov_option(cmd, o->aov);
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  cmd->callback([o, diff, image, as_json, limits] {
    Image img;
    FrameLayers img_layers;
    if (!image->empty()) {
      img = read_image(*image, kMaxImageEdge, kMaxImagePixels);
      o->image.width = img.width;
      o->image.height = img.height;
      if (o->layers()) img_layers = read_layers(*image, img.width, img.height);
    }
    o->validate();
    if (!diff->empty()) {
      check_output_format(*diff);
      std::vector<NamedOutput> all{{*diff, "difference image"}};
      if (!image->empty()) all.push_back({*image, "image compared"});
      if (*as_json) all.push_back({"-", "JSON"});
      check_distinct_outputs(all);
      claim_stdout_if_dash(*diff);
    }
    Scene scene = o->image.load_scene(o->scene_path);
    const int depth = o->image.effective_depth(scene);
    const CompareRun run =
        run_compare(scene, *o, depth, *limits, image->empty() ? nullptr : &img, *image, {}, &img_layers);
    const bool classified = run.classified();
    const Comparison& c = run.comparison;
    const EngineRun &ref_run = run.reference, &cl_run = run.opencl;
    const Verdict& verdict = run.verdict;
    if (!diff->empty())
      write_rgb8(
          diff_image(run.test, run.ref), run.test.width, run.test.height, *diff,
          image_metadata("clrt compare --diff (|image - reference| x 16, hit flips magenta, shadow flips cyan)", *o,
                         depth, classified ? "opencl" : "image " + *image, classified ? cl_run.device : "-"));
    if (*as_json) {
      std::printf("%s\n", json_text(compare_json(run, *o)).c_str());
    } else {
      std::fprintf(report_stream(), 
          "scene          %s  %dx%d  depth %d  spp %d%s  precision %s\n", o->scene_path.c_str(), o->image.width,
          o->image.height, depth, o->image.spp,
          o->image.subsample == Subsample::Off ? "" : ("  subsample " + subsample_name(o->image.subsample)).c_str(),
          classified ? o->kernel.precision.c_str() : "-");
      if (classified)
        std::fprintf(report_stream(), "device         %s\n", cl_run.device.c_str());
      else
        std::fprintf(report_stream(), "image          %s\n", image->c_str());
      std::fprintf(report_stream(), "pixels differ  %zu of %zu (%.4f%%)\n", c.differ, c.pixels,
                  c.pixels ? 100.0 * c.differ / c.pixels : 0.0);
      std::fprintf(report_stream(), "off by > 1     %zu (%.4f%%)\n", c.off_by_gt1, c.percent_off_by_gt1());
      std::fprintf(report_stream(), "max abs error  %d levels (8-bit), %.4f (float)\n", c.max_abs_8bit, c.max_abs_float);
      if (c.max_abs_8bit > 0)
        std::fprintf(report_stream(), "worst pixel    (%d, %d): %d %d %d, reference %d %d %d\n", c.worst_x, c.worst_y, c.worst_test[0],
                    c.worst_test[1], c.worst_test[2], c.worst_reference[0], c.worst_reference[1], c.worst_reference[2]);
      std::fprintf(report_stream(), "RMSE / PSNR    8-bit %.4f / %s dB, float %.4f / %s dB\n", c.rmse_8bit,
                  format_psnr(c.psnr_8bit).c_str(), c.rmse_float, format_psnr(c.psnr_float).c_str());
      if (classified)
        std::fprintf(report_stream(), "flips          hit %zu, shadow %zu\n", c.hit_flips, c.shadow_flips);
      else
        std::fprintf(report_stream(), "flips          n/a (an image file has no hit/shadow data)\n");
      std::fprintf(report_stream(), "NaN/Inf pixels %zu (reference: %zu)\n", c.nan_inf, c.nan_inf_reference);
      if (run.layers) print_layer_comparison(run.layer_comparison, report_stream());
      if (classified)
        std::fprintf(report_stream(), 
            "time           reference %.1f ms; opencl kernel %.2f ms%s, build %.1f ms%s, render total %.1f ms\n",
            ref_run.wall_ms, cl_run.frame.kernel_ms,
            time_source_note(cl_run.frame.host_timed_launches, cl_run.frame.launches).c_str(), cl_run.frame.build_ms,
            cl_run.frame.build_cached ? " (cached)" : "", cl_run.wall_ms);
      if (limits->any())
        std::fprintf(report_stream(), "verdict        %s\n", verdict.pass ? "PASS" : ("FAIL: " + verdict.reason).c_str());
    }
    if (!verdict.pass) throw CheckFailure("compare: " + verdict.reason);
  });
}

}  // namespace clrt

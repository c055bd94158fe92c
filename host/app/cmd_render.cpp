// cmd_render.cpp - `clrt render SCENE -o OUT`.
#include <cstdio>
#include <memory>
#include <string>

#include "app/engine.hpp"
#include "app/frame_report.hpp"
#include "app/image_metadata.hpp"
#include "app/options.hpp"
#include "cl/launch_timing.hpp"
#include "image/image_file.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

namespace clrt {

void add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto out = std::make_shared<std::string>();
  auto format = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("render", "Render a scene to an image (png, ppm, exr, ...)");
  o->add(cmd, /*with_engine=*/true);
  cmd->add_option("-o,--output", *out,
                  "Output image; the extension picks the format ('-' = PNG on standard output, as are devices and "
                  "FIFOs named without an extension)")
      ->required();
  cmd->add_option("--format", *format,
                  "Image format, as an extension (png, ppm, exr, pfm, ...), instead of OUT's: for '-o -' and "
                  "devices (unset: OUT's extension; PNG for '-' and names without one)");
  cmd->callback([o, out, format] {
    o->validate();
    const OutputTarget target = check_output_format(*out, *format);  // fail before rendering
    Scene scene = o->image.load_scene(o->scene_path);
    int depth = o->image.effective_depth(scene);
    EngineRun run;
    // The kernel writes what the file needs: 8-bit RGBA for 8-bit formats,
    // float colour for float ones, never the per-pixel classification.
    const FrameContents contents{output_pixel_format(*out, *format), /*classes=*/false};
    Image img = run_engine(o->engine, scene, *o, depth, &run, contents);
    write_image(img, *out, image_metadata("clrt render", *o, depth, o->engine, run.device), *format);
    // The report goes to stderr when the image itself goes to stdout.
    std::FILE* report = target.kind == OutputKind::File ? stdout : stderr;
    if (report == stderr && quiet()) return;  // --quiet: only the image
    if (o->engine == "opencl")
      std::fprintf(report, "%s: %dx%d depth %d on %s: kernel %.2f ms%s, build %.1f ms%s\n", out->c_str(),
                   o->image.width, o->image.height, depth, run.device.c_str(), run.frame.kernel_ms,
                   time_source_note(run.frame.host_timed_launches, run.frame.launches).c_str(), run.frame.build_ms,
                   run.frame.build_cached ? " (cached)" : "");
    if (o->engine == "opencl" && run.frame.bvh)
      std::fprintf(report, "%s: hierarchy built in %.1f ms, %.2f MiB, %d levels\n", out->c_str(),
                   run.frame.bvh_build_ms, double(run.frame.bvh_bytes) / (1 << 20), run.frame.bvh_depth + 1);
    if (run.frame.shares.size() > 1) print_shares(run.frame.shares, report);
    if (o->engine != "opencl")
      std::fprintf(report, "%s: %dx%d depth %d with the reference renderer: %.1f ms\n", out->c_str(), o->image.width,
                   o->image.height, depth, run.wall_ms);
  });
}

}  // namespace clrt

// cli_common.cpp - shared option handling for the CLI subcommands.
#include "app/cli_common.hpp"

#include "clrt_layout.h"
#include "util/error.hpp"
#include "render/precision.hpp"

namespace clrt {

void add_render_options(CLI::App* cmd, RenderOptions& o, bool with_engine) {
  cmd->add_option("scene", o.scene_path, "Scene file (JSON)")->required();
  cmd->add_option("--width", o.width, "Image width in pixels (default 600)");
  cmd->add_option("--height", o.height, "Image height in pixels (default 600)");
  cmd->add_option("--depth", o.depth, "Recursion depth (default: the scene's recursion_depth)")
      ->check(CLI::Range(0, CLRT_MAX_DEPTH));
  if (with_engine) cmd->add_option("--engine", o.engine, "opencl (default) or reference");
  cmd->add_option("--device", o.device, "Device index, list (0,1), 'all', or name/type substring (cpu, gpu, pthread)");
  cmd->add_option("--precision", o.precision, "naive | stable | robust (default) | fast | fp64");
  cmd->add_flag("--no-specialize", o.no_specialize, "Build the generic kernel instead of a scene-specialized one");
  cmd->add_flag("--no-ftz", o.no_ftz, "Do not build with -cl-denorms-are-zero");
  cmd->add_option("--lanes", o.lanes, "Pixels per work-item (SIMD lanes): 1, 4, 8, 16 (default: 8 specialized, 1 generic/fp64)");
  cmd->add_flag("--no-cache", o.no_cache, "Do not use the program binary cache (build from source, store nothing)");
  cmd->add_flag("--verbose", o.verbose, "Log build options and program cache use on stderr");
  cmd->add_option("--kernel-dir", o.kernel_dir, "Read kernels from this directory instead of the embedded copies");
  cmd->add_option("--local", o.local_size, "Local work size WxH in work-items (default: the kernel's preferred multiple x 1)");
  cmd->add_option("--cl-options", o.cl_options, "Extra OpenCL build options appended to the generated ones (development)");
  cmd->add_option("--max-launch-ms", o.max_launch_ms,
                  "Split the frame so no kernel launch exceeds this many ms (default: 500 on GPUs, none on CPUs; 0 = none)");
  cmd->add_option("--band-rows", o.band_rows, "Fixed tile height in rows (tiles are full-width bands; default: adaptive)");
}

void parse_local_size(const std::string& s, int& lx, int& ly) {
  lx = ly = 0;
  if (s.empty()) return;
  auto x = s.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    size_t used1 = 0, used2 = 0;
    lx = std::stoi(s.substr(0, x), &used1);
    ly = std::stoi(s.substr(x + 1), &used2);
    if (used1 != x || used2 != s.size() - x - 1 || lx <= 0 || ly <= 0) throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    throw UserError("--local: expected WxH with positive integers (got \"" + s + "\")");
  }
}

void RenderOptions::validate() const {
  if (width <= 0 || height <= 0) throw UserError("--width/--height must be > 0 (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
  if (width > kMaxImageEdge || height > kMaxImageEdge || (long long)width * height > kMaxImagePixels)
    throw UserError("image " + std::to_string(width) + "x" + std::to_string(height) + " is too large (at most " +
                    std::to_string(kMaxImageEdge) + " per edge and " + std::to_string(kMaxImagePixels) + " pixels)");
  if (depth != kSceneDepth && (depth < 0 || depth > CLRT_MAX_DEPTH))
    throw UserError("--depth must be in [0, " + std::to_string(CLRT_MAX_DEPTH) + "] (got " + std::to_string(depth) + ")");
  if (engine != "opencl" && engine != "reference") throw UserError("unknown engine \"" + engine + "\" (expected opencl or reference)");
  if (band_rows < 0) throw UserError("--band-rows must be >= 0 (got " + std::to_string(band_rows) + ")");
  if (!(max_launch_ms >= 0) && max_launch_ms != -1) throw UserError("--max-launch-ms must be >= 0");
  int lx, ly;
  parse_local_size(local_size, lx, ly);
  (void)parse_precision(precision);
  (void)kernel_lanes(kernel_config());
}

KernelConfig RenderOptions::kernel_config() const {
  KernelConfig c;
  c.precision = parse_precision(precision);
  c.specialize = !no_specialize;
  c.denorms_zero = !no_ftz;
  c.use_cache = !no_cache;
  c.lanes = lanes;
  c.verbose = verbose;
  c.kernel_dir = kernel_dir;
  c.extra_options = cl_options;
  return c;
}

}  // namespace clrt

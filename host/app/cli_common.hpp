// cli_common.hpp - options shared by the render-like subcommands.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "render/build_options.hpp"
#include "render/tile_scheduler.hpp"
#include "scene/scene.hpp"

namespace clrt {

constexpr int kMaxImageEdge = 16384;
constexpr long long kMaxImagePixels = 64LL * 1024 * 1024;

struct RenderOptions {
  std::string scene_path;
  int width = 600, height = 600;
  // --depth accepts only [0, CLRT_MAX_DEPTH]; without it the scene's
  // recursion_depth is used (kSceneDepth is never a user value).
  static constexpr int kSceneDepth = -1;
  int depth = kSceneDepth;
  std::string engine = "opencl";
  std::string device;  // "" = default device
  std::string precision = "robust";
  bool no_specialize = false;
  bool no_ftz = false;
  int lanes = 0;          // pixels per work-item, 0 = default
  bool no_cache = false;  // bypass the program binary cache
  bool verbose = false;   // log build options / cache use on stderr
  std::string kernel_dir;
  std::string local_size;  // "WxH" or ""
  int band_rows = 0;            // fixed band height, 0 = adaptive
  double max_launch_ms = -1;    // -1 = device default (500 ms GPU, none CPU)
  std::string cl_options;  // extra build options (development)

  // Validates and returns the kernel configuration (UserError otherwise).
  KernelConfig kernel_config() const;
  TilePolicy tile_policy() const { return TilePolicy{max_launch_ms, band_rows}; }
  int effective_depth(const Scene& s) const { return depth == kSceneDepth ? s.recursion_depth : depth; }
  void validate() const;
};

// Adds SCENE plus --width/--height/--depth/--engine/--device/--precision/...
void add_render_options(CLI::App* cmd, RenderOptions& o, bool with_engine = true);

// Parses "8x8" into (8, 8); UserError on anything else.
void parse_local_size(const std::string& s, int& lx, int& ly);

// Registration of each subcommand (one file each: cmd_<name>.cpp).
void add_devices_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_accuracy_command(CLI::App& app);
void add_stability_command(CLI::App& app);

}  // namespace clrt

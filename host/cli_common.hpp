// cli_common.hpp - options shared by the render-like subcommands.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "build_options.hpp"
#include "scene.hpp"

namespace clrt {

constexpr int kMaxImageEdge = 16384;
constexpr long long kMaxImagePixels = 64LL * 1024 * 1024;

struct RenderOptions {
  std::string scene_path;
  int width = 600, height = 600;
  int depth = -1;  // -1 = the scene's recursion_depth
  std::string engine = "opencl";
  std::string device;  // "" = default device
  std::string precision = "robust";
  bool no_specialize = false;
  bool no_ftz = false;
  std::string kernel_dir;
  std::string local_size;  // "WxH" or ""
  int max_tile = 0;
  std::string cl_options;  // extra build options (development)

  // Validates and returns the kernel configuration (UserError otherwise).
  KernelConfig kernel_config() const;
  int effective_depth(const Scene& s) const { return depth >= 0 ? depth : s.recursion_depth; }
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

}  // namespace clrt

// options.hpp - the command line's option groups, composed per subcommand (in
// the style of the Khronos OpenCL-SDK's Options.hpp): each group adds its
// options to a CLI11 command, checks them, and turns them into the core's
// settings (KernelConfig, RenderSettings). Only app/ sees CLI11.
#pragma once
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "eval/accuracy.hpp"
#include "eval/sweep.hpp"
#include "image/layers.hpp"
#include "render/renderer.hpp"
#include "scene/ray_tree.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"

// CLI11's App by name only: the files that add options include CLI11
// (some 10 s of compile time a file at -O3), the reports that include this
// header for the option structs do not.
namespace CLI {
class App;
}  // namespace CLI

namespace clrt {

constexpr int kMaxImageEdge = 16384;

// The help group of the low-level knobs (launch geometry, lanes, build
// options), listed after a command's other options.
constexpr const char* kDeveloperGroup = "Developer options";
constexpr long long kMaxImagePixels = 64LL * 1024 * 1024;

// --width, --height and (optionally) --depth and --spp.
struct ImageOptions {
  int width = 600, height = 600;
  // --depth accepts only [0, CLRT_MAX_DEPTH]; without it the scene's
  // recursion_depth is used (kSceneDepth is never a user value).
  static constexpr int kSceneDepth = -1;
  int depth = kSceneDepth;
  // --spp N: N x N samples per pixel, averaged (supersampling), in
  // [1, CLRT_MAX_SPP]; 1 = one ray per pixel, the book's image.
  int spp = 1;
  // --adaptive T: the book's adaptive supersampling (scene/sampling.hpp);
  // negative = off.
  double adaptive = -1;
  // --subsample MODE: the book's subsampling (scene/sampling.hpp), spp 1 only.
  Subsample subsample = Subsample::Off;
  // --aspect viewport|image: overrides the scene camera's "aspect"
  // (scene/viewport.hpp); "" = the scene's.
  std::string aspect;
  // -D PATH=VALUE, in the order given: scene values set as if each scene
  // file said so (scene/scene_json.hpp, SceneOverride).
  std::vector<std::string> overrides;

  // with_subsample: --subsample (commands that compare variants list it as one instead). with_spp: also
  // --adaptive, --aspect and -D (the commands that render scene files).
  void add(CLI::App* cmd, bool with_depth = true, bool with_spp = true, bool with_subsample = true);
  // --ray-budget (the commands that load scene files: load_scene() checks it).
  void add_ray_budget(CLI::App* cmd);
  // --no-ray-cut (render and compare: the commands whose images it changes).
  void add_ray_cut_flag(CLI::App* cmd);
  // --no-ray-cut: trace every ray down to the depth (scene/ray_tree.hpp).
  bool no_ray_cut = false;
  // --ray-budget N: refuse a frame whose ray tree may pass N rays.
  double ray_budget = kRayBudget;

  Sampling sampling() const {
    Sampling s(spp, adaptive, subsample);
    s.ray_cut = !no_ray_cut;
    return s;
  }
  void validate() const;
  int effective_depth(const Scene& s) const { return depth == kSceneDepth ? s.recursion_depth : depth; }
  // Loads a scene for an image of this size: its camera as --aspect and the
  // scene say (camera_for_image()), with a warning when its pixels are not
  // square and one when its ray tree may take hours (scene/ray_tree.hpp);
  // warn = false: without them (a scene loaded again for its frame). A
  // frame over the ray budget is a UserError (with warn only: it was
  // checked at the first load).
  Scene load_scene(const std::string& path, bool warn = true) const;
  // The same for a scene already parsed, named `name` in the warnings (the
  // Python module's scenes).
  Scene fit_scene(Scene scene, const std::string& name, bool warn = true) const;
};

// --device: one device, or (several = true) a list / 'all'.
struct DeviceOptions {
  std::string device;  // "" = the default device

  void add(CLI::App* cmd, bool several);
  std::vector<DeviceInfo> devices() const { return select_devices(device); }
  DeviceInfo one() const { return select_device(device); }
};

// How the kernel is built: --precision and --lanes (with_variant),
// --no-specialize (with_specialize), and --accel, --no-ftz, --no-cache,
// --verbose, --kernel-dir, --cl-options.
struct KernelOptions {
  std::string precision = "robust";
  bool no_specialize = false;
  bool no_ftz = false;
  int lanes = 0;          // pixels per work-item, 0 = default
  bool no_cache = false;  // bypass the program binary cache
  bool verbose = false;   // log build options / cache use on stderr
  std::string kernel_dir;
  std::string cl_options;  // extra build options (development)
  std::string accel = "auto";

  void add(CLI::App* cmd, bool with_variant, bool with_specialize = true);
  // Validates and returns the kernel configuration (UserError otherwise).
  KernelConfig config() const;
};

// How a frame is launched: --local, --band-rows, --max-launch-ms.
struct LaunchOptions {
  std::string local_size;     // "WxH" or ""
  int band_rows = 0;          // fixed band height, 0 = adaptive
  double max_launch_ms = -1;  // -1 = device default (500 ms GPU, none CPU)

  void add(CLI::App* cmd);
  void validate() const;
  TilePolicy tiles() const { return TilePolicy{max_launch_ms, band_rows}; }
  LocalSize local() const;
};

// --mpi-timeout SECONDS (render, sweep, accuracy: the commands that run
// across MPI ranks): how long rank 0 waits for a rank that owes it a message
// (dist::silence_bound_s()).
void add_mpi_timeout_option(CLI::App* cmd);
// -D,--set PATH=VALUE, any number of times, into `overrides` (checked by
// parse_overrides when the command runs).
void add_override_option(CLI::App* cmd, std::vector<std::string>& overrides);

// --aov LIST (render, compare): the AOV layers (image/layers.hpp) into
// `aov`, checked by parse_layers() as CLI11 reads it.
void add_aov_option(CLI::App* cmd, std::string& aov);

// --no-map and --no-overlap (bench; developer options): how a frame's
// results travel to the host (DeviceRenderer: mapped or read, and read
// while the next band runs or one band at a time).
void add_transfer_flags(CLI::App* cmd, bool& no_map, bool& no_overlap);

// --repeat N: timed runs, in [1, kMaxRepeat].
constexpr int kMaxRepeat = 1000;
void add_repeat_option(CLI::App* cmd, int& repeat, const std::string& help);

// The rule for every number on the command line, added to each option of
// `cmd` and of its subcommands by the type CLI11 parses it as: a floating
// option (FLOAT) takes finite numbers only (CLI11 reads "nan" and "inf" as
// numbers, and NaN passes every range check), an unsigned one (UINT) no
// negative number (CLI11 reads "-1" as 2^64 - 1). Called once, after every
// command is added.
void add_number_checks(CLI::App* cmd);

// Everything a render-like subcommand (render, compare, bench, sweep) takes.
struct RenderOptions {
  std::string scene_path;
  // With several_scenes (render): every SCENE given, in order (scene_path is
  // then the frame's, set by the command).
  std::vector<std::string> scene_paths;
  std::string engine = "opencl";
  ImageOptions image;
  DeviceOptions device;
  KernelOptions kernel;
  LaunchOptions launch;
  // --aov LIST (render, compare; add_aov_option): "" = no layers.
  std::string aov;
  unsigned layers() const { return aov.empty() ? 0 : parse_layers(aov); }

  // Adds SCENE (SCENE... into scene_paths with several_scenes) and every
  // group (--engine only with_engine).
  void add(CLI::App* cmd, bool with_engine, bool several_scenes = false);
  void validate() const;
  RenderSettings settings() const { return RenderSettings{kernel.config(), launch.tiles(), launch.local()}; }
};

// `clrt accuracy`'s options: SCENE... and every group, --repeat, --variants
// and its outputs.
struct AccuracyOptions {
  std::vector<std::string> scenes;
  ImageOptions image;
  DeviceOptions device;
  KernelOptions kernel;
  int repeat = 7;
  std::string variants = default_variant_list();
  std::string csv, plot;
  bool json = false, markdown = false;

  // Checks the options and the output files (before anything is measured).
  void check() const;
  // The settings (UserError on a bad precision or variant).
  AccuracySettings settings() const;
  // Every variant of default_accuracy_variants(), comma-separated.
  static std::string default_variant_list();
};

// `clrt sweep`'s settings from its options (the depths are the caller's:
// parse_depth_range; progress none).
SweepSettings sweep_settings(const RenderOptions& o, int repeat, bool omp);

// --depths: "A:B" (inclusive, 0 <= A <= B <= CLRT_MAX_DEPTH) or a single "N";
// UserError on anything else.
void parse_depth_range(const std::string& s, int& from, int& to);

// Parses "8x8" into {8, 8}; UserError on anything else ("" = default {0, 0}).
LocalSize parse_local_size(const std::string& s);

// Registration of each subcommand (one file each: cmd_<name>.cpp).
void add_devices_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_accuracy_command(CLI::App& app);
void add_stability_command(CLI::App& app);
void add_generate_command(CLI::App& app);
void add_scaling_command(CLI::App& app);
void add_cache_command(CLI::App& app);
void add_validate_command(CLI::App& app);

}  // namespace clrt

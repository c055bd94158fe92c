// options.cpp - the option groups: their flags, checks and conversions.
#include "app/options.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "clrt_layout.h"
#include "dist/communicator.hpp"
#include "image/plot.hpp"
#include "render/precision.hpp"
#include "scene/ray_tree.hpp"
#include "scene/scene_json.hpp"
#include "scene/viewport.hpp"
#include "util/error.hpp"
#include "util/log.hpp"
#include "util/output_file.hpp"

namespace clrt {

void ImageOptions::add(CLI::App* cmd, bool with_depth, bool with_spp, bool with_subsample) {
  cmd->add_option("--width", width, "Image width in pixels")->capture_default_str();
  cmd->add_option("--height", height, "Image height in pixels")->capture_default_str();
  if (with_depth)
    cmd->add_option("--depth", depth, "Recursion depth (unset: the scene's recursion_depth)")
        ->check(CLI::Range(0, CLRT_MAX_DEPTH))
        ->default_str("");  // kSceneDepth is no value to show
  if (with_spp)
    cmd->add_option("--spp", spp, "Supersampling: N x N stratified rays per pixel, averaged")
        ->check(CLI::Range(1, CLRT_MAX_SPP))
        ->capture_default_str();
  if (with_spp)
    cmd->add_option("--adaptive", adaptive,
                    "Adaptive supersampling with --spp N >= 3: trace the N x N grid's 4 corner rays first, and the "
                    "rest only where they hit different primitives or differ by more than this many 8-bit levels")
        ->check(CLI::Range(0.0, 1e6))
        ->default_str("");  // unset: off
  if (with_spp)             // (the commands that render scene files)
    cmd->add_option("--aspect", aspect,
                    "viewport: the scene's viewport as given, stretched to the image (the book; the default unless the "
                    "scene's camera says \"aspect\": \"image\"); image: keep the viewport's larger side and fit the "
                    "other to the image, so that pixels are square")
        ->check(CLI::IsMember({"viewport", "image"}))
        ->default_str("");  // unset: the scene's
  if (with_spp) add_override_option(cmd, overrides);
  if (with_spp && with_subsample)
    cmd->add_option("--subsample", subsample,
                    "The book's subsampling (one ray per pixel): trace the even columns; an odd column's pixel whose "
                    "two neighbours hit the same primitive (or both missed) skips the search and is shaded on that "
                    "hit (shade), or takes their mean colour without a ray (interpolate)")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, Subsample>{{"shade", Subsample::Shade}, {"interpolate", Subsample::Interpolate}}))
        ->default_str("");  // unset: off
}

void ImageOptions::add_ray_budget(CLI::App* cmd) {
  cmd->add_option("--ray-budget", ray_budget,
                  "Refuse, before any work, a frame whose ray tree may pass this many rays (its worst case, with the "
                  "weight cut-off; docs/reference/limits.md)")
      ->check(CLI::Range(1.0, 1e300))
      ->capture_default_str()
      ->group(kDeveloperGroup);
}

void ImageOptions::add_ray_cut_flag(CLI::App* cmd) {
  cmd->add_flag("--no-ray-cut", no_ray_cut,
                "Trace every reflected and refracted ray down to the depth: no weight cut-off (by default a ray too "
                "light to move a pixel's 8-bit value by more than one level is not traced; docs/reference/limits.md)")
      ->group(kDeveloperGroup);
}

void ImageOptions::validate() const {
  if (width <= 0 || height <= 0)
    throw UserError("--width/--height must be > 0 (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
  if (width > kMaxImageEdge || height > kMaxImageEdge || (long long)width * height > kMaxImagePixels)
    throw UserError("image " + std::to_string(width) + "x" + std::to_string(height) + " is too large (at most " +
                    std::to_string(kMaxImageEdge) + " per edge and " + std::to_string(kMaxImagePixels) + " pixels)");
  if (depth != kSceneDepth && (depth < 0 || depth > CLRT_MAX_DEPTH))
    throw UserError("--depth must be in [0, " + std::to_string(CLRT_MAX_DEPTH) + "] (got " + std::to_string(depth) +
                    ")");
  if (spp < 1 || spp > CLRT_MAX_SPP)
    throw UserError("--spp must be in [1, " + std::to_string(CLRT_MAX_SPP) + "] (got " + std::to_string(spp) + ")");
  if (adaptive >= 0 && spp < 3)
    throw UserError(
        "--adaptive needs --spp 3 or more (the 4 corners of an N x N grid are all of it at N = 2; got --spp " +
        std::to_string(spp) + ")");
  if (subsample != Subsample::Off && spp != 1)
    throw UserError("--subsample needs one sample per pixel (got --spp " + std::to_string(spp) + ")");
  (void)parse_overrides(overrides);  // fail before any work
}

Scene ImageOptions::load_scene(const std::string& path, bool warn) const {
  return fit_scene(clrt::load_scene(path, {}, parse_overrides(overrides)), path, warn);
}

Scene ImageOptions::fit_scene(Scene scene, const std::string& path, bool warn) const {
  if (!aspect.empty()) scene.camera.aspect_from_image = aspect == "image";
  scene.camera = camera_for_image(scene.camera, width, height);
  if (!warn) return scene;
  // Work that would not end is refused, work that may not end today is
  // announced (below), before it starts.
  const std::string refused =
      ray_budget_error(scene, effective_depth(scene), width, height, spp, ray_budget, !no_ray_cut);
  if (!refused.empty()) throw UserError(path + ": " + refused);
  if (!square_pixels(scene.camera, width, height)) {
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", pixel_aspect(scene.camera, width, height));
    log_message(LogLevel::Warning, "pixels are not square (" + std::string(ratio) +
                                       ":1): the viewport's shape is not " + std::to_string(width) + "x" +
                                       std::to_string(height) + "'s; --aspect image fits it to the image");
  }
  const std::string work = ray_tree_warning(scene, effective_depth(scene), width, height, spp, !no_ray_cut);
  if (!work.empty()) log_message(LogLevel::Warning, path + ": " + work);
  return scene;
}

void DeviceOptions::add(CLI::App* cmd, bool several) {
  cmd->add_option("--device", device,
                  several ? "Device index, P:D (platform:device), list (0,1), 'all', or name/type substring (cpu, gpu, "
                            "pthread); unset: the first GPU, else the first device (clrt devices)"
                          : "Device index, P:D (platform:device) or name/type substring; unset: the first GPU, else "
                            "the first device (clrt devices)");
}

void KernelOptions::add(CLI::App* cmd, bool with_variant, bool with_specialize) {
  if (with_variant) {
    cmd->add_option("--precision", precision, "naive | stable | robust | fast | fp64")->capture_default_str();
    cmd->add_option(
           "--lanes", lanes,
           "Pixels per work-item (SIMD lanes): 1, 4, 8, 16; unset: 16 on CPUs with 16-wide floats, else 8, "
           "for specialized float builds on CPUs (where a hierarchy is walked: that, 8 or 1, whichever a short "
           "timed probe on the scene finds fastest); 1 on GPUs, on llvmpipe (rusticl), for generic and fp64 builds")
        ->group(kDeveloperGroup);
  }
  if (with_specialize)
    cmd->add_flag("--no-specialize", no_specialize, "Build the generic kernel instead of a scene-specialized one")
        ->group(kDeveloperGroup);
  cmd->add_option("--accel", accel,
                  "auto (a bounding volume hierarchy from " + std::to_string(kBvhMinSpheres) +
                      " spheres on), bvh, or none (test every sphere)")
      ->capture_default_str();
  cmd->add_flag("--no-ftz", no_ftz, "Do not build with -cl-denorms-are-zero")->group(kDeveloperGroup);
  cmd->add_flag("--no-cache", no_cache, "Do not use the program binary cache (build from source, store nothing)");
  cmd->add_flag("--verbose", verbose, "Log build options and program cache use on stderr");
  cmd->add_option("--kernel-dir", kernel_dir, "Read kernels from this directory instead of the embedded copies")
      ->group(kDeveloperGroup);
  cmd->add_option("--cl-options", cl_options, "Extra OpenCL build options appended to the generated ones")
      ->group(kDeveloperGroup);
}

KernelConfig KernelOptions::config() const {
  KernelConfig c;
  c.precision = parse_precision(precision);
  c.specialize = !no_specialize;
  c.denorms_zero = !no_ftz;
  c.use_cache = !no_cache;
  c.lanes = lanes;
  c.verbose = verbose;
  c.kernel_dir = kernel_dir;
  c.extra_options = cl_options;
  c.accel = parse_accel(accel);
  (void)kernel_lanes(c);  // UserError on a lane count no kernel has
  return c;
}

void LaunchOptions::add(CLI::App* cmd) {
  cmd->add_option("--local", local_size,
                  "Local work size WxH in work-items; unset: the kernel's preferred multiple x 1 (1x1 for blocks of "
                  "lanes on CPUs)")
      ->group(kDeveloperGroup);
  cmd->add_option("--max-launch-ms", max_launch_ms,
                  "Split the frame so no kernel launch exceeds this many ms (0 = no limit); unset: 500 on GPUs, no "
                  "limit on CPUs")
      ->default_str("")  // -1 is no value to show
      ->group(kDeveloperGroup);
  cmd->add_option("--band-rows", band_rows, "Fixed tile height in rows (tiles are full-width bands; 0 = adaptive)")
      ->capture_default_str()
      ->group(kDeveloperGroup);
}

void LaunchOptions::validate() const {
  if (band_rows < 0) throw UserError("--band-rows must be >= 0 (got " + std::to_string(band_rows) + ")");
  if (!(max_launch_ms >= 0) && max_launch_ms != -1) throw UserError("--max-launch-ms must be >= 0");
  (void)local();
}

LocalSize LaunchOptions::local() const {
  return parse_local_size(local_size);
}

LocalSize parse_local_size(const std::string& s) {
  LocalSize size;
  if (s.empty()) return size;
  const auto x = s.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    size_t used1 = 0, used2 = 0;
    size.x = std::stoi(s.substr(0, x), &used1);
    size.y = std::stoi(s.substr(x + 1), &used2);
    if (used1 != x || used2 != s.size() - x - 1 || size.x <= 0 || size.y <= 0) throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    throw UserError("--local: expected WxH with positive integers (got \"" + s + "\")");
  }
  return size;
}

void parse_depth_range(const std::string& s, int& from, int& to) {
  try {
    size_t colon = s.find(':'), used = 0;
    if (colon == std::string::npos) {
      from = to = std::stoi(s, &used);
      if (used != s.size()) throw std::invalid_argument("trailing");
    } else {
      size_t used2 = 0;
      from = std::stoi(s.substr(0, colon), &used);
      to = std::stoi(s.substr(colon + 1), &used2);
      if (used != colon || used2 != s.size() - colon - 1) throw std::invalid_argument("trailing");
    }
  } catch (const std::exception&) {
    throw UserError("--depths: expected A:B or N with integers (got \"" + s + "\")");
  }
  if (from < 0 || to < from || to > CLRT_MAX_DEPTH)
    throw UserError("--depths: need 0 <= A <= B <= " + std::to_string(CLRT_MAX_DEPTH) + " (got \"" + s + "\")");
}

void add_mpi_timeout_option(CLI::App* cmd) {
  cmd->add_option_function<double>(
         "--mpi-timeout", [](double seconds) { dist::set_silence_bound_s(seconds); },
         "Under mpirun: end the job, naming the rank and its host, when a rank that owes rank 0 a message has sent "
         "none for this many seconds (a rank at work sends a heartbeat every quarter of it, at most every 5 s; "
         "docs/guide/mpi.md)")
      ->check(CLI::Range(0.1, 1e6))
      ->default_str(std::to_string(int(dist::kDefaultSilenceBoundS)))
      ->group(kDeveloperGroup);
}

void add_override_option(CLI::App* cmd, std::vector<std::string>& overrides) {
  cmd->add_option("-D,--set", overrides,
                  "Set a value of the scene as if the scene file said so (repeatable): PATH of keys and array "
                  "indices, VALUE JSON (-D recursion_depth=5 -D spheres.2.reflective=0.8 -D "
                  "'camera.position=[0,1,-2]' -D 'camera.aspect=\"image\"')")
      ->type_name("PATH=VALUE")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
}

void add_aov_option(CLI::App* cmd, std::string& aov) {
  cmd->add_option("--aov", aov,
                  "AOV layers to write beside the colour, comma-separated: depth (Z), normal (N.X,N.Y,N.Z), albedo "
                  "(albedo.R,G,B), id (primitive id, -1 on a miss); of the first hit of the ray through each pixel's "
                  "centre; into one multi-layer EXR")
      ->type_name("LIST")
      ->check([](const std::string& list) {
        try {
          (void)parse_layers(list);
          return std::string();
        } catch (const UserError& e) {
          return std::string(e.what());
        }
      });
}

void add_transfer_flags(CLI::App* cmd, bool& no_map, bool& no_overlap) {
  cmd->add_flag("--no-map", no_map,
                "Read the results into host memory even where the device could map them (the path of discrete "
                "devices)")
      ->group(kDeveloperGroup);
  cmd->add_flag("--no-overlap", no_overlap,
                "Where results are read, one band at a time (without it, a band's results travel while the next "
                "band's kernel runs)")
      ->group(kDeveloperGroup);
}

void add_repeat_option(CLI::App* cmd, int& repeat, const std::string& help) {
  cmd->add_option("--repeat", repeat, help)->check(CLI::Range(1, kMaxRepeat))->capture_default_str();
}

void RenderOptions::add(CLI::App* cmd, bool with_engine, bool several_scenes) {
  if (several_scenes)
    cmd->add_option("scene", scene_paths,
                    "Scene file(s) (JSON); several: one frame each, written to OUT's pattern (frame_####.png)")
        ->required();
  else
    cmd->add_option("scene", scene_path, "Scene file (JSON)")->required();
  image.add(cmd);
  image.add_ray_budget(cmd);
  if (with_engine) cmd->add_option("--engine", engine, "opencl or reference")->capture_default_str();
  device.add(cmd, /*several=*/true);
  kernel.add(cmd, /*with_variant=*/true);
  launch.add(cmd);
}

void RenderOptions::validate() const {
  image.validate();
  if (engine != "opencl" && engine != "reference")
    throw UserError("unknown engine \"" + engine + "\" (expected opencl or reference)");
  launch.validate();
  (void)kernel.config();
}

namespace {

std::vector<AccuracyVariant> parse_variants(const std::string& list) {
  std::vector<AccuracyVariant> out;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ','))
    if (!name.empty()) out.push_back(parse_accuracy_variant(name));
  if (out.empty()) throw UserError("--variants: empty list");
  return out;
}

}  // namespace

std::string AccuracyOptions::default_variant_list() {
  std::string list;
  for (const AccuracyVariant& v : default_accuracy_variants()) list += (list.empty() ? "" : ",") + v.name();
  return list;
}

void AccuracyOptions::check() const {
  image.validate();
  if (!plot.empty()) check_plot_output(plot);    // fail before measuring
  if (!csv.empty()) check_writable(csv, "CSV");  // fail before measuring, not after
  std::vector<NamedOutput> all;
  if (!csv.empty()) all.push_back({csv, "CSV"});
  if (!plot.empty()) all.push_back({plot, "plot"});
  if (json) all.push_back({"-", "JSON"});
  check_distinct_outputs(all);
  claim_stdout_if_dash(csv);
  (void)settings();
}

AccuracySettings AccuracyOptions::settings() const {
  AccuracySettings s;
  s.width = image.width;
  s.height = image.height;
  s.depth = image.depth;
  s.spp = image.spp;
  s.adaptive = image.adaptive;
  s.repeat = repeat;
  s.base = kernel.config();
  s.variants = parse_variants(variants);
  return s;
}

SweepSettings sweep_settings(const RenderOptions& o, int repeat, bool omp) {
  SweepSettings s;
  s.bench.width = o.image.width;
  s.bench.height = o.image.height;
  s.bench.spp = o.image.spp;
  s.bench.subsample = o.image.subsample;
  s.bench.adaptive = o.image.adaptive;
  s.bench.repeat = repeat;
  s.bench.omp = omp;
  s.bench.embree = false;  // (bench's comparison; the sweep reports OpenMP only)
  s.bench.builds = false;
  return s;
}

void add_number_checks(CLI::App* cmd) {
  // (No description: the help keeps showing the option's type and range.)
  static const CLI::Validator finite(
      [](std::string& text) -> std::string {
        char* end = nullptr;  // (1e999 too: it would convert to infinity)
        const double value = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && !std::isfinite(value))
          return "expected a finite number (got \"" + text.substr(0, 64) + "\")";
        return "";  // a number, or not one at all: CLI11's conversion says so
      },
      "", "finite");
  static const CLI::Validator non_negative(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && value < 0) return "expected a number >= 0 (got \"" + text.substr(0, 64) + "\")";
        return "";
      },
      "", "non-negative");
  for (CLI::Option* option : cmd->get_options()) {
    const std::string type = option->get_type_name();
    if (type.rfind("FLOAT", 0) == 0) option->check(finite);
    if (type.rfind("UINT", 0) == 0) option->check(non_negative);
  }
  for (CLI::App* sub : cmd->get_subcommands({})) add_number_checks(sub);
}

}  // namespace clrt

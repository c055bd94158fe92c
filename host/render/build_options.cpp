// build_options.cpp - the kernel's build options, derived from config + scene
// features.
#include "render/build_options.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "render/precision_support.hpp"
#include "render/scene_buffers.hpp"
#include "util/error.hpp"

namespace clrt {

int default_lanes(const KernelConfig& cfg, const DeviceInfo& dev) {
  if (!cfg.specialize || cfg.precision == Precision::Fp64) return 1;
  if (!is_cpu_type(dev.type) || simd_over_work_items(dev)) return 1;
  return dev.native_float_width >= 16 ? 16 : 8;
}

int packet_rows(const KernelConfig& cfg) {
  const int lanes = kernel_lanes(cfg);
  return lanes >= 16 ? 4 : lanes >= 4 ? 2 : 1;
}

int kernel_lanes(const KernelConfig& cfg) {
  if (cfg.lanes == 0) return cfg.specialize && cfg.precision != Precision::Fp64 ? 8 : 1;
  if (cfg.lanes != 1 && cfg.lanes != 4 && cfg.lanes != 8 && cfg.lanes != 16)
    throw UserError("--lanes must be 1, 4, 8 or 16 (got " + std::to_string(cfg.lanes) + ")");
  if (cfg.lanes > 1 && cfg.precision == Precision::Fp64) throw UserError("--lanes: fp64 kernels are scalar (use 1)");
  return cfg.lanes;
}

int pending_depth_bound(int depth) {
  int bound = 4;
  while (bound < depth && bound < CLRT_MAX_DEPTH) bound *= 2;
  return std::min(bound, CLRT_MAX_DEPTH);
}

namespace {

std::string define(const std::string& name, int value) {
  return "-D" + name + "=" + std::to_string(value);
}
std::string define(const std::string& name, size_t value) {
  return "-D" + name + "=" + std::to_string(value);
}
std::string define(const std::string& name, bool value) {
  return define(name, value ? 1 : 0);
}

// The -D options of a specialized build (kernels/clrt_config.h reads them).
void add_specialization(const KernelFeatures& features, std::vector<std::string>& options) {
  options.push_back("-DCLRT_SPECIALIZED");
  // Not the depth: the kernel reads it at run time, so one program serves
  // every depth (a sweep builds once, not once per depth). Compiled in
  // (-DCLRT_DEPTH, still a knob) it saved under 1% of the demo's kernel
  // time, within the noise (docs/results/archive.md).
  options.push_back(define("CLRT_HAS_AMBIENT", features.has_ambient));
  options.push_back(define("CLRT_HAS_POINT", features.has_point));
  options.push_back(define("CLRT_HAS_DIRECTIONAL", features.has_directional));
  options.push_back(define("CLRT_HAS_SPECULAR", features.has_specular));
  options.push_back(define("CLRT_HAS_REFLECTIVE", features.traces_reflections()));
  options.push_back(define("CLRT_HAS_TRANSPARENT", features.traces_refractions()));
  options.push_back(define("CLRT_HAS_PLANES", features.plane_count > 0));
  options.push_back(define("CLRT_HAS_TRIANGLES", features.triangle_count > 0));
  // Constant counts (and so unrolled loops and per-light types) only for
  // small scenes: the unrolled code, and with it the build time, grows with
  // every sphere and light (docs/reference/kernel.md, "Specialization").
  if (!features.unroll_counts) return;
  options.push_back(define("CLRT_N_SPHERES", features.sphere_count));
  options.push_back(define("CLRT_N_LIGHTS", features.light_count));
  if (features.light_types.empty()) return;
  std::string types = "-DCLRT_LIGHT_TYPES=";
  for (size_t i = 0; i < features.light_types.size(); ++i)
    types += (i ? "," : "") + std::to_string(kernel_light_code(features.light_types[i]));
  options.push_back(types);
}

// Robust builds test each sphere with compensated or cheap arithmetic, as its
// flag says (clrt_sphere.compensated). A specialized build compiles out the
// path no sphere takes when the spheres agree; with unrolled counts it makes
// each sphere's flag a constant, so that every unrolled test is one straight
// path: the flag read at run time cost 10% of the demo's kernel time against
// the constants (docs/reference/precision.md). Otherwise the flags decide at run time.
void add_compensation(const KernelFeatures& features, std::vector<std::string>& options) {
  const size_t compensated = features.compensated_spheres();
  if (compensated == 0 || compensated == features.compensated.size()) {
    options.push_back(define("CLRT_COMPENSATED_SPHERES", compensated > 0));
    return;
  }
  if (!features.unroll_counts) return;
  std::string flags = "-DCLRT_COMPENSATED_FLAGS=";
  for (size_t i = 0; i < features.compensated.size(); ++i)
    flags += (i ? "," : "") + std::to_string(int(features.compensated[i]));
  options.push_back(flags);
}

}  // namespace

std::vector<std::string> build_option_list(const KernelConfig& cfg, const KernelFeatures& features,
                                           bool device_has_fp64) {
  if (!precision_supported(cfg.precision, device_has_fp64))
    throw UserError("precision fp64 needs a device with cl_khr_fp64; this device has none (use --precision robust)");
  std::vector<std::string> options = {"-cl-std=CL1.2", define("CLRT_PRECISION", kernel_code(cfg.precision))};
  if (cfg.denorms_zero) options.push_back("-cl-denorms-are-zero");
  if (cfg.loop_limit_probe) options.push_back("-DCLRT_LOOP_LIMIT_PROBE");
  if (cfg.precision == Precision::Fast) options.push_back("-cl-fast-relaxed-math");
  if (cfg.count_rays) options.push_back("-DCLRT_COUNT_RAYS");
  // What the kernel stores per pixel: only what the caller reads (float
  // colour for Float and Unit frames: Unit is scaled on the host).
  if (cfg.output.pixels == PixelFormat::Rgba8) options.push_back("-DCLRT_OUT_RGBA8");
  if (cfg.output.classes) options.push_back("-DCLRT_OUT_CLASSES");
  // Any AOV layer: the kernel stores all of them (one program serves every
  // set of layers; the host keeps the ones asked for).
  if (cfg.output.layers) options.push_back("-DCLRT_OUT_LAYERS");
  if (cfg.subsample != Subsample::Off)
    options.push_back(define("CLRT_SUBSAMPLE", cfg.subsample == Subsample::Shade ? 1 : 2));
  if (int lanes = kernel_lanes(cfg); lanes > 1) options.push_back(define("CLRT_LANES", lanes));
  if (int rows = packet_rows(cfg); rows > 1) options.push_back(define("CLRT_PACKET_ROWS", rows));
  if (uses_bvh(cfg.accel, features.sphere_count + features.triangle_count, cfg.precision)) {
    options.push_back("-DCLRT_BVH");
    options.push_back(define("CLRT_BVH_WIDTH", CLRT_BVH_WIDTH));  // the host's clrt_wide_node
    // (the walk's share of the boxes' padding: CLRT_BVH_PAD)
    options.push_back(define("CLRT_BVH_SPHERES", features.sphere_count > 0));
    if (cfg.fast_fma.value_or(false)) options.push_back("-DCLRT_FAST_FMA");
  }
  if (cfg.specialize) add_specialization(features, options);
  // The tree walk's pending rays take a slot per level (clrt_ray_tree.h): a scene
  // that refracts gets as many as its depth class needs, not CLRT_MAX_DEPTH
  // (65 slots of 40 bytes per lane; 16 lanes would take 41 KiB per
  // work-item). Depths share a program within a class (a sweep over 0-10
  // builds three).
  if (features.traces_refractions()) options.push_back(define("CLRT_DEPTH_BOUND", pending_depth_bound(features.depth)));
  if (cfg.specialize && cfg.precision == Precision::Robust) add_compensation(features, options);
  if (!cfg.extra_options.empty()) options.push_back(cfg.extra_options);
  return options;
}

std::string join_build_options(const std::vector<std::string>& options) {
  std::string joined;
  for (const std::string& option : options) joined += (joined.empty() ? "" : " ") + option;
  return joined;
}

std::string build_options(const KernelConfig& cfg, const KernelFeatures& features, bool device_has_fp64) {
  return join_build_options(build_option_list(cfg, features, device_has_fp64));
}

std::string build_options(const KernelConfig& cfg, const Scene& scene, int depth, bool device_has_fp64) {
  return build_options(cfg, kernel_features(scene, depth), device_has_fp64);
}

}  // namespace clrt

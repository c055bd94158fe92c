// build_options.cpp - the kernel's build options, derived from config + scene.
#include "render/build_options.hpp"

#include "clrt_layout.h"
#include "util/error.hpp"

namespace clrt {

int default_lanes(const KernelConfig& cfg, const DeviceInfo& dev) {
  if (!cfg.specialize || cfg.precision == Precision::Fp64) return 1;
  if (!is_cpu_type(dev.type)) return 1;
  return dev.native_float_width >= 16 ? 16 : 8;
}

int kernel_lanes(const KernelConfig& cfg) {
  if (cfg.lanes == 0) return cfg.specialize && cfg.precision != Precision::Fp64 ? 8 : 1;
  if (cfg.lanes != 1 && cfg.lanes != 4 && cfg.lanes != 8 && cfg.lanes != 16)
    throw UserError("--lanes must be 1, 4, 8 or 16 (got " + std::to_string(cfg.lanes) + ")");
  if (cfg.lanes > 1 && cfg.precision == Precision::Fp64) throw UserError("--lanes: fp64 kernels are scalar (use 1)");
  return cfg.lanes;
}

bool unroll_counts(const Scene& scene) {
  return scene.spheres.size() <= kMaxUnrolledSpheres && scene.lights.size() <= kMaxUnrolledLights;
}

std::string build_options(const KernelConfig& cfg, const Scene& scene, int depth, bool device_has_fp64) {
  if (cfg.precision == Precision::Fp64 && !device_has_fp64)
    throw UserError("precision fp64 needs a device with cl_khr_fp64; this device has none (use --precision robust)");
  std::string o = "-cl-std=CL1.2 -DCLRT_PREC=" + std::to_string(kernel_code(cfg.precision));
  if (cfg.denorms_zero) o += " -cl-denorms-are-zero";
  if (cfg.precision == Precision::Fast) o += " -cl-fast-relaxed-math";
  if (cfg.count_rays) o += " -DCLRT_COUNT_RAYS";
  if (int lanes = kernel_lanes(cfg); lanes > 1) o += " -DCLRT_LANES=" + std::to_string(lanes);
  if (cfg.specialize) {
    bool amb = false, pt = false, dir = false, spec = false, refl = false;
    for (const auto& l : scene.lights) {
      amb |= l.type == LightType::Ambient;
      pt |= l.type == LightType::Point;
      dir |= l.type == LightType::Directional;
    }
    for (const auto& s : scene.spheres) {
      spec |= s.specular != -1;
      refl |= s.reflective > 0;
    }
    // With no reflective sphere the depth never matters: fold it to 0 so one
    // program serves every depth.
    int d = refl ? depth : 0;
    o += " -DCLRT_SPECIALIZED -DCLRT_DEPTH=" + std::to_string(d) + " -DCLRT_HAS_AMBIENT=" + (amb ? "1" : "0") +
         " -DCLRT_HAS_POINT=" + (pt ? "1" : "0") + " -DCLRT_HAS_DIRECTIONAL=" + (dir ? "1" : "0") +
         " -DCLRT_HAS_SPECULAR=" + (spec ? "1" : "0") + " -DCLRT_HAS_REFLECTIVE=" + (refl && d > 0 ? "1" : "0");
    // Constant counts (and so unrolled loops and per-light types) only for
    // small scenes: the unrolled code, and with it the build time, grows with
    // every sphere and light (docs/performance.md, "Bounded specialization").
    const bool unroll = unroll_counts(scene);
    if (unroll)
      o += " -DCLRT_N_SPHERES=" + std::to_string(scene.spheres.size()) +
           " -DCLRT_N_LIGHTS=" + std::to_string(scene.lights.size());
    if (unroll && !scene.lights.empty()) {
      o += " -DCLRT_LIGHT_TYPES=";
      for (size_t i = 0; i < scene.lights.size(); ++i) {
        const LightType t = scene.lights[i].type;
        o += (i ? "," : "") + std::to_string(t == LightType::Ambient ? CLRT_LIGHT_AMBIENT
                                             : t == LightType::Point ? CLRT_LIGHT_POINT
                                                                     : CLRT_LIGHT_DIRECTIONAL);
      }
    }
  }
  if (!cfg.extra_options.empty()) o += " " + cfg.extra_options;
  return o;
}

}  // namespace clrt

// build_options.hpp - every -D / -cl-* option of the kernel is made here, in
// one place, so that it can be logged and used as part of the cache key.
#pragma once
#include <string>

#include "cl/device.hpp"
#include "render/precision.hpp"
#include "scene/scene.hpp"

namespace clrt {

struct KernelConfig {
  Precision precision = Precision::Robust;
  bool specialize = true;     // derive constants/features from the scene
  bool count_rays = false;    // per-pixel ray counters (bench)
  bool denorms_zero = true;   // -cl-denorms-are-zero (PoCL stalls otherwise)
  int lanes = 0;              // pixels per work-item (SIMD lanes); 0 = default, see kernel_lanes()
  bool use_cache = true;      // on-disk program binary cache (--no-cache)
  bool verbose = false;       // log build options and cache use on stderr
  std::string kernel_dir;     // "" = embedded kernels
  std::string extra_options;  // appended verbatim (development)
};

// Pixels per work-item: cfg.lanes if set, else 8 for specialized float
// builds (float8 lanes, see kernels/trace.cl) and 1 (scalar) otherwise.
// UserError for a count other than 1, 4, 8, 16, or > 1 with fp64.
int kernel_lanes(const KernelConfig& cfg);

// The lane count used when cfg.lanes is 0 on `dev`: specialized float
// builds shade 16 pixels per work-item on CPUs whose native float vector
// width is >= 16 (AVX-512), 8 on other CPUs, 1 on GPUs (whose work-items are
// SIMD lanes already); generic and fp64 builds are scalar (1). Measured in
// docs/performance.md.
int default_lanes(const KernelConfig& cfg, const DeviceInfo& dev);

// Throws UserError when fp64 is asked of a device without cl_khr_fp64.
std::string build_options(const KernelConfig& cfg, const Scene& scene, int depth, bool device_has_fp64);

// A specialized build makes the sphere and light counts (and each light's
// type) compile-time constants, and unrolls their loops, only up to these
// counts; past them it keeps the other specializations and loops over the
// scene's buffers, so build time stays bounded for any scene
// (docs/performance.md, "Bounded specialization").
constexpr size_t kMaxUnrolledSpheres = 16, kMaxUnrolledLights = 16;
bool unroll_counts(const Scene& scene);

}  // namespace clrt

// build_options.hpp - every -D / -cl-* option of the kernel is made here, in
// one place, so that it can be logged and used as part of the cache key.
#pragma once
#include <string>

#include "precision.hpp"
#include "scene.hpp"

namespace clrt {

struct KernelConfig {
  Precision precision = Precision::Robust;
  bool specialize = true;     // derive constants/features from the scene
  bool count_rays = false;    // per-pixel ray counters (bench)
  bool denorms_zero = true;   // -cl-denorms-are-zero (PoCL stalls otherwise)
  std::string kernel_dir;     // "" = embedded kernels
  std::string extra_options;  // appended verbatim (development)
};

// Throws UserError when fp64 is asked of a device without cl_khr_fp64.
std::string build_options(const KernelConfig& cfg, const Scene& scene, int depth, bool device_has_fp64);

}  // namespace clrt

// build_options.hpp - every -D / -cl-* option of the kernel is made here, in
// one place, so that it can be logged and used as part of the cache key.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "image/image.hpp"
#include "render/bvh.hpp"
#include "render/kernel_features.hpp"
#include "render/precision.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"

namespace clrt {

struct KernelConfig {
  Precision precision = Precision::Robust;
  bool specialize = true;     // derive constants/features from the scene
  bool count_rays = false;    // per-pixel ray counters (bench)
  bool denorms_zero = true;   // -cl-denorms-are-zero (PoCL stalls otherwise)
  int lanes = 0;              // pixels per work-item (SIMD lanes); 0 = chosen per scene (lane_choice.hpp)
  // With lanes 0: time the candidate lane counts on the scene before its
  // first frame (lane_choice.hpp); false: default_lanes(), no probe (tests
  // that want one program per configuration; the image is the same).
  bool probe_lanes = true;
  bool use_cache = true;      // on-disk program binary cache (--no-cache)
  bool verbose = false;       // log build options and cache use on stderr
  std::string kernel_dir;     // "" = embedded kernels
  std::string extra_options;  // appended verbatim (development)
  Accel accel = Accel::Auto;  // test every sphere or walk the hierarchy (render/bvh.hpp)
  // What each pixel's result holds (8-bit or float colour, classification):
  // the kernel writes exactly this.
  FrameContents output;
  // The book's subsampling (Sampling::subsample): two launches per tile,
  // even columns then odd (-DCLRT_SUBSAMPLE=1 shade, 2 interpolate). Set by
  // DeviceRenderer::prepare() from the frame's Sampling.
  Subsample subsample = Subsample::Off;
  // Build in the check that the driver did not end the kernel's loops early
  // (-DCLRT_LOOP_LIMIT_PROBE, kernels/clrt_device_status.h): set by
  // DeviceRenderer on devices that do (ends_long_loops()); tests set it
  // elsewhere to see that it reports nothing where nothing happened.
  bool loop_limit_probe = false;
  // The hierarchy's box tests with fma() (-DCLRT_FAST_FMA, kernels/
  // clrt_bvh.h); unset: DeviceRenderer sets it to fuses_multiply_add().
  // Either way the images are the same (tests/render/test_bvh.cpp).
  std::optional<bool> fast_fma;
};

// Pixels per work-item: cfg.lanes if set. The renderer sets it from
// default_lanes() before building; a config that no device has resolved yet
// (lanes 0) counts as 8 for specialized float builds and 1 otherwise.
// UserError for a count other than 1, 4, 8, 16, or > 1 with fp64.
int kernel_lanes(const KernelConfig& cfg);
// Rows of a work-item's block of pixels (its lanes): 16 lanes shade 4x4
// pixels, 8 lanes 4x2, 4 lanes 2x2. A square block's rays stay together
// longer than a row's (they hit fewer different spheres and reflect into
// nearer directions): 12% less kernel time than 16x1 at 10 000 spheres,
// the same on the book's scene (docs/results/archive.md).
int packet_rows(const KernelConfig& cfg);

// The lane count used when cfg.lanes is 0 on `dev`: specialized float
// builds shade 16 pixels per work-item on CPUs whose native float vector
// width is >= 16 (AVX-512), 8 on other CPUs, 1 on GPUs and on llvmpipe
// (rusticl), whose work-items are SIMD lanes already (simd_over_work_items);
// generic and fp64 builds are scalar (1). Why: docs/developer/kernel.md.
int default_lanes(const KernelConfig& cfg, const DeviceInfo& dev);

// The slots of the tree walk's pending rays (clrt_ray_tree.h) for a scene that
// refracts at recursion depth `depth`: the smallest of 4, 8, 16, 32, 64 that
// is >= depth (-DCLRT_DEPTH_BOUND; one program per class of depths).
int pending_depth_bound(int depth);

// The build options, one entry each ("-cl-std=CL1.2", "-DCLRT_LANES=8", ...;
// cfg.extra_options is one entry, verbatim). Features are used only by
// specialized builds. Throws UserError when fp64 is asked of a device without
// cl_khr_fp64, and for a lane count kernel_lanes() rejects.
std::vector<std::string> build_option_list(const KernelConfig& cfg, const KernelFeatures& features,
                                           bool device_has_fp64);

// The entries joined by single spaces: what clBuildProgram gets, what is
// logged, and what the program cache key holds.
std::string join_build_options(const std::vector<std::string>& options);

// join_build_options(build_option_list(cfg, features, device_has_fp64)).
std::string build_options(const KernelConfig& cfg, const KernelFeatures& features, bool device_has_fp64);
// The same with the scene's features (kernel_features(scene, depth)).
std::string build_options(const KernelConfig& cfg, const Scene& scene, int depth, bool device_has_fp64);

}  // namespace clrt

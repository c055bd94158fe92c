// accuracy.hpp - error against run time: every precision variant on every
// scene, kernel time (median of N launches after a warm-up) and the error of
// the image against the double reference (`clrt accuracy`). The book's
// subsampling is a variant too ("robust+subsample"): a speed-up bought with
// error, measured against the same exact reference.
#pragma once
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "eval/compare.hpp"
#include "render/build_options.hpp"
#include "render/precision.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"
#include "util/progress.hpp"

namespace clrt {

// A precision, alone or with subsampling (scene/sampling.hpp).
struct AccuracyVariant {
  Precision precision = Precision::Robust;
  Subsample subsample = Subsample::Off;
  std::string name() const;  // "robust", "robust+subsample-shade", "robust+subsample-interpolate"
  bool operator==(const AccuracyVariant& o) const { return precision == o.precision && subsample == o.subsample; }
};
// A name as name() gives it (UserError for others).
AccuracyVariant parse_accuracy_variant(const std::string& name);
// Every precision, then robust with each subsampling mode.
std::vector<AccuracyVariant> default_accuracy_variants();

struct AccuracySettings {
  int width = 600, height = 600;
  int depth = -1;        // -1 = each scene's recursion_depth
  int spp = 1;           // N x N samples per pixel, the reference's and every variant's
  double adaptive = -1;  // adaptive supersampling's threshold (scene/sampling.hpp); negative: off
  int repeat = 7;        // timed launches per variant (after one warm-up launch)
  KernelConfig base;     // precision is overwritten per variant
  std::vector<AccuracyVariant> variants = default_accuracy_variants();
  // Per scene: its reference, each variant's build and warm-up, each timed
  // run; and once with done == total at the end. Empty: none.
  ProgressFn progress{};
};

struct AccuracyRow {
  std::string scene;  // as given (path)
  std::string variant;
  int depth = 0;
  bool supported = true;
  std::string note;               // why unsupported
  std::vector<double> kernel_ms;  // every timed frame (summed over its launches)
  double median_ms = 0;
  int launches = 0, host_timed_launches = 0;  // over the timed frames (launch_timing.hpp)
  std::string time_source() const;            // "events", "host" or "mixed"
  Comparison error;                           // against the reference
};

struct NamedScene {
  std::string name;
  Scene scene;
};

// Renders the reference once per scene, then each variant once (warm-up; its
// image is the one compared), then `repeat` timed rounds over all variants
// (interleaved, so background load hits every variant alike). A variant the
// device cannot run (fp64 without cl_khr_fp64) gives an unsupported row.
std::vector<AccuracyRow> measure_accuracy(const std::vector<NamedScene>& scenes, const DeviceInfo& device,
                                          const AccuracySettings& s);

// The pieces of measure_accuracy, which an accuracy run spread over the
// ranks of an MPI job (dist/eval_grids.hpp) runs on different ranks.
// The depth a scene is rendered at (--depth, else its recursion_depth).
int accuracy_depth(const Scene& scene, const AccuracySettings& s);
// The double reference of a scene.
Image accuracy_reference(const Scene& scene, const AccuracySettings& s);
// A row's scene, variant and depth, and whether `device` runs the variant
// (supported, note); nothing measured.
AccuracyRow accuracy_row(const NamedScene& scene, const AccuracyVariant& v, const DeviceInfo& device,
                         const AccuracySettings& s);
// One variant alone: its row with the `repeat` timed runs (back to back, not
// interleaved with other variants) and, when supported, its warm-up image in
// `image` (for the error, which is left to the caller: compare_images(image,
// reference)).
AccuracyRow measure_accuracy_variant(const NamedScene& scene, const AccuracyVariant& v, const DeviceInfo& device,
                                     const AccuracySettings& s, Image& image);

}  // namespace clrt

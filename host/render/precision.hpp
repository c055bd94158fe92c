// precision.hpp - the kernel's precision variants (docs/reference/precision.md).
#pragma once
#include <string>
#include <vector>

#include "clrt_layout.h"

namespace clrt {

// The values are the kernel's CLRT_PRECISION codes (kernels/clrt_layout.h).
enum class Precision {
  Naive = CLRT_PRECISION_NAIVE,    // the book's float32 formulas
  Stable = CLRT_PRECISION_STABLE,  // Ray Tracing Gems ch. 7 discriminant + stable roots, float32
  Robust = CLRT_PRECISION_ROBUST,  // default: camera-relative float32 + compensated |f|^2 - r^2
  Fast = CLRT_PRECISION_FAST,      // stable + normal offset, -cl-fast-relaxed-math, native_*
  Fp64 = CLRT_PRECISION_FP64,      // the book's formulas in double (needs cl_khr_fp64)
};

// The value of -DCLRT_PRECISION for `p`.
constexpr int kernel_code(Precision p) {
  return static_cast<int>(p);
}
std::string precision_name(Precision p);
Precision parse_precision(const std::string& name);  // UserError on unknown
const std::vector<Precision>& all_precisions();

}  // namespace clrt

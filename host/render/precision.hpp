// precision.hpp - the kernel's precision variants (see README, "Precision").
#pragma once
#include <string>
#include <vector>

namespace clrt {

enum class Precision {
  Naive,   // the book's float32 formulas
  Stable,  // Ray Tracing Gems ch. 7 discriminant + stable roots, float32
  Robust,  // default: camera-relative float32 + compensated |f|^2 - r^2
  Fast,    // stable + normal offset, -cl-fast-relaxed-math, native_*
  Fp64,    // the book's formulas in double (needs cl_khr_fp64)
};

// Same numbering as CLRT_PREC in kernels/trace.cl.
inline int kernel_code(Precision p) { return static_cast<int>(p); }
std::string precision_name(Precision p);
Precision parse_precision(const std::string& name);  // UserError on unknown
const std::vector<Precision>& all_precisions();

}  // namespace clrt

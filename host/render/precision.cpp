// precision.cpp - names of the precision variants.
#include "render/precision.hpp"

#include "util/error.hpp"

namespace clrt {

std::string precision_name(Precision p) {
  switch (p) {
    case Precision::Naive:
      return "naive";
    case Precision::Stable:
      return "stable";
    case Precision::Robust:
      return "robust";
    case Precision::Fast:
      return "fast";
    case Precision::Fp64:
      return "fp64";
  }
  return "?";
}

const std::vector<Precision>& all_precisions() {
  static const std::vector<Precision> v{Precision::Naive, Precision::Stable, Precision::Robust, Precision::Fast,
                                        Precision::Fp64};
  return v;
}

Precision parse_precision(const std::string& name) {
  for (Precision p : all_precisions())
    if (precision_name(p) == name) return p;
  throw UserError("unknown precision \"" + name + "\" (expected naive, stable, robust, fast or fp64)");
}

}  // namespace clrt

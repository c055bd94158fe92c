// precision_support.cpp - device capabilities per precision variant.
#include "render/precision_support.hpp"

namespace clrt {

std::string unsupported_reason(Precision p, const DeviceInfo& device) {
  if (p == Precision::Fp64 && !device.fp64) return "unsupported: device has no cl_khr_fp64";
  return "";
}

}  // namespace clrt

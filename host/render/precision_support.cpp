// precision_support.cpp - device capabilities per precision variant.
#include "render/precision_support.hpp"

namespace clrt {

bool precision_supported(Precision p, bool device_has_fp64) {
  return p != Precision::Fp64 || device_has_fp64;
}

std::string unsupported_reason(Precision p, const DeviceInfo& device) {
  if (!precision_supported(p, device.fp64)) return "unsupported: device has no cl_khr_fp64";
  return "";
}

}  // namespace clrt

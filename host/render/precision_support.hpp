// precision_support.hpp - whether a device can run a precision variant.
#pragma once
#include <string>

#include "cl/device.hpp"
#include "render/precision.hpp"

namespace clrt {

// "" when `device` can run `p`; otherwise why not (fp64 needs cl_khr_fp64).
std::string unsupported_reason(Precision p, const DeviceInfo& device);

}  // namespace clrt

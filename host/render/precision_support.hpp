// precision_support.hpp - whether a device can run a precision variant: the
// one place that knows fp64 needs cl_khr_fp64.
#pragma once
#include <string>

#include "cl/device.hpp"
#include "render/precision.hpp"

namespace clrt {

// Whether a device with (or without) cl_khr_fp64 can run `p`.
bool precision_supported(Precision p, bool device_has_fp64);

// "" when `device` can run `p`; otherwise why not (fp64 needs cl_khr_fp64).
std::string unsupported_reason(Precision p, const DeviceInfo& device);

}  // namespace clrt

// device.hpp - OpenCL platform/device enumeration and selection.
#pragma once
#include <string>
#include <vector>

#include "cl/cl.hpp"

namespace clrt {

struct DeviceInfo {
  int index = 0;           // global index over all platforms, as `clrt devices` shows
  int platform_index = 0;  // the platform's position in the ICD loader's list
  int device_index = 0;    // the device's position on its platform
  cl::Platform platform;
  cl::Device device;
  std::string name, platform_name, vendor, type, version, c_version, driver;
  cl_uint compute_units = 0;
  bool fp64 = false;
  cl_ulong max_alloc = 0, global_mem = 0;
  size_t max_work_group = 0;
  cl_uint clock_mhz = 0;
  cl_uint native_float_width = 0;
};

// Device kinds by DeviceInfo::type ("CPU", "GPU", "ACCELERATOR", ...): the
// one place that reads it.
inline bool is_cpu_type(const std::string& type) {
  return type.find("CPU") != std::string::npos;
}
inline bool is_gpu_type(const std::string& type) {
  return type.find("GPU") != std::string::npos;
}
// Whether the driver runs a work-group's work-items as the lanes of SIMD
// vectors itself, as GPUs do and as Mesa's llvmpipe (rusticl) does on a
// CPU: there a kernel that shades a block of pixels per work-item gains
// nothing and costs the driver's compiler 10x the time (docs/developer/kernel.md).
inline bool simd_over_work_items(const DeviceInfo& dev) {
  return is_gpu_type(dev.type) || dev.platform_name == "rusticl" || dev.name.rfind("llvmpipe", 0) == 0;
}

// Whether the driver ends a work-item's loops after a fixed number of
// iterations in all, silently: Mesa's llvmpipe (65 535; kernels/
// clrt_device_status.h). Programs for it check whether that happened.
inline bool ends_long_loops(const DeviceInfo& dev) {
  return dev.name.rfind("llvmpipe", 0) == 0;
}

// Whether the device runs fma() in hardware, as fast as a multiply: every
// GPU, and a CPU device (its driver compiles for this machine's CPU: PoCL,
// llvmpipe) where this CPU has FMA instructions. (OpenCL's FP_FAST_FMAF
// would say so in the kernel; neither PoCL nor rusticl defines it.)
bool fuses_multiply_add(const DeviceInfo& dev);

// Every device of every platform. Throws DeviceError("no OpenCL platform ...")
// when the ICD loader finds none.
std::vector<DeviceInfo> list_devices();

// Position in `all` (non-empty) of the default device: the first GPU, else
// the first device.
size_t default_device(const std::vector<DeviceInfo>& all);

// "P:D": the platform and the device's position on it (`clrt devices`).
std::string platform_device_id(const DeviceInfo& d);

// Selects devices by SPEC: "" (first GPU, else first device), an index, a
// "P:D" pair (platform P, its device D), a comma-separated list of these,
// "all", or a case-insensitive substring of the device name, type
// (cpu/gpu/accelerator) or platform name (the first match; when several
// devices match, one line through util/log says which was taken).
// Unknown SPEC -> UserError listing what exists.
std::vector<DeviceInfo> select_devices(const std::string& spec);
// The same choice among `all` (non-empty), e.g. list_devices().
std::vector<DeviceInfo> pick_devices(const std::vector<DeviceInfo>& all, const std::string& spec);
DeviceInfo select_device(const std::string& spec);

}  // namespace clrt

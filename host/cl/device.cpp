// device.cpp - platform/device enumeration and selection by index or name.
#include "cl/device.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "cl/pocl_workers.hpp"
#include "util/error.hpp"
#include "util/log.hpp"

namespace clrt {

bool fuses_multiply_add(const DeviceInfo& dev) {
  if (is_gpu_type(dev.type)) return true;
  if (!is_cpu_type(dev.type)) return false;
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("fma");
#elif defined(__aarch64__)
  return true;  // (FMA is part of ARMv8's floating point)
#else
  return false;
#endif
}
namespace {

// (named apart from image_file.cpp's lower(): clrt_core is a unity build)
std::string lowercase(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string type_name(cl_device_type t) {
  std::string out;
  if (t & CL_DEVICE_TYPE_CPU) out += "CPU";
  if (t & CL_DEVICE_TYPE_GPU) out += out.empty() ? "GPU" : "+GPU";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) out += out.empty() ? "ACCELERATOR" : "+ACCELERATOR";
  if (out.empty()) out = "OTHER";
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  return s;
}

bool all_digits(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

}  // namespace

namespace {

// PoCL keeps its kernel cache under $XDG_CACHE_HOME (else ~/.cache) and
// exposes no device when it cannot create it, which would otherwise read as
// "no OpenCL device". Names the cause when that is what happened.
std::string cache_home_hint() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  std::string dir = xdg && *xdg ? xdg : (home && *home ? std::string(home) + "/.cache" : "");
  if (dir.empty()) return "";
  std::error_code ec;
  std::filesystem::path p(dir);
  while (!p.empty() && !std::filesystem::exists(p, ec)) p = p.parent_path();
  if (p.empty() || std::filesystem::is_directory(p, ec)) {
    if (::access(p.empty() ? "." : p.c_str(), W_OK) == 0) return "";
  }
  return std::string(" (") + (xdg && *xdg ? "XDG_CACHE_HOME=" : "the cache directory ") + dir +
         " cannot be created or written, and PoCL needs it for its kernel cache)";
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  pin_pocl_workers_by_default();  // (PoCL reads it when it starts its workers, at the first call)
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    // The ICD loader reports CL_PLATFORM_NOT_FOUND_KHR (-1001) with no ICDs.
    throw DeviceError("no OpenCL platform found (" + cl_error_name(e.err()) +
                      "); install an OpenCL driver such as pocl-opencl-icd, or use --engine reference");
  }
  if (platforms.empty())
    throw DeviceError(
        "no OpenCL platform found; install an OpenCL driver such as pocl-opencl-icd, or use --engine reference");
  std::vector<DeviceInfo> out;
  for (size_t platform_index = 0; platform_index < platforms.size(); ++platform_index) {
    auto& p = platforms[platform_index];
    std::vector<cl::Device> devs;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devs);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices (CL_DEVICE_NOT_FOUND)
    }
    for (size_t device_index = 0; device_index < devs.size(); ++device_index) {
      auto& d = devs[device_index];
      DeviceInfo info;
      info.index = static_cast<int>(out.size());
      info.platform_index = static_cast<int>(platform_index);
      info.device_index = static_cast<int>(device_index);
      info.platform = p;
      info.device = d;
      info.name = trim(d.getInfo<CL_DEVICE_NAME>());
      info.platform_name = trim(p.getInfo<CL_PLATFORM_NAME>());
      info.vendor = trim(d.getInfo<CL_DEVICE_VENDOR>());
      info.type = type_name(d.getInfo<CL_DEVICE_TYPE>());
      info.version = trim(d.getInfo<CL_DEVICE_VERSION>());
      info.c_version = trim(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
      info.driver = trim(d.getInfo<CL_DRIVER_VERSION>());
      info.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.fp64 = d.getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
      info.max_alloc = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      info.global_mem = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.max_work_group = d.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
      info.clock_mhz = d.getInfo<CL_DEVICE_MAX_CLOCK_FREQUENCY>();
      info.native_float_width = d.getInfo<CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT>();
      out.push_back(std::move(info));
    }
  }
  if (out.empty())
    throw DeviceError("no OpenCL device found on any platform" + cache_home_hint() + "; use --engine reference");
  return out;
}

size_t default_device(const std::vector<DeviceInfo>& all) {
  for (size_t i = 0; i < all.size(); ++i)
    if (is_gpu_type(all[i].type)) return i;
  return 0;
}

std::string platform_device_id(const DeviceInfo& d) {
  return std::to_string(d.platform_index) + ":" + std::to_string(d.device_index);
}

std::vector<DeviceInfo> select_devices(const std::string& spec) {
  return pick_devices(list_devices(), spec);
}

std::vector<DeviceInfo> pick_devices(const std::vector<DeviceInfo>& all, const std::string& spec_in) {
  if (all.empty()) throw std::logic_error("pick_devices without devices");
  const std::string spec = lowercase(spec_in);
  if (spec.empty() || spec == "default") return {all[default_device(all)]};
  if (spec == "all") return all;
  std::vector<DeviceInfo> picked;
  std::stringstream ss(spec);
  std::string part;
  while (std::getline(ss, part, ',')) {
    bool found = false;
    const size_t colon = part.find(':');
    if (all_digits(part)) {
      // Any index longer than 9 digits is out of range (and would overflow stoul).
      if (part.size() <= 9 && std::stoul(part) < all.size()) picked.push_back(all[std::stoul(part)]), found = true;
    } else if (colon != std::string::npos && all_digits(part.substr(0, colon)) && all_digits(part.substr(colon + 1))) {
      for (auto& d : all) {
        if (platform_device_id(d) == part) {
          picked.push_back(d);
          found = true;
          break;
        }
      }
    } else {
      std::vector<const DeviceInfo*> matches;
      for (auto& d : all)
        if (lowercase(d.name).find(part) != std::string::npos || lowercase(d.type).find(part) != std::string::npos ||
            lowercase(d.platform_name).find(part) != std::string::npos)
          matches.push_back(&d);
      if (!matches.empty()) {
        picked.push_back(*matches.front());
        found = true;
      }
      if (matches.size() > 1) {
        std::string which;
        for (const DeviceInfo* d : matches)
          which += (which.empty() ? "" : ", ") + std::to_string(d->index) + " [" + platform_device_id(*d) + "]";
        const DeviceInfo& first = *matches.front();
        log_message(LogLevel::Info, "--device " + part + " matches " + std::to_string(matches.size()) + " devices (" +
                                        which + "); using " + std::to_string(first.index) + " [" +
                                        platform_device_id(first) + "]: " + first.name + " (" + first.platform_name +
                                        ")");
      }
    }
    if (!found) {
      std::string have;
      for (auto& d : all) have += (have.empty() ? "" : ", ") + std::to_string(d.index) + ": " + d.name;
      throw UserError("unknown device \"" + part + "\" (available: " + have + ")");
    }
  }
  return picked;
}

DeviceInfo select_device(const std::string& spec) {
  auto v = select_devices(spec);
  return v.front();
}

}  // namespace clrt

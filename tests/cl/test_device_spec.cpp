// test_device_spec.cpp - what a --device spec picks among a list of devices
// (made up here: no OpenCL needed).
#include <catch2/catch.hpp>

#include "cl/device.hpp"
#include "util/error.hpp"

using namespace clrt;

namespace {

DeviceInfo fake(int index, const std::string& name, const std::string& type, const std::string& platform) {
  DeviceInfo d;
  d.index = index;
  d.name = name;
  d.type = type;
  d.platform_name = platform;
  return d;
}

std::vector<int> indices(const std::vector<DeviceInfo>& picked) {
  std::vector<int> out;
  for (const auto& d : picked) out.push_back(d.index);
  return out;
}

const std::vector<DeviceInfo> kCpuOnly = {fake(0, "cpu-haswell-AMD EPYC", "CPU", "Portable Computing Language"),
                                          fake(1, "llvmpipe (LLVM 15.0.6, 256 bits)", "GPU", "rusticl")};
const std::vector<DeviceInfo> kWithGpu = {fake(0, "pthread-AMD EPYC", "CPU", "Portable Computing Language"),
                                          fake(1, "NVIDIA H100", "GPU", "NVIDIA CUDA"),
                                          fake(2, "pthread-AMD EPYC", "CPU", "Portable Computing Language")};

}  // namespace

TEST_CASE("the default device is the first GPU, else the first device", "[device]") {
  CHECK(default_device(kWithGpu) == 1);
  CHECK(indices(pick_devices(kWithGpu, "")) == std::vector<int>{1});
  CHECK(indices(pick_devices(kWithGpu, "default")) == std::vector<int>{1});
  const std::vector<DeviceInfo> cpus = {kWithGpu[0], kWithGpu[2]};
  CHECK(default_device(cpus) == 0);
}

TEST_CASE("device specs: index, list, all, and case-insensitive substrings", "[device]") {
  CHECK(indices(pick_devices(kWithGpu, "2")) == std::vector<int>{2});
  CHECK(indices(pick_devices(kWithGpu, "0,2")) == std::vector<int>{0, 2});
  CHECK(indices(pick_devices(kWithGpu, "all")) == std::vector<int>{0, 1, 2});
  CHECK(indices(pick_devices(kWithGpu, "ALL")) == std::vector<int>{0, 1, 2});
  // A substring of the name, the type or the platform: the first match.
  CHECK(indices(pick_devices(kWithGpu, "h100")) == std::vector<int>{1});
  CHECK(indices(pick_devices(kWithGpu, "cpu")) == std::vector<int>{0});
  CHECK(indices(pick_devices(kWithGpu, "Pthread")) == std::vector<int>{0});
  CHECK(indices(pick_devices(kCpuOnly, "rusticl")) == std::vector<int>{1});
  // The same device twice is two workers (two contexts share the frame).
  CHECK(indices(pick_devices(kWithGpu, "1,1")) == std::vector<int>{1, 1});
}

TEST_CASE("unknown device specs name what exists", "[device]") {
  for (const char* spec : {"3", "99999999999999999999", "opencl-fpga", "0,7", "-1"}) {
    INFO(spec);
    try {
      pick_devices(kWithGpu, spec);
      FAIL("accepted");
    } catch (const UserError& e) {
      const std::string what = e.what();
      CHECK(what.find("unknown device") != std::string::npos);
      CHECK(what.find("1: NVIDIA H100") != std::string::npos);
    }
  }
}

TEST_CASE("device types are read in one place", "[device]") {
  CHECK(is_cpu_type("CPU"));
  CHECK(is_cpu_type("CPU ACCELERATOR"));
  CHECK_FALSE(is_cpu_type("GPU"));
  CHECK(is_gpu_type("GPU"));
  CHECK_FALSE(is_gpu_type("ACCELERATOR"));
}

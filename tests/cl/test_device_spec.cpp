// test_device_spec.cpp - what a --device spec picks among a list of devices
// (made up here: no OpenCL needed).
#include <catch2/catch.hpp>

#include "cl/device.hpp"
#include "util/error.hpp"
#include "util/log.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_device_spec {

using namespace clrt;

namespace {

DeviceInfo fake(int index, const std::string& name, const std::string& type, const std::string& platform,
                int platform_index = 0, int device_index = -1) {
  DeviceInfo d;
  d.index = index;
  d.platform_index = platform_index;
  d.device_index = device_index < 0 ? index : device_index;
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

namespace {

// Two platforms, two CPU devices on the first: what `clrt devices` numbers
// 0 (0:0), 1 (0:1), 2 (1:0).
const std::vector<DeviceInfo> kTwoCpus = {fake(0, "pthread-AMD EPYC", "CPU", "Portable Computing Language", 0, 0),
                                          fake(1, "cpu-minimal-AMD EPYC", "CPU", "Portable Computing Language", 0, 1),
                                          fake(2, "llvmpipe", "GPU", "rusticl", 1, 0)};

// The messages log_message() receives while `f` runs.
template <class F>
std::vector<std::string> logged(F f) {
  std::vector<std::string> lines;
  set_log_sink([&](LogLevel, const std::string& m) { lines.push_back(m); });
  try {
    f();
  } catch (...) {
    set_log_sink({});
    throw;
  }
  set_log_sink({});
  return lines;
}

}  // namespace

TEST_CASE("device specs: P:D names a platform's device", "[device]") {
  CHECK(platform_device_id(kTwoCpus[1]) == "0:1");
  CHECK(platform_device_id(kTwoCpus[2]) == "1:0");
  CHECK(indices(pick_devices(kTwoCpus, "0:1")) == std::vector<int>{1});
  CHECK(indices(pick_devices(kTwoCpus, "1:0")) == std::vector<int>{2});
  CHECK(indices(pick_devices(kTwoCpus, "1:0,0:0,1")) == std::vector<int>{2, 0, 1});
  for (const char* bad : {"2:0", "0:2", "0:", ":0", "0:0:0", "a:b"}) {
    INFO(bad);
    CHECK_THROWS_AS(pick_devices(kTwoCpus, bad), UserError);
  }
}

TEST_CASE("a name that matches several devices says which it took, once", "[device]") {
  std::vector<DeviceInfo> picked;
  auto lines = logged([&] { picked = pick_devices(kTwoCpus, "cpu"); });
  CHECK(indices(picked) == std::vector<int>{0});
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].find('\n') == std::string::npos);
  CHECK(lines[0].find("--device cpu matches 2 devices (0 [0:0], 1 [0:1]); using 0 [0:0]: pthread-AMD EPYC") !=
        std::string::npos);
  // One match, an index, P:D or a list of them: nothing to say.
  for (const char* quiet : {"rusticl", "llvmpipe", "0", "0:1", "0,1", "all", ""}) {
    INFO(quiet);
    CHECK(logged([&] { pick_devices(kTwoCpus, quiet); }).empty());
  }
}

}  // namespace test_device_spec

// peak_flops.cpp - a multiply-add throughput kernel, timed like every launch.
#include "eval/peak_flops.hpp"

#include <algorithm>
#include <vector>

#include "cl/kernel_source.hpp"
#include "cl/launch_timing.hpp"
#include "cl/program.hpp"

namespace clrt {
namespace {

// FLOP per work-item and iteration: 8 chains x 16 lanes x 2 (multiply + add).
constexpr double kFlopPerIteration = 8 * 16 * 2;

}  // namespace

PeakFlops measure_peak_flops(const DeviceInfo& dev, int repeat) {
  PeakFlops p;
  try {
    cl::Context ctx(dev.device);
    cl::CommandQueue q(ctx, dev.device, CL_QUEUE_PROFILING_ENABLE);
    cl::Program prog = build_program(ctx, dev, load_kernel_source("peak_flops.cl"),
                                     "-cl-std=CL1.2 -cl-mad-enable -cl-denorms-are-zero");
    cl::Kernel k(prog, "peak_flops");
    // Enough work-items to occupy every compute unit: GPUs need thousands in
    // flight per unit, CPU drivers run work-groups on worker threads.
    const bool cpu = is_cpu_type(dev.type);
    const size_t items = size_t(std::max<cl_uint>(1, dev.compute_units)) * (cpu ? 64 : 2048);
    cl::Buffer out(ctx, CL_MEM_WRITE_ONLY, items * sizeof(float));
    k.setArg(0, out);
    k.setArg(1, 0.9999f);
    k.setArg(2, 0.001f);
    auto launch = [&](int iterations) {
      k.setArg(3, cl_int(iterations));
      return run_timed(q, k, cl::NDRange(items), cl::NullRange);
    };
    // Calibrate: grow the iteration count until a launch takes >= 20 ms.
    int iterations = 64;
    LaunchTime t = launch(iterations);  // also the warm-up
    while (t.ms < 20 && iterations < (1 << 22)) {
      iterations *= t.ms > 0.5 ? std::max(2, int(20 / t.ms) + 1) : 8;
      iterations = std::min(iterations, 1 << 22);
      t = launch(iterations);
    }
    std::vector<double> ms;
    for (int i = 0; i < std::max(1, repeat); ++i) {
      t = launch(iterations);
      ms.push_back(t.ms);
      p.from_events = p.from_events && t.from_events;
    }
    p.launch_ms = summarize(ms);
    p.gflops = kFlopPerIteration * double(items) * iterations / (p.launch_ms.min * 1e6);
    p.measured = p.launch_ms.min > 0;
    if (!p.measured) p.note = "the peak kernel's launches took no measurable time";
  } catch (const cl::Error& e) {
    p.note = "the peak kernel failed: " + describe(e);
  } catch (const std::exception& e) {
    p.note = std::string("the peak kernel failed: ") + e.what();
  }
  return p;
}

}  // namespace clrt

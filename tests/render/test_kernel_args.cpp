// test_kernel_args.cpp - the render kernels' parameters against the host's
// RenderArg: both come from kernels/clrt_kernel_args.h, and this checks the
// kernels the compiler built (count, order and names, read back through
// -cl-kernel-arg-info), in a build without layers, in one with them and in
// a subsampling one (its two entry points).
#include <catch2/catch.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cl/kernel_source.hpp"
#include "cl/program.hpp"
#include "image/layers.hpp"
#include "render/build_options.hpp"
#include "render/kernel_args.hpp"
#include "scene/sampling.hpp"
#include "test_util.hpp"

namespace test_kernel_args {

using namespace clrt;

TEST_CASE("every built render kernel takes the host's list of arguments, by name and in order",
          "[opencl][kernel_args]") {
  const DeviceInfo dev = clrt_test::test_device();
  const cl::Context ctx(dev.device);
  const Scene scene = clrt_test::load("scenes/cgfs-demo.json");
  const std::string source = load_kernel_source("trace.cl");
  // Without layers, with them, and with each subsampling mode (shade's
  // program has a second entry point).
  for (const auto& [layers, subsample] :
       {std::pair{false, Subsample::Off}, std::pair{true, Subsample::Off}, std::pair{false, Subsample::Shade},
        std::pair{false, Subsample::Interpolate}}) {
    INFO("layers " << layers << ", subsample " << int(subsample));
    KernelConfig cfg;
    cfg.specialize = false;  // (the generic program: the quickest to build)
    cfg.lanes = 1;
    cfg.output.layers = layers ? kAllLayers : 0;
    cfg.subsample = subsample;
    // Not through the cache: a cached binary need not keep the argument info.
    const std::string options = build_options(cfg, scene, 3, dev.fp64) + " -cl-kernel-arg-info";
    const cl::Program program = build_program(ctx, dev, source, options, nullptr, BuildFlags{false, false});
    const std::vector<std::string> names = render_kernel_names(subsample == Subsample::Shade);
    // The program defines these entry points and no other.
    CHECK(program.getInfo<CL_PROGRAM_NUM_KERNELS>() == names.size());
    for (const std::string& kernel_name : names) {
      INFO(kernel_name);
      const cl::Kernel kernel(program, kernel_name.c_str());
      const cl_uint count = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
      REQUIRE(count == render_arg_count(layers));
      for (cl_uint i = 0; i < count; ++i) {
        std::string name = kernel.getArgInfo<CL_KERNEL_ARG_NAME>(i);
        name = name.c_str();  // (some drivers count the terminating zero in the string's size)
        CHECK(name == kRenderArgNames[i]);
      }
    }
  }
}

TEST_CASE("the argument indices follow the list, the layers last", "[kernel_args]") {
  // Every index but the layers' is the same in every build: the host sets
  // them without asking which build it holds.
  CHECK(static_cast<cl_uint>(RenderArg::params) == 0);
  CHECK(static_cast<cl_uint>(RenderArg::layers) == render_arg_count(false));
  CHECK(render_arg_count(true) == render_arg_count(false) + 1);
  CHECK(std::string(kRenderArgNames[static_cast<size_t>(RenderArg::tile_h)]) == "tile_h");
  CHECK(kRenderArgKinds[static_cast<size_t>(RenderArg::tile_h)] == RenderArgKind::integer);
  CHECK(kRenderArgKinds[static_cast<size_t>(RenderArg::planes)] == RenderArgKind::buffer);
}

}  // namespace test_kernel_args

// kernel_args.hpp - the render kernels: their names, and their arguments by
// name: the host's side of the one list both sides expand
// (kernels/clrt_kernel_args.h). Setting an argument names it,
// set_arg<RenderArg::planes>(kernel, buffer), and the kind of value the list
// gives it is checked when compiling.
#pragma once
#include <cstddef>
#include <iterator>
#include <string>
#include <vector>

#include "cl/cl.hpp"
#include "clrt_kernel_args.h"

namespace clrt {

// The entry points a program defines (kernels/trace.cl): render, and with
// shade subsampling camera_hits too, its first launch. All of them take the
// same arguments.
inline std::vector<std::string> render_kernel_names(bool shade_subsampling) {
  if (shade_subsampling) return {"camera_hits", "render"};
  return {"render"};
}

// The kernels' argument indices, in the list's order.
enum class RenderArg : cl_uint {
#define CLRT_ARG_ENUMERATOR(name, type, kind) name,
  CLRT_RENDER_ARGS(CLRT_ARG_ENUMERATOR, CLRT_ARG_ENUMERATOR)
#undef CLRT_ARG_ENUMERATOR
};

// What the host passes for an argument (the list's third field).
enum class RenderArgKind { buffer, integer };

inline constexpr RenderArgKind kRenderArgKinds[] = {
#define CLRT_ARG_KIND(name, type, kind) RenderArgKind::kind,
    CLRT_RENDER_ARGS(CLRT_ARG_KIND, CLRT_ARG_KIND)
#undef CLRT_ARG_KIND
};

// The arguments' names, as the kernel's parameters are named.
inline constexpr const char* kRenderArgNames[] = {
#define CLRT_ARG_NAME(name, type, kind) #name,
    CLRT_RENDER_ARGS(CLRT_ARG_NAME, CLRT_ARG_NAME)
#undef CLRT_ARG_NAME
};

// The layers buffer is an argument of layer builds only: it must stay last,
// so that every other index is the same in every build.
static_assert(static_cast<size_t>(RenderArg::layers) + 1 == std::size(kRenderArgNames),
              "the layers argument must be the last of CLRT_RENDER_ARGS");

// The number of arguments of a kernel built with or without the layers.
constexpr cl_uint render_arg_count(bool layers) {
  return static_cast<cl_uint>(std::size(kRenderArgNames)) - (layers ? 0 : 1);
}

template <RenderArg arg>
void set_arg(cl::Kernel& kernel, const cl::Buffer& buffer) {
  static_assert(kRenderArgKinds[static_cast<size_t>(arg)] == RenderArgKind::buffer, "this argument is no buffer");
  kernel.setArg(static_cast<cl_uint>(arg), buffer);
}

template <RenderArg arg>
void set_arg(cl::Kernel& kernel, cl_int value) {
  static_assert(kRenderArgKinds[static_cast<size_t>(arg)] == RenderArgKind::integer, "this argument is no integer");
  kernel.setArg(static_cast<cl_uint>(arg), value);
}

}  // namespace clrt

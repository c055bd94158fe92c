// cl.hpp - the one place that configures and includes the OpenCL C++ bindings.
#pragma once
#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"
#endif
#include <CL/opencl.hpp>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <string>

namespace clrt {

// "CL_INVALID_WORK_GROUP_SIZE" for -54, "CL_UNKNOWN_ERROR(-9999)" otherwise.
std::string cl_error_name(cl_int code);
// "OpenCL error CL_INVALID_VALUE (-30) in clCreateBuffer" from a cl::Error.
std::string describe(const cl::Error& e);

}  // namespace clrt

// build_features.hpp - what this build of clrt has: the one place that reads
// CMakeLists.txt's CLRT_LEAN option (docs/guide/lean.md). A lean build has
// OpenCL (and MPI when enabled) only: no OpenImageIO (clrt writes and reads
// PPM and PFM itself), no PLplot charts, no OBJ meshes (tinyobjloader), no
// OpenMP/Embree comparison tracers. CMake picks the source files of each
// side (e.g. plot.cpp or plot_none.cpp); code tests kLeanBuild where one
// file serves both.
#pragma once

namespace clrt {

#if defined(CLRT_LEAN) && CLRT_LEAN
constexpr bool kLeanBuild = true;
#else
constexpr bool kLeanBuild = false;
#endif

// How the stubs of a lean build begin their UserError: "this clrt was built
// with CLRT_LEAN=ON: no ...".
constexpr const char* kLeanBuildNote = "this clrt was built with CLRT_LEAN=ON";

}  // namespace clrt

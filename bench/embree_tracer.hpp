// embree_tracer.hpp - the OpenMP float tracer of omp_tracer.hpp with its
// intersection queries answered by Intel Embree 3 (a BVH built per call;
// spheres as user geometry, triangles as Embree's own):
// the book's ray tracer (Computer Graphics from Scratch, ch. 2-5), built with
// -O3 -march=native -fopenmp. A benchmark comparison for `clrt bench` only,
// never the oracle; its image matches omp_render's (tests/eval/
// test_embree_tracer.cpp). Embree's types stay inside embree_tracer.cpp.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace clrt_bench {

// How the spheres reach Embree.
enum class EmbreeSpheres {
  // RTC_GEOMETRY_TYPE_USER: Embree's BVH, omp_tracer's float sphere test
  // (the book's quadratic). The default: the image is omp_render's.
  User,
  // RTC_GEOMETRY_TYPE_SPHERE_POINT: Embree's own sphere primitive. Its
  // different (geometric) formula changes the image of the book's floor
  // (radius 5000): kept to measure that, see embree_tracer.cpp.
  Builtin,
};

struct EmbreeBuildInfo {
  double device_ms = 0;  // rtcNewDevice (Embree's TBB thread pool)
  double build_ms = 0;   // geometry + rtcCommitScene: the BVH build
  double render_ms = 0;  // the OpenMP loop over rows only: the figure to compare
  int threads = 0;       // OpenMP threads of the render
  size_t spheres = 0;
  size_t triangles = 0;  // RTC_GEOMETRY_TYPE_TRIANGLE
};

// Renders width x height at `depth` into rgb (width*height*3 floats, 0..255
// unclamped, row 0 at the top) with all OpenMP threads, like omp_render.
// Builds the Embree scene once per call; `info` (optional) receives the
// build and render times. Returns the number of threads used. Throws
// std::runtime_error when Embree reports an error.
int embree_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<float>& rgb,
                  EmbreeBuildInfo* info = nullptr, EmbreeSpheres spheres = EmbreeSpheres::User);
// The same as 8-bit RGBA (width*height*4, the canvas rule), like omp_render.
int embree_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<uint8_t>& rgba8,
                  EmbreeBuildInfo* info = nullptr, EmbreeSpheres spheres = EmbreeSpheres::User);

}  // namespace clrt_bench

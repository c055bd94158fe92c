// omp_tracer.hpp - a straightforward OpenMP C++ float implementation of the
// book's ray tracer (Computer Graphics from Scratch, ch. 2-5), built with
// -O3 -march=native -fopenmp. A benchmark comparison for `clrt bench` only:
// it is never used as the oracle (that is host/reference.cpp, in double).
#pragma once
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace clrt_bench {

// Renders width x height at `depth` into rgb (width*height*3 floats, 0..255
// unclamped, row 0 at the top) with all OpenMP threads. Returns the number
// of threads used.
int omp_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<float>& rgb);
// The same as 8-bit RGBA (width*height*4, the canvas rule: what clrt's
// kernel writes for 8-bit outputs).
int omp_render(const clrt::Scene& scene, int width, int height, int depth, std::vector<uint8_t>& rgba8);

// Wakes the OpenMP threads (an empty parallel region): a tracer's frame
// then starts as in frames rendered back to back, its threads still
// spinning from the last (eval/bench.cpp times frames of several tracers
// in turn, with pauses between them).
void omp_warm_threads();

}  // namespace clrt_bench

// omp_render_main.cpp - clrt_omp_render SCENE WIDTH HEIGHT OUT: the OpenMP
// float tracer of `clrt bench` (omp_tracer.hpp) as a whole process, the
// baseline of `clrt render` as a whole process (docs/results/README.md,
// "Start-up"): load the scene, render one frame at the scene's depth, write
// the image the way clrt writes an 8-bit one (the canvas rule of to_u8(),
// then image_file.hpp, which loads the imaging module). A benchmark tool,
// not part of clrt; errors are one line and exit status 2.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "image/image_file.hpp"
#include "omp_tracer.hpp"
#include "scene/scene_json.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SCENE WIDTH HEIGHT OUT\n", argv[0]);
    return 2;
  }
  try {
    const int width = std::stoi(argv[2]), height = std::stoi(argv[3]);
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
      throw std::invalid_argument("WIDTH and HEIGHT must be 1..16384");
    clrt::check_output_format(argv[4]);
    const clrt::Scene scene = clrt::load_scene(argv[1]);
    std::vector<float> rgb;
    clrt_bench::omp_render(scene, width, height, scene.recursion_depth, rgb);
    std::vector<uint8_t> u8(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) u8[i] = clrt::to_u8(double(rgb[i]));
    clrt::write_rgb8(u8, width, height, argv[4]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clrt_omp_render: error: %s\n", e.what());
    return 2;
  }
  return 0;
}

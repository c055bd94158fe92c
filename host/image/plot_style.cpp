// plot_style.cpp - the palette, the colour of a named series and the
// markers of the charts (plot.hpp): the same in the full build (plot.cpp,
// PLplot) and in a lean one (plot_none.cpp): reports call them in either.
#include <cstdint>

#include "image/plot.hpp"

namespace clrt {

PlotColor plot_palette_color(size_t i) {
  // Okabe-Ito (colour-blind friendly) without its yellow, then darker tones and greys.
  static const PlotColor kPalette[] = {{0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.00f, 0.62f, 0.45f},
                                       {0.80f, 0.47f, 0.65f}, {0.90f, 0.62f, 0.00f}, {0.34f, 0.71f, 0.91f},
                                       {0.55f, 0.16f, 0.16f}, {0.40f, 0.40f, 0.40f}, {0.45f, 0.30f, 0.65f},
                                       {0.35f, 0.50f, 0.10f}, {0.10f, 0.10f, 0.10f}, {0.65f, 0.65f, 0.65f}};
  return kPalette[i % (sizeof kPalette / sizeof kPalette[0])];
}

PlotColor plot_color_for_name(const std::string& name) {
  // Fixed entries: the accuracy variants (render/precision, eval/accuracy),
  // then the series of the sweep and scaling charts.
  static const std::pair<const char*, size_t> kNamed[] = {{"naive", 1},
                                                          {"stable", 4},
                                                          {"robust", 0},
                                                          {"fast", 3},
                                                          {"fp64", 2},
                                                          {"robust+subsample-shade", 5},
                                                          {"robust+subsample-interpolate", 8},
                                                          {"reference", 10},
                                                          {"clrt", 0},
                                                          {"Embree", 1},
                                                          {"OpenMP", 2}};
  for (const auto& kv : kNamed)
    if (name == kv.first) return plot_palette_color(kv.second);
  // FNV-1a: the same on every platform and run (std::hash need not be).
  uint32_t h = 2166136261u;
  for (unsigned char c : name) h = (h ^ c) * 16777619u;
  return plot_palette_color(h % 12);
}

const char* plot_marker(size_t i) {
  static const char* const kMarkers[] = {"●", "■", "▲", "◆", "▼", "✚", "✖", "★"};
  return kMarkers[i % plot_marker_count()];
}

size_t plot_marker_count() {
  return 8;
}

}  // namespace clrt

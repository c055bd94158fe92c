// edge_scene.hpp - a scene whose supersampled pixels are known exactly: a
// sphere lit by ambient light of intensity 1 only (every hit sample has
// exactly the sphere's colour, every miss the background's), whose
// silhouette crosses one pixel between two columns of its sub-pixel samples,
// so that exactly k of the N x N samples hit and the pixel is
// (k * colour + (N^2 - k) * background) / N^2. Used by the reference's and
// the kernel's supersampling tests: the same pixel values in both engines
// say that they place the samples by the same rule.
#pragma once
#include <cmath>
#include <cstdio>
#include <string>

#include "scene/scene_json.hpp"

namespace clrt_test {

struct EdgeScene {
  static constexpr int kWidth = 64, kHeight = 64;
  // The sphere (centre (0, 0, 10)) is seen as a disc of radius
  // kEdgePixels pixels around the canvas origin; pixel (kEdgeX, 0) holds its
  // right-hand edge, 0.07 px right of the pixel's centre. Over the sample
  // rows (|y| < 0.5 px) the silhouette stays within 0.0065 px of that.
  static constexpr double kEdgePixels = 20.07;
  static constexpr int kEdgeX = 20;
  static constexpr double kColour[3] = {200, 100, 40};
  static constexpr double kBackground[3] = {0, 0, 250};

  static clrt::Scene scene() {
    // viewport 1 x 1 at d = 1: a pixel is 1/kWidth of the viewport, and a
    // sphere at distance Z with radius r has the angular radius whose
    // tangent rho satisfies rho^2 = r^2 / (Z^2 - r^2).
    const double rho = kEdgePixels / kWidth, z = 10;
    const double r = rho * z / std::sqrt(1 + rho * rho);
    char radius[64];
    std::snprintf(radius, sizeof radius, "%.17g", r);
    return clrt::parse_scene(std::string(R"({"background": [0, 0, 250], "recursion_depth": 3,
        "spheres": [{"center": [0, 0, 10], "radius": )") +
                                 radius + R"(, "color": [200, 100, 40]}],
        "lights": [{"type": "ambient", "intensity": 1}]})",
                             "edge");
  }
  // Column and row of the canvas pixel (x, 0).
  static int col(int x) { return kWidth / 2 + x; }
  static int row() { return kHeight / 2 - 1; }
  // How many of the N x N samples of pixel (kEdgeX, 0) hit the sphere: the
  // columns whose offset o_i = (i + 0.5) / N - 0.5 lies left of the edge,
  // N samples each. -1 when a sample column lies within 0.02 px of the edge
  // (too close to call: N = 1..5 are clear by at least 0.055 px).
  static int hits(int n) {
    int k = 0;
    for (int i = 0; i < n; ++i) {
      const double o = (i + 0.5) / n - 0.5;
      const double margin = kEdgePixels - kEdgeX - o;
      if (std::fabs(margin) < 0.02) return -1;
      if (margin > 0) k += n;
    }
    return k;
  }
  // The exact mean of pixel (kEdgeX, 0), channel c.
  static double expected(int n, int c) {
    const int k = hits(n);
    return (k * kColour[c] + (n * n - k) * kBackground[c]) / (n * n);
  }
};

}  // namespace clrt_test

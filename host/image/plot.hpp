// plot.hpp - small PNG (or any OpenImageIO format) charts: scatter and line
// series with axes, ticks, labels, optional log axes and a legend, drawn with
// OpenImageIO's ImageBufAlgo. Used by `clrt accuracy --plot` and the sweeps.
#pragma once
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace clrt {

struct Series {
  Series() = default;
  Series(std::string n, std::vector<double> xs, std::vector<double> ys)
      : name(std::move(n)), x(std::move(xs)), y(std::move(ys)) {}

  std::string name;                 // legend entry ("" = not in the legend)
  std::vector<double> x, y;         // same length; non-finite points are skipped
  bool lines = false;               // connect consecutive points
  bool markers = true;              // draw a marker at each point
  std::vector<std::string> labels;  // optional per-point text drawn beside the marker
  // RGB in [0, 1]; a negative first component picks the next palette colour.
  std::array<float, 3> color{-1.f, 0.f, 0.f};
};

struct PlotOptions {
  int width = 900, height = 600;      // pixels
  bool log_x = false, log_y = false;  // points <= 0 on a log axis are skipped
  bool legend = true;
  bool x_from_zero = false, y_from_zero = false;  // linear axes: include 0
  int font_size = 15;
};

// Draws the chart and writes it (format from the extension, atomically, like
// every other image clrt writes). Throws UserError for an unwritable path,
// std::invalid_argument for series whose x and y lengths differ. If no font is
// found the chart is still written, without text (and a warning is logged).
void write_plot(const std::string& path, const std::string& title, const std::string& xlabel, const std::string& ylabel,
                const std::vector<Series>& series, const PlotOptions& options = {});

// Tick positions for [lo, hi]: "nice" steps 1/2/5 x 10^k (linear), or powers
// of ten with 2 and 5 in between when the range spans few decades (log).
// Exposed for tests.
std::vector<double> plot_ticks(double lo, double hi, bool log_scale);

}  // namespace clrt

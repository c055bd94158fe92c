// plot.hpp - charts drawn with PLplot (Debian's libplplot-dev, in-process)
// through its cairo devices: PNG, SVG or PDF, picked by the file's
// extension. Scatter and line series with min/max error bars, per-series
// colour and marker, linear or log axes, integer ticks, one or more panels
// stacked in one file and a legend outside the data area. Used by
// `clrt accuracy --plot`, `clrt sweep --plot` and `clrt scaling --plot`.
#pragma once
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace clrt {

using PlotColor = std::array<float, 3>;  // RGB in [0, 1]

struct Series {
  Series() = default;
  Series(std::string n, std::vector<double> xs, std::vector<double> ys)
      : name(std::move(n)), x(std::move(xs)), y(std::move(ys)) {}

  // Legend entry ("" = not in the legend). A series without points is a
  // legend entry only: a line if `lines`, its marker if `markers`.
  std::string name;
  std::vector<double> x, y;  // same length; non-finite points are skipped
  // Optional error bars: both empty, or both as long as y (a bar from
  // y_lo[i] to y_hi[i], e.g. the min and max of the timed runs).
  std::vector<double> y_lo, y_hi;
  std::vector<double> x_lo, x_hi;   // the same along x
  bool lines = false;               // connect consecutive points
  bool markers = true;              // draw a marker at each point
  std::vector<std::string> labels;  // optional per-point text drawn beside the marker
  // A negative first component picks the palette colour of the series'
  // position (plot_palette_color); see plot_color_for_name for a fixed one.
  PlotColor color{-1.f, 0.f, 0.f};
  int marker = -1;  // plot_marker(i) index; < 0: the series' position
};

struct PlotOptions {
  int width = 1000, height = 600;                 // pixels (PNG); SVG and PDF scale alike
  bool log_x = false, log_y = false;              // points <= 0 on a log axis are skipped
  bool legend = true;                             // right of the data area, outside it
  bool x_from_zero = false, y_from_zero = false;  // linear axes: include 0
  bool integer_x = false;                         // x ticks at whole numbers only (depths, counts)
};

// One chart of a figure: panels are stacked top to bottom in one file and
// share the figure's size; the options' width/height are the first panel's.
struct PlotPanel {
  std::string title, xlabel, ylabel;
  std::vector<Series> series;
  PlotOptions options;
};

// The file formats a plot can be written as, by extension (lower case):
// {"png", "svg", "pdf"}.
const std::vector<std::string>& plot_extensions();

// Throws UserError unless `path` can be written as a plot: the checks of
// check_output() and a known extension (plot_extensions()). Run it before
// the measurement, so a bad --plot fails in milliseconds.
void check_plot_output(const std::string& path);

// Draws the chart and writes it (format from the extension; PLplot writes a
// private scratch file that is then written through write_output(), so
// atomically and symlink-safely like every other file clrt writes). Throws
// UserError for an unwritable path or an unknown extension,
// std::invalid_argument for series whose x, y (and error bar) lengths differ.
void write_plot(const std::string& path, const std::string& title, const std::string& xlabel, const std::string& ylabel,
                const std::vector<Series>& series, const PlotOptions& options = {});
void write_plot(const std::string& path, const std::vector<PlotPanel>& panels);

// The palette (Okabe-Ito, colour-blind friendly, then greys), cycled.
PlotColor plot_palette_color(size_t i);
// A colour that depends on `name` only: the palette entry of a known name
// (the accuracy variants, the reference, the comparison tracers), else one
// picked by a hash of the name. The same series has the same colour in every
// chart, whatever else is plotted beside it.
PlotColor plot_color_for_name(const std::string& name);
// Marker glyphs (filled circle, square, triangle, diamond, ...), cycled;
// plot_marker_count() distinct ones.
const char* plot_marker(size_t i);
size_t plot_marker_count();

}  // namespace clrt

// plot.cpp - charts: the layout here, the drawing with OpenImageIO's
// ImageBufAlgo in the imaging module (image_io.hpp; see plot.hpp).
#include "image/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "util/log.hpp"

namespace clrt {

namespace {

using imageio::AlignX;
using imageio::AlignY;
using imageio::Canvas;
using Rgb = imageio::Rgb;
const Rgb kBlack{0, 0, 0}, kGrid{0.88f, 0.88f, 0.88f}, kWhite{1, 1, 1}, kAxis{0.25f, 0.25f, 0.25f};
// A colour-blind-friendly palette (Okabe-Ito), then greys.
const Rgb kPalette[] = {{0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.00f, 0.62f, 0.45f}, {0.80f, 0.47f, 0.65f},
                        {0.90f, 0.62f, 0.00f}, {0.34f, 0.71f, 0.91f}, {0.94f, 0.89f, 0.26f}, {0.40f, 0.40f, 0.40f}};

// The font: DejaVu Sans (Debian's fonts-dejavu-core), else OpenImageIO's
// default search; "" with ok=false when neither is found.
struct Font {
  std::string name;
  bool ok = false;
};
const Font& font() {
  static const Font f = [] {
    for (const char* name : {"DejaVuSans", "DejaVu Sans", ""})
      if (imageio::module().text_size("0", 12, name).defined) return Font{name, true};
    log_message(LogLevel::Warning, "no font found for plot text (install fonts-dejavu-core); drawing without text");
    return Font{"", false};
  }();
  return f;
}

void text(Canvas& img, int x, int y, const std::string& s, int size, const Rgb& color, AlignX ax = AlignX::Left,
          AlignY ay = AlignY::Baseline) {
  if (s.empty() || !font().ok) return;
  img.text(x, y, s, size, font().name, color, ax, ay);
}

int text_width(const std::string& s, int size) {
  if (s.empty() || !font().ok) return 0;
  const imageio::TextBox r = imageio::module().text_size(s, size, font().name);
  return r.defined ? r.width : 0;
}

// Text rotated 90 degrees counter-clockwise, centred on (cx, cy).
void vertical_text(Canvas& img, int cx, int cy, const std::string& s, int size, const Rgb& color) {
  if (s.empty() || !font().ok) return;
  img.vertical_text(cx, cy, s, size, font().name, color);
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  std::string s = buf;
  for (const char* from : {"e+0", "e+", "e-0"}) {
    auto p = s.find(from);
    if (p != std::string::npos) {
      s.replace(p, std::string(from).size(), from[1] == '-' ? "e-" : "e");
      break;
    }
  }
  return s;
}

// One axis: data range and the mapping to pixels.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // in data units
  double tr(double v) const { return log ? std::log10(v) : v; }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0); }
  // Fraction of the axis, 0 at lo, 1 at hi.
  double frac(double v) const { return (tr(v) - tr(lo)) / (tr(hi) - tr(lo)); }
};

Axis make_axis(const std::vector<Series>& series, bool use_x, bool log, bool from_zero) {
  Axis a;
  a.log = log;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      double v = use_x ? s.x[i] : s.y[i];
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !a.usable(v)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(lo <= hi)) lo = log ? 1 : 0, hi = log ? 10 : 1;  // no data
  if (!log && from_zero) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  double tlo = a.tr(lo), thi = a.tr(hi);
  if (thi - tlo < 1e-12 * std::max(1.0, std::fabs(thi))) {
    double w = log ? 0.5 : std::max(1e-12, std::fabs(thi) * 0.1 + (thi == 0 ? 1 : 0));
    tlo -= w, thi += w;
  }
  double pad = 0.06 * (thi - tlo);
  bool keep_zero = !log && from_zero && lo == 0;
  tlo = keep_zero ? tlo : tlo - pad;
  thi += pad;
  a.lo = log ? std::pow(10.0, tlo) : tlo;
  a.hi = log ? std::pow(10.0, thi) : thi;
  return a;
}

void marker(Canvas& img, int x, int y, int shape, const Rgb& c) {
  const int h = 4;
  switch (shape % 6) {
    case 0:
      img.box(x - h, y - h, x + h, y + h, c, true);
      break;
    case 1:
      img.box(x - h, y - h, x + h, y + h, c, false);
      img.box(x - h + 1, y - h + 1, x + h - 1, y + h - 1, c, false);
      break;
    case 2:
      for (int d = -1; d <= 1; ++d) {
        img.line(x - h - 1, y + d, x + h + 1, y + d, c);
        img.line(x + d, y - h - 1, x + d, y + h + 1, c);
      }
      break;
    case 3:
      for (int d = 0; d <= 1; ++d) {
        img.line(x - h + d, y - h, x + h + d, y + h, c);
        img.line(x - h + d, y + h, x + h + d, y - h, c);
      }
      break;
    case 4:  // filled diamond
      for (int d = -h - 1; d <= h + 1; ++d) {
        int w = h + 1 - std::abs(d);
        img.line(x - w, y + d, x + w, y + d, c);
      }
      break;
    default:  // hollow triangle
      for (int d = 0; d <= 1; ++d) {
        img.line(x - h - 1, y + h - d, x + h + 1, y + h - d, c);
        img.line(x - h - 1 + d, y + h, x + d, y - h - 1, c);
        img.line(x + h + 1 - d, y + h, x - d, y - h - 1, c);
      }
  }
}

}  // namespace

std::vector<double> plot_ticks(double lo, double hi, bool log_scale) {
  std::vector<double> out;
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) return out;
  if (log_scale && lo > 0) {
    const double decades = std::log10(hi / lo);
    const int e0 = int(std::floor(std::log10(lo))), e1 = int(std::ceil(std::log10(hi)));
    const int every = std::max(1, int(std::ceil(decades / 8)));
    const double tol = 1e-9;
    for (int e = e0; e <= e1; ++e) {
      if (every > 1 && (e - e0) % every) continue;
      for (double m : {1.0, 2.0, 5.0}) {
        if (m != 1.0 && decades > 2.5) continue;
        double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - tol) && v <= hi * (1 + tol)) out.push_back(v);
      }
    }
    if (out.size() >= 2) return out;
    out.clear();  // less than a decade: fall back to linear ticks
  }
  const double raw = (hi - lo) / 6;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm < 1.5 ? 1 : norm < 3.5 ? 2 : norm < 7.5 ? 5 : 10) * mag;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    out.push_back(std::fabs(v) < step * 1e-9 ? 0.0 : v);
  return out;
}

void write_plot(const std::string& path, const std::string& title, const std::string& xlabel, const std::string& ylabel,
                const std::vector<Series>& series, const PlotOptions& opt) {
  for (const auto& s : series)
    if (s.x.size() != s.y.size())
      throw std::invalid_argument("write_plot: series \"" + s.name + "\": x/y sizes differ");
  const int W = std::max(200, opt.width), H = std::max(150, opt.height), fs = std::max(8, opt.font_size);
  const Axis ax = make_axis(series, true, opt.log_x, opt.x_from_zero);
  const Axis ay = make_axis(series, false, opt.log_y, opt.y_from_zero);
  const std::vector<double> xt = plot_ticks(ax.lo, ax.hi, ax.log), yt = plot_ticks(ay.lo, ay.hi, ay.log);

  // Plot area: room on the left for the y tick labels and the rotated label.
  int ytw = 0;
  for (double v : yt) ytw = std::max(ytw, text_width(tick_label(v), fs));
  const int left = 20 + (ylabel.empty() ? 0 : fs + 10) + ytw + 8, right = W - 24;
  const int top = title.empty() ? 20 : 2 * fs + 16, bottom = H - (xlabel.empty() ? 2 * fs : 3 * fs + 16);
  auto px = [&](double v) { return left + int(std::lround(ax.frac(v) * (right - left))); };
  auto py = [&](double v) { return bottom - int(std::lround(ay.frac(v) * (bottom - top))); };

  const std::unique_ptr<Canvas> canvas = imageio::module().canvas(W, H, kWhite);
  Canvas& img = *canvas;
  // Grid and ticks.
  for (double v : xt) {
    int x = px(v);
    img.line(x, top, x, bottom, kGrid);
    img.line(x, bottom, x, bottom + 5, kAxis);
    text(img, x, bottom + 8, tick_label(v), fs, kBlack, AlignX::Center, AlignY::Top);
  }
  for (double v : yt) {
    int y = py(v);
    img.line(left, y, right, y, kGrid);
    img.line(left - 5, y, left, y, kAxis);
    text(img, left - 8, y, tick_label(v), fs, kBlack, AlignX::Right, AlignY::Center);
  }
  img.box(left, top, right, bottom, kAxis, false);
  text(img, W / 2, fs + 10, title, fs + 3, kBlack, AlignX::Center, AlignY::Center);
  text(img, (left + right) / 2, H - 10, xlabel, fs, kBlack, AlignX::Center, AlignY::Bottom);
  vertical_text(img, 12 + fs / 2, (top + bottom) / 2, ylabel, fs, kBlack);

  // Series.
  std::vector<Rgb> colors;
  size_t next = 0;
  for (const auto& s : series)
    colors.push_back(s.color[0] >= 0 ? s.color : kPalette[next++ % (sizeof kPalette / sizeof kPalette[0])]);
  std::vector<std::array<int, 4>> placed;  // label boxes drawn so far (x0, y0, x1, y1)
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    auto ok = [&](size_t i) { return ax.usable(s.x[i]) && ay.usable(s.y[i]); };
    if (s.lines)
      for (size_t i = 1; i < s.x.size(); ++i) {
        if (!ok(i - 1) || !ok(i)) continue;
        for (int d = 0; d <= 1; ++d)
          img.line(px(s.x[i - 1]), py(s.y[i - 1]) + d, px(s.x[i]), py(s.y[i]) + d, colors[k]);
      }
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!ok(i)) continue;
      if (s.markers) marker(img, px(s.x[i]), py(s.y[i]), int(k), colors[k]);
      if (i < s.labels.size() && !s.labels[i].empty()) {
        // Right of the marker, or left of it when that would leave the plot;
        // moved up or down when it would overlap a label already drawn.
        const int w = text_width(s.labels[i], fs - 3), h = fs;
        const bool flip = px(s.x[i]) + 10 + w > right - 2;
        const int x0 = flip ? px(s.x[i]) - 10 - w : px(s.x[i]) + 10;
        int base = py(s.y[i]) - 6;
        for (int shift : {0, -h, h + 4, -2 * h, 2 * h + 4, -3 * h}) {
          const int b = py(s.y[i]) - 6 + shift;
          bool clash = b - h < top || b > bottom;
          for (const auto& r : placed) clash |= x0 < r[2] && r[0] < x0 + w && b - h < r[3] && r[1] < b;
          if (!clash) {
            base = b;
            break;
          }
        }
        placed.push_back({x0, base - h, x0 + w, base});
        text(img, x0, base, s.labels[i], fs - 3, colors[k]);
      }
    }
  }

  // Legend, top right inside the plot area.
  if (opt.legend) {
    int n = 0, tw = 0;
    for (const auto& s : series)
      if (!s.name.empty()) ++n, tw = std::max(tw, text_width(s.name, fs));
    if (n > 0) {
      const int row = fs + 8, bw = tw + 44, bh = n * row + 8;
      // The corner of the plot area that covers the fewest points.
      int x0 = right - bw - 8, y0 = top + 8;
      size_t fewest = SIZE_MAX;
      for (int corner = 0; corner < 4; ++corner) {
        const int cx = corner % 2 ? left + 8 : right - bw - 8, cy = corner < 2 ? top + 8 : bottom - bh - 8;
        size_t covered = 0;
        for (const auto& s : series)
          for (size_t i = 0; i < s.x.size(); ++i) {
            if (!ax.usable(s.x[i]) || !ay.usable(s.y[i])) continue;
            const int x = px(s.x[i]), y = py(s.y[i]);
            covered += x >= cx - 12 && x <= cx + bw + 12 && y >= cy - 12 && y <= cy + bh + 12;
          }
        if (covered < fewest) fewest = covered, x0 = cx, y0 = cy;
      }
      img.box(x0, y0, x0 + bw, y0 + bh, kWhite, true);
      img.box(x0, y0, x0 + bw, y0 + bh, kAxis, false);
      int r = 0;
      for (size_t k = 0; k < series.size(); ++k) {
        if (series[k].name.empty()) continue;
        int y = y0 + 4 + r * row + row / 2;
        if (series[k].lines) img.line(x0 + 6, y, x0 + 30, y, colors[k]);
        marker(img, x0 + 18, y, int(k), colors[k]);
        text(img, x0 + 38, y, series[k].name, fs, kBlack, AlignX::Left, AlignY::Center);
        ++r;
      }
    }
  }

  write_rgb8(img.rgb8(), W, H, path);
}

}  // namespace clrt

// plot.cpp - charts with PLplot's C API and its cairo devices (pngcairo,
// svgcairo, pdfcairo; Debian's plplot-driver-cairo). PLplot keeps global
// state, so one chart is drawn at a time (a mutex), on a stream of its own.
#include "image/plot.hpp"

#include <plplot.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "image/image_file.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace clrt {

namespace {

// The PLplot device that writes `ext`.
std::string plot_device(const std::string& ext) {
  return ext + "cairo";
}

// Whether PLplot lists `device` among its file devices (the cairo driver is
// a package of its own, plplot-driver-cairo).
bool device_available(const std::string& device) {
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  std::vector<const char*> menu_v(128), names_v(128);
  const char** menu = menu_v.data();
  const char** names = names_v.data();
  int n = int(names_v.size());
  plgFileDevs(&menu, &names, &n);
  for (int i = 0; i < n; ++i)
    if (names[i] && device == names[i]) return true;
  return false;
}

// PLplot calls exit() after a fatal error; this handler makes that one
// `clrt: error:` line with status 2 (docs/guide/errors.md).
int plot_exit_handler(const char* message) {
  std::fprintf(stderr, "clrt: error: plot: %s\n", message && *message ? message : "PLplot failed");
  return kExitBadInput;
}

struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // window, in transformed units (log10 on a log axis)
  double tr(double v) const { return log ? std::log10(v) : v; }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

Axis make_axis(const std::vector<Series>& series, bool use_x, bool log, bool from_zero, bool integer) {
  Axis a;
  a.log = log;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto take = [&](double v) {
    if (!a.usable(v)) return;
    lo = std::min(lo, a.tr(v));
    hi = std::max(hi, a.tr(v));
  };
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if (use_x) {
        take(s.x[i]);
        if (!s.x_lo.empty()) take(s.x_lo[i]), take(s.x_hi[i]);
      } else {
        take(s.y[i]);
        if (!s.y_lo.empty()) take(s.y_lo[i]), take(s.y_hi[i]);
      }
    }
  if (!(lo <= hi)) lo = 0, hi = 1;  // no data
  if (!log && from_zero) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  if (hi - lo < 1e-12 * std::max(1.0, std::fabs(hi))) {
    const double w = log ? 0.5 : std::max(1e-12, std::fabs(hi) * 0.1 + (hi == 0 ? 1 : 0));
    lo = !log && from_zero && lo == 0 ? 0 : lo - w;  // all zero: [0, 1], not [-1, 1]
    hi += w;
  }
  if (integer && !log) {  // whole numbers with half a step of room: ticks stay on them
    a.lo = std::floor(lo) - 0.5;
    a.hi = std::ceil(hi) + 0.5;
    return a;
  }
  const double pad = 0.06 * (hi - lo);
  a.lo = lo - pad;  // (a zero line stays off the frame)
  a.hi = hi + pad;
  return a;
}

// The tick step for whole-number ticks over [lo, hi]: 1, 2, 5, 10, ...
double integer_step(double lo, double hi) {
  const double raw = (hi - lo) / 10;
  if (raw <= 1) return 1;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  return std::max(1.0, (norm <= 1 ? 1 : norm <= 2 ? 2 : norm <= 5 ? 5 : 10) * mag);
}

PLINT to255(float c) {
  return PLINT(std::lround(std::clamp(c, 0.f, 1.f) * 255));
}

// cmap0 indices: 0 background, 1 axes and text, 2 grid, then one per series.
// Character height in PLplot's millimetres: the same on every page size.
constexpr double kCharMm = 4.2;
constexpr PLINT kBackground = 0, kInk = 1, kGrid = 2, kFirstSeries = 3;

struct Layout {
  double left, right, bottom, top;  // the data area, normalised page coordinates
};

// `s` cut to `n` characters (UTF-8 sequences kept whole), "..." marking a cut.
std::string shorten(const std::string& s, size_t n) {
  if (s.size() <= n || n < 4) return s;
  size_t end = n - 3;
  while (end > 0 && (static_cast<unsigned char>(s[end]) & 0xC0) == 0x80) --end;
  return s.substr(0, end) + "...";
}

void draw_panel(const PlotPanel& p, PLINT first_color, const Layout& box, double text_scale, size_t legend_chars) {
  const PlotOptions& o = p.options;
  const Axis ax = make_axis(p.series, true, o.log_x, o.x_from_zero, o.integer_x);
  const Axis ay = make_axis(p.series, false, o.log_y, o.y_from_zero, false);
  plschr(kCharMm, text_scale);
  plvpor(box.left, box.right, box.bottom, box.top);
  plwind(ax.lo, ax.hi, ay.lo, ay.hi);
  const double xtick = o.integer_x && !o.log_x ? integer_step(ax.lo, ax.hi) : 0;
  const PLINT nxsub = o.integer_x && !o.log_x ? 1 : 0;
  const std::string xl = o.log_x ? "l" : "", yl = o.log_y ? "l" : "";
  // Grid first (light, under the data), then the frame, ticks and numbers.
  plcol0(kGrid);
  plwidth(1);
  plbox(("g" + xl).c_str(), xtick, nxsub, ("g" + yl).c_str(), 0, 0);
  plcol0(kInk);
  plbox(("bcnst" + xl).c_str(), xtick, nxsub, ("bcnstv" + yl).c_str(), 0, 0);
  plmtex("b", 2.8, 0.5, 0.5, p.xlabel.c_str());
  plmtex("l", 4.2, 0.5, 0.5, p.ylabel.c_str());
  plschr(kCharMm, text_scale * 1.15);
  plmtex("t", 1.2, 0.0, 0.0, p.title.c_str());
  plschr(kCharMm, text_scale);

  std::vector<PLINT> opt, text_col, line_col, line_style, sym_col, sym_num;
  std::vector<PLFLT> line_width, sym_scale;
  std::vector<std::string> texts, symbols;
  const double label_dx = 0.012 * (ax.hi - ax.lo);
  for (size_t k = 0; k < p.series.size(); ++k) {
    const Series& s = p.series[k];
    const PLINT color = first_color + PLINT(k);
    const char* glyph = plot_marker(s.marker >= 0 ? size_t(s.marker) : k);
    std::vector<PLFLT> x, y, lo, hi, xlo, xhi;
    std::vector<size_t> at;
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !ax.usable(s.x[i]) || !ay.usable(s.y[i])) continue;
      x.push_back(ax.tr(s.x[i]));
      y.push_back(ay.tr(s.y[i]));
      if (!s.y_lo.empty()) {
        lo.push_back(ay.usable(s.y_lo[i]) ? ay.tr(s.y_lo[i]) : y.back());
        hi.push_back(ay.usable(s.y_hi[i]) ? ay.tr(s.y_hi[i]) : y.back());
      }
      if (!s.x_lo.empty()) {
        xlo.push_back(ax.usable(s.x_lo[i]) ? ax.tr(s.x_lo[i]) : x.back());
        xhi.push_back(ax.usable(s.x_hi[i]) ? ax.tr(s.x_hi[i]) : x.back());
      }
      at.push_back(i);
    }
    plcol0(color);
    if (!x.empty()) {
      if (!lo.empty()) {
        plwidth(1.5);
        plerry(PLINT(x.size()), x.data(), lo.data(), hi.data());
      }
      if (!xlo.empty()) {
        plwidth(1.5);
        plerrx(PLINT(x.size()), xlo.data(), xhi.data(), y.data());
      }
      if (s.lines && x.size() > 1) {
        plwidth(2);
        plline(PLINT(x.size()), x.data(), y.data());
      }
      if (s.markers) plstring(PLINT(x.size()), x.data(), y.data(), glyph);
      plcol0(kInk);
      plschr(kCharMm, text_scale * 0.8);
      for (size_t j = 0; j < at.size(); ++j)
        if (at[j] < s.labels.size() && !s.labels[at[j]].empty())
          plptex(x[j] + label_dx, y[j], ax.hi - ax.lo, ay.hi - ay.lo, 0, s.labels[at[j]].c_str());
      plschr(kCharMm, text_scale);
    }
    if (s.name.empty() || !o.legend) continue;
    opt.push_back((s.lines ? PL_LEGEND_LINE : 0) | (s.markers ? PL_LEGEND_SYMBOL : 0));
    if (opt.back() == 0) opt.back() = PL_LEGEND_LINE;
    texts.push_back(shorten(s.name, legend_chars));
    text_col.push_back(kInk);
    line_col.push_back(color);
    line_style.push_back(1);
    line_width.push_back(2);
    sym_col.push_back(color);
    sym_scale.push_back(1);
    sym_num.push_back(1);
    symbols.push_back(glyph);
  }
  plwidth(1);
  if (texts.empty()) return;
  std::vector<const char*> tp, sp;
  for (auto& t : texts) tp.push_back(t.c_str());
  for (auto& t : symbols) sp.push_back(t.c_str());
  std::vector<PLINT> none(texts.size(), 0);
  std::vector<PLFLT> nonef(texts.size(), 0);
  PLFLT w = 0, h = 0;
  pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
           PL_POSITION_RIGHT | PL_POSITION_OUTSIDE | PL_POSITION_VIEWPORT, 0.02, 0.0, 0.05, kBackground, kInk, 1, 0, 1,
           PLINT(texts.size()), opt.data(), 0.8, 0.75, 2.0, 0.0, text_col.data(), tp.data(), none.data(), none.data(),
           nonef.data(), nonef.data(), line_col.data(), line_style.data(), line_width.data(), sym_col.data(),
           sym_scale.data(), sym_num.data(), sp.data());
}

}  // namespace

const std::vector<std::string>& plot_extensions() {
  static const std::vector<std::string> v{"png", "svg", "pdf"};
  return v;
}

void check_plot_output(const std::string& path) {
  const OutputTarget target = check_output(path, "plot");
  const std::string ext = lowercase_extension(target.kind == OutputKind::File ? path : target.path);
  const auto& known = plot_extensions();
  if (std::find(known.begin(), known.end(), ext) == known.end())
    throw UserError("plot " + path + ": unknown format" + (ext.empty() ? "" : " '." + ext + "'") +
                    " (the extension picks it: .png, .svg or .pdf)");
  if (!device_available(plot_device(ext)))
    throw UserError("plot " + path + ": PLplot has no " + plot_device(ext) +
                    " device (install Debian's plplot-driver-cairo)");
}

void write_plot(const std::string& path, const std::string& title, const std::string& xlabel, const std::string& ylabel,
                const std::vector<Series>& series, const PlotOptions& options) {
  write_plot(path, {PlotPanel{title, xlabel, ylabel, series, options}});
}

void write_plot(const std::string& path, const std::vector<PlotPanel>& panels) {
  for (const auto& p : panels)
    for (const auto& s : p.series) {
      if (s.x.size() != s.y.size())
        throw std::invalid_argument("write_plot: series \"" + s.name + "\": x/y sizes differ");
      if (s.y_lo.size() != s.y_hi.size() || (!s.y_lo.empty() && s.y_lo.size() != s.y.size()))
        throw std::invalid_argument("write_plot: series \"" + s.name + "\": error bar sizes differ");
      if (s.x_lo.size() != s.x_hi.size() || (!s.x_lo.empty() && s.x_lo.size() != s.x.size()))
        throw std::invalid_argument("write_plot: series \"" + s.name + "\": error bar sizes differ");
    }
  if (panels.empty()) throw std::invalid_argument("write_plot: no panel");
  check_plot_output(path);
  const std::string ext = lowercase_extension(path);

  // The page: the widest panel, the panels' heights added up.
  int width = 0, height = 0;
  for (const auto& p : panels) width = std::max(width, p.options.width), height += p.options.height;
  // Room right of the data for the legend: its longest entry.
  size_t longest = 0;
  for (const auto& p : panels)
    for (const auto& s : p.series)
      if (p.options.legend) longest = std::max(longest, s.name.size());
  const double text_scale = 0.85;
  // The data area keeps 55% of the width at least; longer names are cut.
  const double char_px = 8.5;  // a legend character (PNG pixels), about
  const double right_px = longest ? 30 + 50 + char_px * double(longest) : 25;
  const double right = std::max(0.55, 1 - right_px / width);
  const size_t legend_chars = size_t(std::max(4.0, ((1 - right) * width - 80) / char_px));

  ScratchFile scratch("plot." + ext);
  {
    static std::mutex m;
    std::lock_guard<std::mutex> lock(m);
    plsexit(plot_exit_handler);
    PLINT stream = 0;
    plmkstrm(&stream);
    plsdev(plot_device(ext).c_str());
    plsfnam(scratch.path().c_str());
    plspage(0, 0, width, height, 0, 0);
    size_t n_colors = kFirstSeries;
    for (const auto& p : panels) n_colors += p.series.size();
    plscmap0n(PLINT(n_colors));
    plscol0(kBackground, 255, 255, 255);
    plscol0(kInk, 0, 0, 0);
    plscol0(kGrid, 222, 222, 222);
    PLINT next = kFirstSeries;
    for (const auto& p : panels)
      for (size_t k = 0; k < p.series.size(); ++k) {
        const PlotColor c = p.series[k].color[0] < 0 ? plot_palette_color(k) : p.series[k].color;
        plscol0(next++, to255(c[0]), to255(c[1]), to255(c[2]));
      }
    plinit();
    pladv(0);
    double top = 1;
    PLINT first = kFirstSeries;
    for (const auto& p : panels) {
      const double band = double(p.options.height) / height;
      Layout box{85.0 / width, right, top - band + 62.0 / height, top - 38.0 / height};
      draw_panel(p, first, box, text_scale, legend_chars);
      first += PLINT(p.series.size());
      top -= band;
    }
    plend1();
  }
  write_output(path, scratch.read(), "plot");
}

}  // namespace clrt

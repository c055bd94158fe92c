// test_plot.cpp - the PLplot chart module: each format's file (magic bytes),
// a non-blank PNG of the asked size, fixed colours by name, refused formats.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "image/image_file.hpp"
#include "image/plot.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_plot {

using namespace clrt;

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<Series> sample_series() {
  Series a{"a", {1, 10, 100}, {0.5, 0.05, 0.005}};
  a.lines = true;
  a.y_lo = {0.4, 0.04, 0.004};
  a.y_hi = {0.6, 0.06, 0.006};
  Series b{"b", {3}, {0.2}};
  b.labels = {"point"};
  b.x_lo = {2}, b.x_hi = {4};
  return {a, b};
}

}  // namespace

TEST_CASE("write_plot writes PNG, SVG and PDF by extension", "[plot]") {
  const auto dir = std::filesystem::temp_directory_path();
  PlotOptions o;
  o.width = 400, o.height = 300, o.log_x = true, o.log_y = true;
  for (const std::string ext : {"png", "svg", "pdf", "PNG"}) {
    const std::string path = (dir / ("clrt_test_plot." + ext)).string();
    std::filesystem::remove(path);
    write_plot(path, "title", "x", "y", sample_series(), o);
    const std::string bytes = file_bytes(path);
    INFO(path);
    REQUIRE(bytes.size() > 100);
    if (ext == "png" || ext == "PNG") CHECK(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
    if (ext == "svg") CHECK(bytes.find("<svg") != std::string::npos);
    if (ext == "pdf") CHECK(bytes.compare(0, 5, "%PDF-") == 0);
    std::filesystem::remove(path);
  }
  // No scratch file is left beside the target.
  for (auto& e : std::filesystem::directory_iterator(dir))
    CHECK(e.path().filename().string().find("clrt_test_plot") == std::string::npos);
}

TEST_CASE("write_plot writes a non-blank PNG of the requested size, two panels stacked", "[plot]") {
  auto path = (std::filesystem::temp_directory_path() / "clrt_test_plot2.png").string();
  std::filesystem::remove(path);
  PlotOptions o;
  o.width = 400, o.height = 300, o.integer_x = true, o.x_from_zero = true;
  write_plot(path, {PlotPanel{"one", "x", "y", sample_series(), o}, PlotPanel{"two", "x", "y", sample_series(), o}});
  // Read back through clrt's imaging module (OpenImageIO behind dlopen: the
  // test processes do not link it; docs/testing.md), 8-bit values 0..255.
  const Image img = read_image(path, 4096, 1 << 24);
  CHECK(img.width == 400);
  CHECK(img.height == 600);
  size_t ink = 0;
  for (size_t i = 0; i + 2 < img.rgb.size(); i += 3)
    if (img.rgb[i] < 127.5 || img.rgb[i + 1] < 127.5 || img.rgb[i + 2] < 127.5) ++ink;
  CHECK(ink > 1000);
  std::filesystem::remove(path);
  CHECK_THROWS_AS(write_plot(path, "", "", "", {Series{"bad", {1, 2}, {1}}}, o), std::invalid_argument);
  Series bars{"bars", {1, 2}, {1, 2}};
  bars.y_lo = {0.5};
  bars.y_hi = {1.5};
  CHECK_THROWS_AS(write_plot(path, "", "", "", {bars}, o), std::invalid_argument);
  CHECK_FALSE(std::filesystem::exists(path));
}

TEST_CASE("a plot with an unknown extension is refused before drawing", "[plot]") {
  const auto dir = std::filesystem::temp_directory_path();
  for (const std::string name : {"p.jpg", "p.txt", "p", "p.exr"}) {
    const std::string path = (dir / ("clrt_test_" + name)).string();
    INFO(path);
    CHECK_THROWS_AS(check_plot_output(path), UserError);
    CHECK_THROWS_AS(write_plot(path, "", "", "", sample_series()), UserError);
    CHECK_FALSE(std::filesystem::exists(path));
  }
  CHECK_NOTHROW(check_plot_output((dir / "clrt_test_ok.svg").string()));
  CHECK_THROWS_AS(check_plot_output((dir / "no/such/dir/p.png").string()), UserError);
}

TEST_CASE("a name has one colour whatever else is plotted, markers differ", "[plot]") {
  // The accuracy variants each have their own fixed colour.
  const std::vector<std::string> variants{
      "naive", "stable", "robust", "fast", "fp64", "robust+subsample-shade", "robust+subsample-interpolate"};
  std::set<PlotColor> seen;
  for (const auto& v : variants) {
    CHECK(plot_color_for_name(v) == plot_color_for_name(std::string(v)));
    seen.insert(plot_color_for_name(v));
  }
  CHECK(seen.size() == variants.size());
  CHECK(plot_color_for_name("robust") == plot_palette_color(0));
  CHECK(plot_color_for_name("some other name") == plot_color_for_name("some other name"));
  std::set<std::string> markers;
  for (size_t i = 0; i < plot_marker_count(); ++i) markers.insert(plot_marker(i));
  CHECK(markers.size() == plot_marker_count());
  CHECK(std::string(plot_marker(plot_marker_count())) == plot_marker(0));
}

}  // namespace test_plot

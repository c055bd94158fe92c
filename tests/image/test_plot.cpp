// test_plot.cpp - the PNG chart module: ticks and a written, non-blank file.
#include <OpenImageIO/imagebuf.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "image/plot.hpp"

using namespace clrt;

TEST_CASE("linear ticks are nice 1/2/5 steps inside the range", "[plot]") {
  auto t = plot_ticks(0.0, 10.0, false);
  REQUIRE(t.size() >= 3);
  CHECK(t.front() == Approx(0.0));
  CHECK(t.back() == Approx(10.0));
  CHECK(t[1] - t[0] == Approx(2.0));  // 10 / 6 -> step 2
  auto n = plot_ticks(-0.37, 0.81, false);
  for (double v : n) CHECK((v >= -0.37 && v <= 0.81));
}

TEST_CASE("log ticks are powers of ten", "[plot]") {
  auto t = plot_ticks(1e-3, 1e3, true);
  REQUIRE(t.size() == 7);
  for (size_t i = 0; i < t.size(); ++i) CHECK(t[i] == Approx(std::pow(10.0, int(i) - 3)));
  // Under one decade: falls back to linear ticks, still inside the range.
  auto u = plot_ticks(2.0, 7.0, true);
  REQUIRE(u.size() >= 2);
  for (double v : u) CHECK((v >= 2.0 && v <= 7.0));
}

TEST_CASE("write_plot writes a non-blank PNG of the requested size", "[plot]") {
  auto path = (std::filesystem::temp_directory_path() / "clrt_test_plot.png").string();
  std::filesystem::remove(path);
  Series a{"a", {1, 10, 100}, {0.5, 0.05, 0.005}};
  a.lines = true;
  Series b{"b", {3}, {0.2}};
  b.labels = {"point"};
  PlotOptions o;
  o.width = 400, o.height = 300, o.log_x = true, o.log_y = true;
  write_plot(path, "title", "x", "y", {a, b}, o);
  OIIO::ImageBuf img(path);
  REQUIRE(img.read());
  CHECK(img.spec().width == 400);
  CHECK(img.spec().height == 300);
  // Count non-white pixels: axes, grid, markers and text must be there.
  size_t ink = 0;
  for (OIIO::ImageBuf::ConstIterator<unsigned char, float> it(img); !it.done(); ++it)  // 8-bit PNG, read as float
    if (it[0] < 0.5f || it[1] < 0.5f || it[2] < 0.5f) ++ink;
  CHECK(ink > 1000);
  std::filesystem::remove(path);
  CHECK_THROWS(write_plot(path, "", "", "", {Series{"bad", {1, 2}, {1}}}, o));
}

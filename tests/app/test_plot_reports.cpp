// test_plot_reports.cpp - what the --plot charts of accuracy and sweep hold:
// a variant's colour does not depend on its position, a marker per scene,
// devices of equal names stay two series, the error per depth is plotted.
// (No OpenCL: rows are made here.)
#include <catch2/catch.hpp>
#include <map>

#include "app/accuracy_report.hpp"
#include "app/sweep_report.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_plot_reports {

using namespace clrt;

namespace {

AccuracyRow accuracy_row(const std::string& scene, const std::string& variant, double ms, double rmse) {
  AccuracyRow r;
  r.scene = scene, r.variant = variant, r.median_ms = ms, r.kernel_ms = {ms * 0.9, ms, ms * 1.2};
  r.error.rmse_8bit = rmse;
  return r;
}

// Variant -> colour of its data points (series with points).
std::map<std::string, PlotColor> point_colors(const PlotPanel& p, const std::vector<AccuracyRow>& rows) {
  std::map<std::string, PlotColor> out;
  size_t i = 0;
  for (const auto& s : p.series)
    if (!s.x.empty()) out[rows.at(i++).variant] = s.color;
  return out;
}

}  // namespace

TEST_CASE("accuracy plot: a variant's colour does not depend on its position", "[plot][accuracy]") {
  const std::vector<AccuracyRow> a{accuracy_row("s.json", "naive", 1, 3), accuracy_row("s.json", "robust", 2, 0.5),
                                   accuracy_row("s.json", "fp64", 4, 0)};
  const std::vector<AccuracyRow> b{accuracy_row("s.json", "fp64", 4, 0), accuracy_row("s.json", "robust", 2, 0.5)};
  const auto ca = point_colors(accuracy_plot_panel(a, "t"), a);
  const auto cb = point_colors(accuracy_plot_panel(b, "t"), b);
  CHECK(ca.at("robust") == cb.at("robust"));
  CHECK(ca.at("fp64") == cb.at("fp64"));
  CHECK(ca.at("robust") != ca.at("naive"));
  const PlotPanel p = accuracy_plot_panel(a, "t");
  CHECK(p.options.log_x);
  CHECK(p.options.log_y);
  for (const auto& s : p.series)
    if (!s.x.empty()) {
      CHECK(s.x_lo.size() == 1);  // min-max of the timed runs
      CHECK(s.y.front() > 0);     // exact (0) drawn at the floor of a log axis
    }
}

TEST_CASE("accuracy plot: one marker per scene", "[plot][accuracy]") {
  const std::vector<AccuracyRow> rows{accuracy_row("a.json", "robust", 1, 1), accuracy_row("b.json", "robust", 2, 2),
                                      accuracy_row("a.json", "naive", 1, 3)};
  const PlotPanel p = accuracy_plot_panel(rows, "t");
  std::vector<int> markers;
  for (const auto& s : p.series)
    if (!s.x.empty()) markers.push_back(s.marker);
  REQUIRE(markers.size() == 3);
  CHECK(markers[0] == markers[2]);
  CHECK(markers[0] != markers[1]);
}

TEST_CASE("sweep plot: two devices of one name are two series, error per depth plotted", "[plot][sweep]") {
  std::vector<SweepRow> rows;
  for (int device : {0, 1})
    for (int depth : {0, 1, 2}) {
      SweepRow r;
      r.device = "Same GPU";
      r.device_index = device;
      r.device_pd = "0:" + std::to_string(device);
      r.depth = depth;
      r.bench.kernel.median = 1 + depth, r.bench.kernel.min = 0.5 + depth, r.bench.kernel.max = 2 + depth;
      r.error.rmse_8bit = 0.1 * depth;
      rows.push_back(r);
    }
  std::vector<PlotPanel> rays;
  const auto panels = sweep_plot_panels(rows, "t", &rays);
  REQUIRE(panels.size() == 2);  // time and error per depth
  REQUIRE(rays.size() == 1);
  std::vector<const Series*> devices;
  for (const auto& s : panels[0].series)
    if (s.name.find("Same GPU") != std::string::npos) devices.push_back(&s);
  REQUIRE(devices.size() == 2);
  CHECK(devices[0]->name != devices[1]->name);
  CHECK(devices[0]->name.find("0:0") != std::string::npos);
  CHECK(devices[1]->name.find("0:1") != std::string::npos);
  CHECK(devices[0]->x.size() == 3);
  CHECK(devices[0]->y_lo == std::vector<double>{0.5, 1.5, 2.5});  // min-max bars
  CHECK(devices[0]->color != devices[1]->color);
  CHECK(panels[0].options.integer_x);
  CHECK(panels[1].series.size() == 2);
  CHECK(panels[1].series[0].y == std::vector<double>{0, 0.1, 0.2});
  CHECK(rays[0].series.size() == 2);
}

TEST_CASE("a --plot with an unknown extension fails before measuring", "[plot][cli][full-build]") {
  clrt_test::TempDir dir;
  const std::string demo = clrt_test::source_path("scenes/cgfs-demo.json");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"accuracy", demo, "--width", "8", "--height", "8", "--plot", dir / "p.jpg"},
        std::vector<std::string>{"sweep", demo, "--depths", "0:1", "--width", "8", "--height", "8", "--plot",
                                 dir / "p.gif"},
        std::vector<std::string>{"scaling", "--spheres", "8", "--width", "8", "--height", "8", "--plot", dir / "p"}}) {
    const auto r = clrt_test::run_clrt(args);
    INFO(args[0] << ": status " << r.status << ", stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK(r.err.rfind("clrt: error: ", 0) == 0);
    CHECK(r.err.find("unknown format") != std::string::npos);
    CHECK(r.out.empty());  // nothing measured
  }
  CHECK(dir.entries().empty());
}

}  // namespace test_plot_reports

// cmd_scaling.cpp - `clrt scaling --spheres 1000,10000,...`: frame time
// against the number of spheres, clrt beside the Embree tracer.
#include <CLI/CLI.hpp>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <memory>
#include <sstream>

#include "app/options.hpp"
#include "app/scaling_report.hpp"
#include "eval/scaling.hpp"
#include "image/image_file.hpp"
#include "image/plot.hpp"
#include "scene/mesh_grid.hpp"
#include "scene/random_scene.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

namespace clrt {

namespace {

// "1000,10000" -> {1000, 10000}; each in [1, most], for the option `name`.
std::vector<size_t> parse_counts(const std::string& text, const std::string& name, size_t most) {
  std::vector<size_t> counts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    // Leading white space is skipped; from_chars takes no sign, trailing
    // text or exponent ("-5", "+5", "5 ", "1e3" fail).
    const char* begin = item.data();
    const char* end = begin + item.size();
    while (begin != end && std::isspace(static_cast<unsigned char>(*begin))) ++begin;
    unsigned long long n = 0;
    const auto [stop, error] = std::from_chars(begin, end, n);
    if (error != std::errc() || stop != end || n < 1 || n > most)
      throw UserError(name + ": expected counts from 1 to " + std::to_string(most) + " separated by commas (got \"" +
                      text.substr(0, 64) + "\")");
    counts.push_back(size_t(n));
  }
  if (counts.empty() || text.back() == ',') throw UserError(name + ": expected counts separated by commas");
  if (counts.size() > 32) throw UserError(name + ": at most 32 counts");
  return counts;
}

}  // namespace

void add_scaling_command(CLI::App& app) {
  auto image = std::make_shared<ImageOptions>();
  auto device = std::make_shared<DeviceOptions>();
  auto kernel = std::make_shared<KernelOptions>();
  auto launch = std::make_shared<LaunchOptions>();
  auto counts = std::make_shared<std::string>("1000,10000,100000");
  auto triangles = std::make_shared<std::string>();
  auto settings = std::make_shared<ScalingSettings>();
  auto repeat = std::make_shared<int>(3);
  auto no_embree = std::make_shared<bool>(false);
  auto csv = std::make_shared<std::string>();
  auto plot = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand(
      "scaling",
      "Frame time against the number of spheres (random scenes made in memory) or triangles (grids of tori), beside "
      "the Embree tracer");
  auto* spheres = cmd->add_option("--spheres", *counts, "Sphere counts, separated by commas")->capture_default_str();
  cmd->add_option("--triangles", *triangles,
                  "Triangle counts of mesh scenes (grids of tori, up to 4000000), separated by commas; without "
                  "--spheres only these run");
  cmd->add_option("--seed", settings->seed, "Seed of the scenes")->capture_default_str();
  cmd->add_option("--fill", settings->fill, "Fraction of the volume the spheres fill")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  image->add(cmd, /*with_depth=*/true, /*with_spp=*/false);  // beside Embree: one ray per pixel
  device->add(cmd, /*several=*/true);
  kernel->add(cmd, /*with_variant=*/true);
  launch->add(cmd);
  add_repeat_option(cmd, *repeat, "Timed rounds per scene after one warm-up");
  cmd->add_flag("--no-embree", *no_embree, "Skip the Embree comparison");
  cmd->add_option("--csv", *csv, "Write the table as CSV to this file");
  cmd->add_option("--plot", *plot, "Write a log-log plot of frame time against spheres here: .png, .svg or .pdf");
  cmd->callback([=] {
    image->validate();
    launch->validate();
    settings->counts = parse_counts(*counts, "--spheres", kMaxGeneratedSpheres);
    if (!triangles->empty()) {
      settings->triangles = parse_counts(*triangles, "--triangles", kMaxGridTriangles);
      if (spheres->count() == 0) settings->counts.clear();
    }
    if (!plot->empty()) check_plot_output(*plot);  // fail before measuring
    if (!csv->empty()) check_writable(*csv, "CSV");
    std::vector<NamedOutput> all;
    if (!csv->empty()) all.push_back({*csv, "CSV"});
    if (!plot->empty()) all.push_back({*plot, "plot"});
    check_distinct_outputs(all);
    claim_stdout_if_dash(*csv);
    settings->bench.width = image->width;
    settings->bench.height = image->height;
    settings->bench.depth = image->depth;  // kSceneDepth (-1): the scenes' own (3)
    settings->bench.repeat = *repeat;
    settings->bench.reference = false;  // every sphere per ray: hours at these sizes
    settings->bench.omp = false;
    settings->bench.embree = !*no_embree;
    settings->bench.builds = false;
    settings->bench.peak = false;
    settings->progress = stderr_progress();  // on a terminal only, not with --quiet
    RenderSettings render{kernel->config(), launch->tiles(), launch->local()};
    render.kernel.output = {PixelFormat::Rgba8, /*classes=*/false};  // like bench: a PNG's frames
    const auto rows = run_scaling(device->devices(), render, *settings);
    print_scaling(rows);
    if (!csv->empty()) {
      write_text_atomic(*csv, scaling_csv(rows), "CSV");
      std::fprintf(report_stream(), "wrote %s\n", csv->c_str());
    }
    if (!plot->empty()) {
      plot_scaling(rows, *plot, "frame time against spheres");
      std::fprintf(report_stream(), "wrote %s\n", plot->c_str());
    }
  });
}

}  // namespace clrt

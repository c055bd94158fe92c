// sweep_report.hpp - how `clrt sweep` shows its rows: a table, CSV, and
// plots of time and rays per depth.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/sweep.hpp"
#include "image/plot.hpp"

namespace clrt {

// CSV: the report header columns, then per row its figures (device, depth,
// kernel_ms_median, ...) and compare's metrics of the error against the
// reference (error_pixels_off_by_gt1, ...) and of the change from the depth
// before (change_pixels_differ, ...).
std::string sweep_csv(const std::vector<SweepRow>& rows);
// JSON: the report header, "mpi_ranks" when more than one rank ran the sweep
// (dist/eval_grids.hpp), scene, width, height, spp, repeat, and "rows": the
// same figures, with "error" and "change" as compare's metric objects.
// `overrides`: the command's -D (overrides_json), after "scene".
nlohmann::ordered_json sweep_json(const std::vector<SweepRow>& rows, const std::string& scene,
                                  const nlohmann::ordered_json& overrides, int mpi_ranks = 1);
void print_sweep(const std::vector<SweepRow>& rows);
// Time per depth (median, min-max bars, and the reference) above the error
// per depth (RMSE vs reference) to `path`; rays per depth to the same name
// with "-rays" before the extension. Returns the second path. One series per
// device, by index and P:D (equal names stay apart, labelled "name [P:D]").
std::string rays_plot_path(const std::string& path);  // "a/t.png" -> "a/t-rays.png"
std::vector<PlotPanel> sweep_plot_panels(const std::vector<SweepRow>& rows, const std::string& title,
                                         std::vector<PlotPanel>* rays_panel = nullptr);
std::string plot_sweep(const std::vector<SweepRow>& rows, const std::string& path, const std::string& title);

}  // namespace clrt

// accuracy_report.hpp - the forms `clrt accuracy` shows its rows in: a
// fixed-width table, Markdown, JSON, CSV and an error-against-time chart.
#pragma once
#include <string>
#include <vector>

#include "eval/accuracy.hpp"
#include "image/plot.hpp"

namespace clrt {

std::string accuracy_table(const std::vector<AccuracyRow>& rows);  // fixed-width text
std::string accuracy_markdown(const std::vector<AccuracyRow>& rows);
// JSON: the report header, "mpi_ranks" when more than one rank measured the
// rows (dist/eval_grids.hpp), device, width, height, spp, repeat, overrides
// (the -D texts, as overrides_json), "rows".
std::string accuracy_json(const std::vector<AccuracyRow>& rows, const AccuracySettings& s, const std::string& device,
                          const std::vector<std::string>& overrides, int mpi_ranks = 1);
// CSV: the report header columns, device, scene, variant, depth, supported,
// kernel_ms_median, kernel_time_source, then compare's metric columns.
std::string accuracy_csv(const std::vector<AccuracyRow>& rows, const std::string& device);
void write_accuracy_csv(const std::vector<AccuracyRow>& rows, const std::string& path, const std::string& device);
// Error (RMSE, 8-bit levels) against median kernel time (min-max bars), both
// axes log; a fixed colour per variant name (plot_color_for_name), a marker
// per scene. RMSE 0 is drawn at a floor and labelled. PNG, SVG or PDF.
PlotPanel accuracy_plot_panel(const std::vector<AccuracyRow>& rows, const std::string& title);
void write_accuracy_plot(const std::vector<AccuracyRow>& rows, const std::string& path, const std::string& title);

}  // namespace clrt

// sweep_report.hpp - how `clrt sweep` shows its rows: a table, CSV, and
// plots of time and rays per depth.
#pragma once
#include <string>
#include <vector>

#include "eval/sweep.hpp"

namespace clrt {

std::string sweep_csv(const std::vector<SweepRow>& rows);
void print_sweep(const std::vector<SweepRow>& rows);
// Time per depth to `path`; rays per depth to the same name with "-rays"
// before the extension. Returns the second path.
std::string rays_plot_path(const std::string& path);  // "a/t.png" -> "a/t-rays.png"
std::string plot_sweep(const std::vector<SweepRow>& rows, const std::string& path, const std::string& title);

}  // namespace clrt

// scaling_report.hpp - how `clrt scaling` shows its rows: a table, CSV, and
// a plot of frame time against the number of spheres on log-log axes.
#pragma once
#include <string>
#include <vector>

#include "eval/scaling.hpp"

namespace clrt {

std::string scaling_csv(const std::vector<ScalingRow>& rows);
void print_scaling(const std::vector<ScalingRow>& rows);
void plot_scaling(const std::vector<ScalingRow>& rows, const std::string& path, const std::string& title);

}  // namespace clrt

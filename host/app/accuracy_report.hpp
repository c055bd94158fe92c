// accuracy_report.hpp - the forms `clrt accuracy` shows its rows in: a
// fixed-width table, Markdown, JSON, CSV and an error-against-time chart.
#pragma once
#include <string>
#include <vector>

#include "eval/accuracy.hpp"

namespace clrt {

std::string accuracy_table(const std::vector<AccuracyRow>& rows);  // fixed-width text
std::string accuracy_markdown(const std::vector<AccuracyRow>& rows);
std::string accuracy_json(const std::vector<AccuracyRow>& rows, const AccuracySettings& s, const std::string& device);
// CSV: the report header columns, device, scene, variant, depth, supported,
// kernel_ms_median, kernel_time_source, then compare's metric columns.
std::string accuracy_csv(const std::vector<AccuracyRow>& rows, const std::string& device);
void write_accuracy_csv(const std::vector<AccuracyRow>& rows, const std::string& path, const std::string& device);
// Error (RMSE, 8-bit levels, log scale) against median kernel time; one series
// per variant, one point per scene. RMSE 0 is drawn at a floor and labelled.
void write_accuracy_plot(const std::vector<AccuracyRow>& rows, const std::string& path, const std::string& title);

}  // namespace clrt

// stats.hpp - summary of repeated timings: N, median, mean, standard
// deviation (sample, N-1), min and max. Every timed figure a command reports
// goes through this, so none is a single unexplained sample.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace clrt {

struct Stats {
  int n = 0;
  double median = 0, mean = 0, sd = 0, min = 0, max = 0;
};

double median(std::vector<double> v);
Stats summarize(const std::vector<double>& v);

// {"n", "median_UNIT", "mean_UNIT", "sd_UNIT", "min_UNIT", "max_UNIT"}: the
// unit in every name ("ms" for times, "ratio" for speedups).
nlohmann::json stats_json(const Stats& s, const std::string& unit);
// The table columns of a timing, by the one naming rule of the CSV reports:
// PREFIX_FIELD for each of `fields` ("median", "min", "max", "mean", "sd"),
// in their order (e.g. stats_columns("frame_ms", s, {"median", "sd"}):
// frame_ms_median, frame_ms_sd). std::invalid_argument for another field.
std::vector<std::pair<std::string, double>> stats_columns(const std::string& prefix, const Stats& s,
                                                          const std::vector<std::string>& fields);
// "median 12.34 ms, mean 12.50 ± 0.40, min 12.01, max 13.20 (N=7)"; with N=1
// just "12.34 ms (N=1)". `unit` follows the median.
std::string format_stats(const Stats& s, const char* unit = "ms", int decimals = 2);

}  // namespace clrt

// stats.hpp - summary of repeated timings: N, median, mean, standard
// deviation (sample, N-1), min and max. Every timed figure a command reports
// goes through this, so none is a single unexplained sample.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
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
// "median 12.34 ms, mean 12.50 ± 0.40, min 12.01, max 13.20 (N=7)"; with N=1
// just "12.34 ms (N=1)". `unit` follows the median.
std::string format_stats(const Stats& s, const char* unit = "ms", int decimals = 2);

}  // namespace clrt

// stats.cpp - summaries of repeated measurements.
#include "util/stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace clrt {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Stats summarize(const std::vector<double>& v) {
  Stats s;
  s.n = int(v.size());
  if (v.empty()) return s;
  s.median = median(v);
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  if (s.n > 1) {
    double ss = 0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.sd = std::sqrt(ss / (s.n - 1));
  }
  return s;
}

nlohmann::json stats_json(const Stats& s, const std::string& unit) {
  const std::string u = "_" + unit;
  return {{"n", s.n},       {"median" + u, s.median}, {"mean" + u, s.mean},
          {"sd" + u, s.sd}, {"min" + u, s.min},       {"max" + u, s.max}};
}

std::vector<std::pair<std::string, double>> stats_columns(const std::string& prefix, const Stats& s,
                                                          const std::vector<std::string>& fields) {
  std::vector<std::pair<std::string, double>> columns;
  for (const std::string& field : fields) {
    const double value = field == "median" ? s.median
                         : field == "min"  ? s.min
                         : field == "max"  ? s.max
                         : field == "mean" ? s.mean
                         : field == "sd"   ? s.sd
                                           : throw std::invalid_argument("stats_columns: no field " + field);
    columns.emplace_back(prefix + "_" + field, value);
  }
  return columns;
}

std::string format_stats(const Stats& s, const char* unit, int decimals) {
  char buf[256];
  const int d = decimals;
  // A ratio reads "1.63x"; a quantity "1.63 ms".
  const char* space = std::string(unit) == "x" ? "" : " ";
  if (s.n <= 1)
    std::snprintf(buf, sizeof buf, "%.*f%s%s (N=%d)", d, s.median, space, unit, s.n);
  else
    std::snprintf(buf, sizeof buf, "median %.*f%s%s, mean %.*f ± %.*f, min %.*f, max %.*f (N=%d)", d, s.median, space,
                  unit, d, s.mean, d, s.sd, d, s.min, d, s.max, s.n);
  return buf;
}

}  // namespace clrt

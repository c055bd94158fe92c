// bench_report.hpp - how `clrt bench` shows a BenchResult: aligned text lines
// and one JSON object.
#pragma once
#include <nlohmann/json.hpp>

#include "eval/bench.hpp"

namespace clrt {

// The report header (report_header.hpp), then every figure of the result;
// flat *_ms / *_median keys repeat the medians of the matching Stats objects.
nlohmann::ordered_json bench_json(const BenchResult& r);
void print_bench(const BenchResult& r);

}  // namespace clrt

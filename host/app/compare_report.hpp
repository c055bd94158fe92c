// compare_report.hpp - how a Comparison is shown: the one table that names
// each metric (every JSON key and CSV column of a comparison comes from it)
// and the PSNR as text.
#pragma once
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "app/engine.hpp"
#include "app/options.hpp"
#include "eval/compare.hpp"
#include "eval/layer_compare.hpp"
#include "util/csv.hpp"

namespace clrt {

// The metrics of a Comparison, named with their unit, in this order:
// pixels, pixels_differ, pixels_off_by_gt1, pixels_off_by_gt1_percent,
// max_abs_8bit, rmse_8bit, psnr_8bit_db, max_abs_float, rmse_float,
// psnr_float_db, nan_inf_pixels, nan_inf_pixels_reference, hit_flip_pixels,
// shadow_flip_pixels. An infinite PSNR (identical images) is null in JSON and
// an empty field in CSV. *_8bit and *_float are in 8-bit levels (0..255).
std::vector<std::pair<std::string, nlohmann::ordered_json>> comparison_metrics(const Comparison& c);

// Those metrics as one JSON object (keys as above, in that order).
nlohmann::ordered_json comparison_json(const Comparison& c);
// The same into the current row of `t`, each column named PREFIX + key.
void comparison_csv(CsvTable& t, const Comparison& c, const std::string& prefix = "");

// "inf" for an infinite PSNR, otherwise the number with 2 decimals.
std::string format_psnr(double psnr);

// A LayerComparison as JSON: {"layers": "depth,...,id", "id_differ_pixels",
// ..., "pass"} (docs/guide/output.md), and as the text report's lines, one
// per layer with its tolerance.
nlohmann::ordered_json layer_comparison_json(const LayerComparison& c);
void print_layer_comparison(const LayerComparison& c, std::FILE* out);

// `clrt compare --json`'s object (docs/guide/output.md): the report header,
// the options of `o` and the run's figures, the metrics above, and the
// limits and verdict when any limit is set. The Python module's
// clrt.compare() returns the same object.
nlohmann::ordered_json compare_json(const CompareRun& c, const RenderOptions& o);

}  // namespace clrt

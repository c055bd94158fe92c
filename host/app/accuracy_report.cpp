// accuracy_report.cpp - accuracy rows as table, Markdown, JSON, CSV and plot.
#include "app/accuracy_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/compare_report.hpp"
#include "app/report_header.hpp"
#include "image/plot.hpp"
#include "util/csv.hpp"
#include "util/json_text.hpp"
#include "util/output_file.hpp"
#include "util/stats.hpp"

namespace clrt {

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string base_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

struct Cells {
  std::vector<std::string> head{"scene",       "variant",         "kernel ms (median)", "off by >1",
                                "% off by >1", "max abs (8-bit)", "RMSE (8-bit)",       "PSNR (dB)",
                                "NaN/Inf",     "hit flips",       "shadow flips"};
  std::vector<std::vector<std::string>> body;
};

Cells cells(const std::vector<AccuracyRow>& rows) {
  Cells c;
  for (const auto& r : rows) {
    if (!r.supported) {
      c.body.push_back({base_name(r.scene), r.variant, "unsupported", "-", "-", "-", "-", "-", "-", "-", "-"});
      continue;
    }
    const Comparison& e = r.error;
    // "h": timed by the host clock, the device's profiling events were implausible.
    const std::string ms = fmt("%.2f", r.median_ms) + (r.host_timed_launches ? " h" : "");
    c.body.push_back({base_name(r.scene), r.variant, ms, std::to_string(e.off_by_gt1),
                      fmt("%.4f", e.percent_off_by_gt1()), std::to_string(e.max_abs_8bit), fmt("%.4f", e.rmse_8bit),
                      format_psnr(e.psnr_8bit), std::to_string(e.nan_inf), std::to_string(e.hit_flips),
                      std::to_string(e.shadow_flips)});
  }
  return c;
}

}  // namespace

std::string accuracy_table(const std::vector<AccuracyRow>& rows) {
  Cells c = cells(rows);
  std::vector<size_t> w(c.head.size());
  for (size_t k = 0; k < w.size(); ++k) {
    w[k] = c.head[k].size();
    for (const auto& r : c.body) w[k] = std::max(w[k], r[k].size());
  }
  std::ostringstream os;
  auto line = [&](const std::vector<std::string>& r) {
    for (size_t k = 0; k < r.size(); ++k) {
      std::string pad(w[k] - r[k].size(), ' ');
      os << (k < 2 ? r[k] + pad : pad + r[k]) << (k + 1 < r.size() ? "  " : "\n");
    }
  };
  line(c.head);
  for (const auto& r : c.body) line(r);
  for (const auto& r : rows)
    if (!r.supported) os << base_name(r.scene) << " " << r.variant << ": " << r.note << "\n";
  for (const auto& r : rows)
    if (r.host_timed_launches) {
      os << "h: timed by the host wall clock (the device's profiling events were implausible)\n";
      break;
    }
  return os.str();
}

std::string accuracy_markdown(const std::vector<AccuracyRow>& rows) {
  Cells c = cells(rows);
  std::ostringstream os;
  os << "|";
  for (auto& h : c.head) os << " " << h << " |";
  os << "\n|";
  for (size_t k = 0; k < c.head.size(); ++k) os << (k < 2 ? ":---|" : "---:|");
  os << "\n";
  for (const auto& r : c.body) {
    os << "|";
    for (auto& v : r) os << " " << v << " |";
    os << "\n";
  }
  return os.str();
}

std::string accuracy_json(const std::vector<AccuracyRow>& rows, const AccuracySettings& s, const std::string& device,
                          const std::vector<std::string>& overrides, int mpi_ranks) {
  nlohmann::ordered_json out = header_json(report_header(device));
  if (mpi_ranks > 1) out["mpi_ranks"] = mpi_ranks;
  out.update(nlohmann::ordered_json{
      {"device", device}, {"width", s.width}, {"height", s.height}, {"spp", s.spp}, {"repeat", s.repeat}});
  out["overrides"] = overrides_json(overrides);
  nlohmann::ordered_json arr = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    nlohmann::ordered_json j = {
        {"scene", r.scene}, {"variant", r.variant}, {"depth", r.depth}, {"supported", r.supported}};
    if (!r.supported) {
      j["note"] = r.note;
    } else {
      j.update(nlohmann::ordered_json{{"kernel_ms_median", r.median_ms},
                                      {"kernel_ms", r.kernel_ms},
                                      {"kernel", nlohmann::ordered_json(stats_json(summarize(r.kernel_ms), "ms"))},
                                      {"kernel_time_source", r.time_source()}});
      j.update(comparison_json(r.error));
    }
    arr.push_back(j);
  }
  out["rows"] = arr;
  return json_text(out);
}

std::string accuracy_csv(const std::vector<AccuracyRow>& rows, const std::string& device) {
  const ReportHeader h = report_header(device);
  CsvTable t;
  for (const auto& r : rows) {
    t.row();
    header_csv(t, h);
    t.set("device", device);
    t.set("scene", r.scene);
    t.set("variant", r.variant);
    t.set_number("depth", r.depth);
    t.set_number("supported", r.supported ? 1 : 0);
    // An unsupported variant: its measured columns stay empty.
    t.set("kernel_ms_median", r.supported ? csv_number(r.median_ms) : "");
    t.set("kernel_time_source", r.supported ? r.time_source() : "");
    if (r.supported)
      comparison_csv(t, r.error);
    else
      for (auto& m : comparison_metrics(r.error)) t.set(m.first, "");
  }
  if (rows.empty()) {  // the header alone
    t.row();
    header_csv(t, h);
  }
  return rows.empty() ? csv_record(t.names()) : t.text();
}

void write_accuracy_csv(const std::vector<AccuracyRow>& rows, const std::string& path, const std::string& device) {
  write_text_atomic(path, accuracy_csv(rows, device), "CSV");
}

PlotPanel accuracy_plot_panel(const std::vector<AccuracyRow>& rows, const std::string& title) {
  // Log-log: an exact variant (RMSE 0) is drawn at a floor one decade under
  // the smallest non-zero RMSE and labelled "(0)".
  double min_pos = 1;
  for (const auto& r : rows)
    if (r.supported && r.error.rmse_8bit > 0) min_pos = std::min(min_pos, r.error.rmse_8bit);
  const double floor = min_pos / 10;
  // Colour by variant name (a fixed table, whatever the order of
  // --variants), marker by scene (in the order given).
  std::vector<std::string> variants, scenes;
  for (const auto& r : rows) {
    if (!r.supported) continue;
    if (std::find(variants.begin(), variants.end(), r.variant) == variants.end()) variants.push_back(r.variant);
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  }
  std::vector<Series> series;
  for (const auto& v : variants) {  // legend entries: a line in the variant's colour
    Series s(v, {}, {});
    s.lines = true, s.markers = false;
    s.color = plot_color_for_name(v);
    series.push_back(s);
  }
  for (size_t k = 0; k < scenes.size(); ++k) {  // and a black marker per scene
    Series s(std::filesystem::path(scenes[k]).stem().string(), {}, {});
    s.color = {0, 0, 0};
    s.marker = int(k);
    series.push_back(s);
  }
  for (const auto& r : rows) {  // the points: one series per variant and scene
    if (!r.supported) continue;
    Series s;
    s.color = plot_color_for_name(r.variant);
    s.marker = int(std::find(scenes.begin(), scenes.end(), r.scene) - scenes.begin());
    const bool exact = r.error.rmse_8bit <= 0;
    s.x.push_back(r.median_ms);
    s.y.push_back(exact ? floor : r.error.rmse_8bit);
    if (!r.kernel_ms.empty()) {  // min-max of the timed runs
      s.x_lo.push_back(*std::min_element(r.kernel_ms.begin(), r.kernel_ms.end()));
      s.x_hi.push_back(*std::max_element(r.kernel_ms.begin(), r.kernel_ms.end()));
    }
    s.labels.push_back(exact ? r.variant + " (0)" : "");
    series.push_back(s);
  }
  PlotOptions o;
  o.log_x = o.log_y = true;
  return {title, "kernel time, median (ms; bar: min-max)", "RMSE vs double reference, 8-bit levels (0 at the bottom)",
          series, o};
}

void write_accuracy_plot(const std::vector<AccuracyRow>& rows, const std::string& path, const std::string& title) {
  write_plot(path, {accuracy_plot_panel(rows, title)});
}

}  // namespace clrt

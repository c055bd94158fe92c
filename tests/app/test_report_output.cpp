// test_report_output.cpp - the machine-readable reports
// (docs/guide/output.md): every CSV parses with a strict RFC 4180 reader
// into rows of the header's width, one name per metric across JSON and CSV,
// the report header (clrt version, timestamp, driver) in every report, keys
// in their documented order, `devices --json` and `sweep --json`, and null
// for an infinite PSNR.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/compare_report.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"
#include "util/csv.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_report_output {

namespace {

using Rows = std::vector<std::vector<std::string>>;

// A strict RFC 4180 reader: a quoted field starts with '"', doubles its
// quotes and is followed by ',' or the end of the record; an unquoted field
// holds no '"'; records end in LF (or CRLF); every record has the header's
// number of fields. Anything else throws.
Rows parse_csv_strict(const std::string& text) {
  Rows rows;
  std::vector<std::string> rec;
  std::string field;
  size_t i = 0;
  const size_t n = text.size();
  if (n == 0 || text.back() != '\n') throw std::runtime_error("CSV does not end in a newline");
  while (i < n) {
    field.clear();
    if (text[i] == '"') {
      ++i;
      for (;;) {
        if (i >= n) throw std::runtime_error("unterminated quoted field");
        if (text[i] == '"') {
          if (i + 1 < n && text[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        field += text[i++];
      }
      if (i < n && text[i] != ',' && text[i] != '\n' && text[i] != '\r')
        throw std::runtime_error("text after a closing quote");
    } else {
      while (i < n && text[i] != ',' && text[i] != '\n' && text[i] != '\r') {
        if (text[i] == '"') throw std::runtime_error("quote inside an unquoted field");
        field += text[i++];
      }
    }
    rec.push_back(field);
    if (text[i] == ',') {
      ++i;
      continue;
    }
    if (text[i] == '\r') {
      if (i + 1 >= n || text[i + 1] != '\n') throw std::runtime_error("bare CR");
      ++i;
    }
    ++i;  // LF
    if (!rows.empty() && rec.size() != rows.front().size())
      throw std::runtime_error("record " + std::to_string(rows.size()) + " has " + std::to_string(rec.size()) +
                               " fields, the header " + std::to_string(rows.front().size()));
    rows.push_back(rec);
    rec.clear();
  }
  return rows;
}

// The column NAME of a parsed CSV (throws when absent).
size_t column(const Rows& rows, const std::string& name) {
  for (size_t k = 0; k < rows.front().size(); ++k)
    if (rows.front()[k] == name) return k;
  throw std::runtime_error("no column " + name);
}

const std::vector<std::string> kMetricKeys = {
    "pixels",          "pixels_differ",     "pixels_off_by_gt1", "pixels_off_by_gt1_percent",
    "max_abs_8bit",    "rmse_8bit",         "psnr_8bit_db",      "max_abs_float",
    "rmse_float",      "psnr_float_db",     "nan_inf_pixels",    "nan_inf_pixels_reference",
    "hit_flip_pixels", "shadow_flip_pixels"};

// `clrt --version`'s version: "clrt X.Y.Z".
std::string cli_version() {
  auto r = clrt_test::run_clrt({"--version"});
  const std::string first = r.out.substr(0, r.out.find('\n'));
  return first.substr(first.find(' ') + 1);
}

// The three header fields, as the JSON holds them, first and in this order.
void check_header_json(const std::string& text, bool driver_known) {
  auto j = nlohmann::ordered_json::parse(text);
  REQUIRE(j.is_object());
  REQUIRE(j.size() >= 3);
  auto it = j.begin();
  CHECK(it.key() == "clrt_version");
  CHECK((it++).value() == cli_version());
  CHECK(it.key() == "timestamp_utc");
  CHECK(std::regex_match((it++).value().get<std::string>(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
  CHECK(it.key() == "device_driver");
  if (driver_known) CHECK(!it.value().get<std::string>().empty());
}

void check_header_csv(const Rows& rows) {
  REQUIRE(rows.size() >= 2);
  REQUIRE(rows.front().size() >= 3);
  CHECK(rows.front()[0] == "clrt_version");
  CHECK(rows.front()[1] == "timestamp_utc");
  CHECK(rows.front()[2] == "device_driver");
  const std::string version = cli_version();
  for (size_t r = 1; r < rows.size(); ++r) {
    CHECK(rows[r][0] == version);
    CHECK(std::regex_match(rows[r][1], std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
    CHECK(!rows[r][2].empty());
  }
}

}  // namespace

TEST_CASE("the strict CSV reader rejects what RFC 4180 does not allow", "[csv]") {
  CHECK_NOTHROW(parse_csv_strict("a,b\n1,\"x,\"\"y\"\"\"\n"));
  CHECK_THROWS(parse_csv_strict("a,b\n1\n"));         // short record
  CHECK_THROWS(parse_csv_strict("a,b\n1,x\"y\n"));    // bare quote
  CHECK_THROWS(parse_csv_strict("a,b\n1,\"x\"y\n"));  // text after the closing quote
  CHECK_THROWS(parse_csv_strict("a,b\n1,\"x\n"));     // unterminated
  CHECK_THROWS(parse_csv_strict("a,b\n1,2"));         // no final newline
}

TEST_CASE("CsvTable quotes every field and keeps rows in the header's columns", "[csv]") {
  clrt::CsvTable t;
  t.row();
  t.set("name", "a,b \"c\"\nd");
  t.set_number("value", 1.5);
  t.row();
  t.set("value", "2");  // "name" left out: an empty field
  t.set("note", "late column");
  const Rows rows = parse_csv_strict(t.text());
  REQUIRE(rows.size() == 3);
  CHECK(rows[0] == std::vector<std::string>{"name", "value", "note"});
  CHECK(rows[1] == std::vector<std::string>{"a,b \"c\"\nd", "1.5", ""});
  CHECK(rows[2] == std::vector<std::string>{"", "2", "late column"});
  CHECK(clrt::csv_record({"x", "y,z"}) == "x,\"y,z\"\n");
}

TEST_CASE("one name per comparison metric, with its unit, in JSON and CSV, infinite PSNR is null",
          "[compare][output]") {
  clrt::Comparison c;
  c.pixels = 100;
  c.off_by_gt1 = 3;
  c.psnr_8bit = INFINITY;
  c.psnr_float = 42.5;
  const auto j = clrt::comparison_json(c);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  CHECK(keys == kMetricKeys);  // the documented order
  CHECK(j["psnr_8bit_db"].is_null());
  CHECK(j["psnr_float_db"] == 42.5);
  CHECK(j["pixels_off_by_gt1"] == 3);
  CHECK(j["pixels_off_by_gt1_percent"] == 3.0);
  clrt::CsvTable t;
  t.row();
  clrt::comparison_csv(t, c, "error_");
  const Rows rows = parse_csv_strict(t.text());
  REQUIRE(rows.size() == 2);
  for (size_t k = 0; k < kMetricKeys.size(); ++k) CHECK(rows[0][k] == "error_" + kMetricKeys[k]);
  CHECK(rows[1][column(rows, "error_psnr_8bit_db")] == "");  // infinite: empty
  CHECK(rows[1][column(rows, "error_psnr_float_db")] == "42.5");
  // The old, divergent names are gone from every form.
  const std::string dumped = j.dump() + t.text();
  for (const char* old : {"\"off_by_gt1", "err_off_by_gt1", "percent_off_by_gt1", "psnr_8bit\"", "\"hit_flips"})
    CHECK(dumped.find(old) == std::string::npos);
}

TEST_CASE("clrt accuracy --json and --csv: header, metric names, strict CSV", "[cli][accuracy][opencl][output]") {
  clrt_test::TempDir dir;
  auto r = clrt_test::run_clrt({"accuracy", clrt_test::source_path("scenes/cgfs-demo.json"), "--width", "16",
                                "--height", "12", "--repeat", "1", "--variants", "robust,naive", "--json", "--csv",
                                dir / "a,\"odd\".csv", "-D", "spheres.0.reflective=0.5", "-D", "epsilon=0.01"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  check_header_json(r.out, true);
  auto j = nlohmann::ordered_json::parse(r.out);
  // The -D, in the order given.
  CHECK(j["overrides"].dump() == R"({"spheres.0.reflective":0.5,"epsilon":0.01})");
  REQUIRE(j["rows"].size() == 2);
  for (const auto& k : kMetricKeys) CHECK(j["rows"][0].contains(k));
  const Rows rows = parse_csv_strict(clrt_test::slurp(dir / "a,\"odd\".csv"));
  check_header_csv(rows);
  REQUIRE(rows.size() == 3);
  for (const auto& k : kMetricKeys) CHECK_NOTHROW(column(rows, k));
  CHECK(rows[1][column(rows, "variant")] == "robust");
  CHECK(rows[1][column(rows, "pixels")] == std::to_string(16 * 12));
}

TEST_CASE("clrt sweep --json parses and --csv parses strictly, with the same metric names",
          "[cli][sweep][opencl][output]") {
  clrt_test::TempDir dir;
  auto r = clrt_test::run_clrt({"sweep", clrt_test::source_path("scenes/cgfs-demo.json"), "--depths", "0:1", "--width",
                                "16", "--height", "12", "--repeat", "1", "--json", "--csv", dir / "s.csv", "--set",
                                "camera.position=[0, 0.5, 0]"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  check_header_json(r.out, true);  // stdout is the JSON object alone
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["overrides"] == nlohmann::json::parse(R"({"camera.position": [0, 0.5, 0]})"));
  REQUIRE(j["rows"].size() == 2);
  CHECK(j["rows"][1]["depth"] == 1);
  CHECK(j["rows"][0]["rays_primary"] == 16 * 12);
  for (const auto& k : kMetricKeys) {
    CHECK(j["rows"][0]["error"].contains(k));
    CHECK(j["rows"][0]["change"].contains(k));
  }
  const Rows rows = parse_csv_strict(clrt_test::slurp(dir / "s.csv"));
  check_header_csv(rows);
  REQUIRE(rows.size() == 3);
  for (const auto& k : kMetricKeys) {
    CHECK_NOTHROW(column(rows, "error_" + k));
    CHECK_NOTHROW(column(rows, "change_" + k));
  }
  CHECK(rows[2][column(rows, "depth")] == "1");
  CHECK(rows[1][column(rows, "device")] == j["rows"][0]["device"].get<std::string>());
}

TEST_CASE("clrt devices --json lists every device with its driver", "[cli][device][output]") {
  auto r = clrt_test::run_clrt({"devices", "--json"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  check_header_json(r.out, true);
  auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["devices"].is_array());
  REQUIRE(!j["devices"].empty());
  int defaults = 0;
  for (const auto& d : j["devices"]) {
    for (const char* k :
         {"index", "platform_device", "name", "type", "driver_version", "compute_units", "global_memory_bytes"})
      CHECK(d.contains(k));
    defaults += d["default"].get<bool>();
  }
  CHECK(defaults == 1);
}

TEST_CASE("clrt compare --json: header first, the metric names, null PSNR for identical images",
          "[cli][compare][opencl][output]") {
  clrt_test::TempDir dir;
  const std::string demo = clrt_test::source_path("scenes/cgfs-demo.json");
  // The reference image compared with itself: infinite PSNR.
  auto render = clrt_test::run_clrt({"render", demo, "--engine", "reference", "--width", "16", "--height", "12",
                                     "--output", dir / clrt_test::image_name("ref")});
  INFO(render.err);
  REQUIRE(render.status == 0);
  auto r = clrt_test::run_clrt({"compare", demo, "--image", dir / clrt_test::image_name("ref"), "--json"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  check_header_json(r.out, false);
  auto j = nlohmann::json::parse(r.out);
  for (const auto& k : kMetricKeys) CHECK(j.contains(k));
  CHECK(j["overrides"] == nlohmann::json::object());  // no -D
  CHECK(j["pixels_differ"] == 0);
  CHECK(j["psnr_8bit_db"].is_null());
  CHECK(j["hit_flip_pixels"].is_null());  // an image file has no hit data
}

}  // namespace test_report_output
